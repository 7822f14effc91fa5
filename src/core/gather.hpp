#pragma once
// A distributed vector copied to std::vector: on every rank, or on rank 0 only
// (other ranks get an empty vector). For small vectors (N ~ 10^2..10^4).
#include <petscvec.h>
#include <vector>

namespace nltopo {

PetscErrorCode GatherVec(Vec v, bool to_all, std::vector<PetscReal> *out);

} // namespace nltopo
