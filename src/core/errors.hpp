#pragma once
// One-line errors for users: the first PETSc error is printed as
//   nltopo: error: <message>
// (by rank 0 of the failing communicator), with no traceback block.
#include <petscsys.h>

namespace nltopo {

PetscErrorCode OneLineErrorHandler(MPI_Comm comm, int line, const char *fun, const char *file, PetscErrorCode n, PetscErrorType p,
                                   const char *mess, void *ctx);

// Checks every "-options_file F" in argv before PETSc reads it, so a missing
// file gives one line naming it. Returns false (and prints) on the first bad one.
bool OptionsFilesReadable(int argc, char **argv);

} // namespace nltopo
