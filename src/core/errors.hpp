#pragma once
#include <initializer_list>
// One-line errors for users: the first PETSc error is printed as
//   nltopo: error: <message>
// (by rank 0 of the failing communicator), with no traceback block.
#include <petscsys.h>

namespace nltopo {

PetscErrorCode OneLineErrorHandler(MPI_Comm comm, int line, const char *fun, const char *file, PetscErrorCode n, PetscErrorType p,
                                   const char *mess, void *ctx);

// Checks the command line before PETSc reads it: every "-options_file F" must
// be readable (one line naming it otherwise), and neither the command line,
// those files nor PETSC_OPTIONS may use "-lattice_Gamma", which PETSc's
// case-insensitive options database would silently read as -lattice_gamma.
// Returns false (and prints) on the first problem.
bool PreflightArguments(int argc, char **argv);

// A study that sets some options itself refuses them from the user: one line
// naming the first one given and what sets it instead.
// The output being written (OutputFile::Open sets it): HDF5 failures (disk
// full, the file or its directory removed) are reported as "cannot write -output <path>".
void SetOutputContext(const char *path);

PetscErrorCode RejectGivenOptions(MPI_Comm comm, std::initializer_list<const char *> names, const char *set_by);

} // namespace nltopo
