#pragma once
// A grid axis from options, inside the caller's PetscOptionsBegin block (whose
// prefix is <prefix>): -<name>_min/_max/_n/_spacing (linear or log, ends
// included), or an explicit -<name>_list, which replaces them.
#include <petscsys.h>
#include <vector>

namespace nltopo {

PetscErrorCode ReadAxis(PetscOptionItems *PetscOptionsObject, MPI_Comm comm, const char *prefix, const char *name, PetscReal lo, PetscReal hi, PetscInt n,
                        bool log_default, std::vector<PetscReal> *axis);

} // namespace nltopo
