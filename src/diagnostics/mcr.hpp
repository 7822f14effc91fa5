#pragma once
// Mode concentration ratio (paper eq. for MCR, model.md Diagnostics):
//   MCR = sum u_i^4 / (sum u_i^2)^2   (1/N for a uniform vector, 1 for a single site).
#include <petscvec.h>

namespace nltopo {

// MCR of a distributed vector (collective). Returns 0 for the zero vector.
PetscErrorCode Mcr(Vec u, PetscReal *mcr);

} // namespace nltopo
