#include "core/signals.hpp"
#include <csignal>
#include <cstdio>
#include <cstring>

namespace nltopo {

namespace {
volatile std::sig_atomic_t g_signal = 0; // written only by the handler
int g_seen = 0;                          // largest collective value returned

extern "C" void StopHandler(int sig)
{
  if (g_signal) { // the second stop signal: the default action (terminate) at once
    std::signal(sig, SIG_DFL);
    std::raise(sig);
    return;
  }
  g_signal = sig;
}
} // namespace

void InstallStopSignalHandlers()
{
  struct sigaction sa;
  std::memset(&sa, 0, sizeof(sa));
  sa.sa_handler = StopHandler;
  sigemptyset(&sa.sa_mask);
  sa.sa_flags = SA_RESTART; // system calls (file I/O, MPI progress) resume after the handler
  sigaction(SIGINT, &sa, nullptr);
  sigaction(SIGTERM, &sa, nullptr);
}

int StopSignalLocal() { return (int)g_signal; }

int StopSignalSeen() { return g_seen; }

PetscErrorCode InterruptRequested(MPI_Comm comm, int *sig)
{
  PetscMPIInt size;
  int local = (int)g_signal;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_size(comm, &size));
  if (size > 1) PetscCallMPI(MPI_Allreduce(&local, sig, 1, MPI_INT, MPI_MAX, comm));
  else *sig = local;
  if (*sig > g_seen) g_seen = *sig;
  PetscFunctionReturn(0);
}

const char *SignalName(int sig)
{
  static char buf[32];
  if (sig == SIGINT) return "SIGINT";
  if (sig == SIGTERM) return "SIGTERM";
  std::snprintf(buf, sizeof(buf), "signal %d", sig);
  return buf;
}

PetscErrorCode CheckInterrupt(MPI_Comm comm)
{
  int sig;
  PetscFunctionBeginUser;
  PetscCall(InterruptRequested(comm, &sig));
  PetscCheck(!sig, comm, PETSC_ERR_SIG, "%s", ""); // silent: the study that catches it reports
  PetscFunctionReturn(0);
}

PetscErrorCode CheckInterruptAtStep(MPI_Comm comm, PetscInt step)
{
  PetscMPIInt size;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_size(comm, &size));
  if (size == 1 || step % 16 == 0) PetscCall(CheckInterrupt(comm));
  PetscFunctionReturn(0);
}

PetscErrorCode TSInterruptPostStep(TS ts)
{
  PetscInt step;
  PetscFunctionBeginUser;
  PetscCall(TSGetStepNumber(ts, &step));
  PetscCall(CheckInterruptAtStep(PetscObjectComm((PetscObject)ts), step));
  PetscFunctionReturn(0);
}

} // namespace nltopo
