#pragma once
#include <initializer_list>
// One-line errors for users: the first PETSc error is printed as
//   nltopo: error: <message>
// (by rank 0 of the failing communicator), with no traceback block.
// PETSC_ERR_SIG is a stop signal, not an error (core/signals.hpp): with an
// empty message it is silent, otherwise printed as "nltopo: <message>".
#include <petscsys.h>

namespace nltopo {

PetscErrorCode OneLineErrorHandler(MPI_Comm comm, int line, const char *fun, const char *file, PetscErrorCode n, PetscErrorType p, const char *mess, void *ctx);

// Whether OneLineErrorHandler has printed a stop signal's message (main
// prints a generic one for a study that stopped without saying where).
bool InterruptReported();

// A study that sets some options itself refuses them from the user: one line
// naming the first one given and what sets it instead.
// The output being written (OutputFile::Open sets it): HDF5 failures (disk
// full, the file or its directory removed) are reported as "cannot write -output <path>".
void SetOutputContext(const char *path);

PetscErrorCode RejectGivenOptions(MPI_Comm comm, std::initializer_list<const char *> names, const char *set_by);

// Runs fn() (returning a PetscErrorCode) with PETSc errors returned, not
// printed: *code is its error (0: none) and msg its message. For work one rank
// does alone (its own run, rank 0's file), whose failure FailTogether then
// makes collective.
template <typename Fn> PetscErrorCode CaptureError(Fn &&fn, PetscErrorCode *code, char *msg, size_t len)
{
  PetscFunctionBeginUser;
  PetscCall(PetscPushErrorHandler(PetscReturnErrorHandler, NULL));
  *code = fn();
  PetscCall(PetscPopErrorHandler());
  msg[0] = 0;
  if (*code) {
    const char *text = NULL;
    char *specific = NULL;
    PetscCall(PetscErrorMessage(*code, &text, &specific));
    PetscCall(PetscStrncpy(msg, specific && specific[0] ? specific : (text ? text : "error"), len));
  }
  PetscFunctionReturn(0);
}

// Collective: if any rank of comm has code != 0, every rank fails with the
// code and message of the lowest such rank (printed once, by rank 0).
PetscErrorCode FailTogether(MPI_Comm comm, PetscErrorCode code, const char *msg);

} // namespace nltopo
