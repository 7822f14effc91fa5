#pragma once
// SIGINT, SIGTERM and SIGHUP stop a run at its next safe point (docs/errors.md
// "Signals"); SIGPIPE is ignored (a reader of stdout that went away, e.g.
// `nltopo ... | head`: the run drops what it prints and finishes). The handler only records the signal (a volatile
// sig_atomic_t); the studies poll it where they can stop without losing what
// is done, write that (root attribute complete = 0) and exit non-zero with
//   nltopo: interrupted by SIGTERM at <safe point>; partial output <file> (complete = 0)
// A second signal takes the default action: the process dies at once.
#include <petscts.h>

namespace nltopo {

// Installs the handler for SIGINT, SIGTERM and SIGHUP and ignores SIGPIPE
// (replacing PETSc's handler), and makes PETSc's printing to stdout stop
// quietly once its reader is gone (EPIPE). Call once, after PetscInitialize.
void InstallStopSignalHandlers();
// SIGPIPE ignored: again after PetscFinalize, whose PetscPopSignalHandler resets it.
void IgnoreBrokenPipe();
// Whether a write to stdout failed because its reader is gone.
bool StdoutClosed();

// The stop signal this process received (0: none). Not collective; async-signal safe to read.
int StopSignalLocal();

// The stop signal any rank of comm received (0: none): MPI_Allreduce MAX of the
// local flags (no communication on a one-rank comm). Collective on comm.
PetscErrorCode InterruptRequested(MPI_Comm comm, int *sig);

// The largest signal number any InterruptRequested has returned in this process (0: none).
int StopSignalSeen();

// "SIGINT", "SIGTERM", "SIGHUP" or "signal <n>".
const char *SignalName(int sig);

// Returns the silent error PETSC_ERR_SIG (empty message: OneLineErrorHandler
// prints nothing) when InterruptRequested(comm). Deep inside a computation
// (a time step, a shooting residual) this unwinds to the study, which writes
// what it has and raises the one-line message. Collective on comm.
PetscErrorCode CheckInterrupt(MPI_Comm comm);

// CheckInterrupt inside a time integration, after step number `step`: at every
// step on one rank (a flag read), at every 16th step (the same steps on every
// rank) across ranks. Collective on comm.
PetscErrorCode CheckInterruptAtStep(MPI_Comm comm, PetscInt step);
// The same as a TS post-step (TSSetPostStep): a stop signal ends the integration at a step.
PetscErrorCode TSInterruptPostStep(TS ts);

// Whether ierr is that error: the run was interrupted, not failed.
inline bool IsInterrupt(PetscErrorCode ierr) { return ierr == PETSC_ERR_SIG; }

} // namespace nltopo
