#include "core/signals.hpp"
#include <cerrno>
#include <csignal>
#include <cstdarg>
#include <cstdio>
#include <cstring>
#include <vector>

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

bool g_stdout_closed = false; // a write to stdout failed with EPIPE: the reader is gone

// PETSc's printing (PetscPrintf, PetscFPrintf, PetscSynchronizedPrintf all
// end here) with the reader of stdout gone: the text is dropped, not an error.
// Once a write to stdout failed with EPIPE (SIGPIPE is ignored), nothing more
// is written there; the run goes on and commits its output.
PetscErrorCode (*g_petsc_vfprintf)(FILE *, const char[], va_list) = nullptr;

PetscErrorCode DroppingVFPrintf(FILE *fd, const char format[], va_list ap)
{
  if (fd != stdout) return g_petsc_vfprintf(fd, format, ap);
  if (g_stdout_closed) return 0;
  char small[1024];
  std::vector<char> big;
  char *text = small;
  size_t full = 0;
  va_list again;
  va_copy(again, ap);
  PetscErrorCode ierr = PetscVSNPrintf(small, sizeof(small), format, &full, ap); // PETSc's formats (PetscInt_FMT, ...)
  if (!ierr && full > sizeof(small)) {
    big.resize(full);
    text = big.data();
    ierr = PetscVSNPrintf(text, full, format, NULL, again);
  }
  va_end(again);
  if (ierr) return ierr;
  errno = 0;
  if (std::fputs(text, fd) < 0 || std::fflush(fd)) {
    if (errno == EPIPE) g_stdout_closed = true;
    else std::clearerr(fd); // another failure (a full disk under a redirected stdout): the log line is lost, the run goes on
  }
  return 0;
}
} // namespace

void InstallStopSignalHandlers()
{
  struct sigaction sa;
  std::memset(&sa, 0, sizeof(sa));
  sa.sa_handler = StopHandler;
  sigemptyset(&sa.sa_mask);
  sa.sa_flags = SA_RESTART; // system calls (file I/O, MPI progress) resume after the handler
  // (PetscInitialize installed PETSc's handler for SIGHUP, SIGPIPE and
  // SIGTERM, unless -no_signal_handler: a crash banner and MPI_Abort. These
  // replace it; PetscFinalize's PetscPopSignalHandler resets them to the
  // default, after the run.)
  sigaction(SIGINT, &sa, nullptr);
  sigaction(SIGTERM, &sa, nullptr);
  sigaction(SIGHUP, &sa, nullptr); // a closed terminal or session: a stop like SIGTERM
  IgnoreBrokenPipe();
  if (!g_petsc_vfprintf) {
    g_petsc_vfprintf = PetscVFPrintf;
    PetscVFPrintf = DroppingVFPrintf;
  }
}

void IgnoreBrokenPipe() { std::signal(SIGPIPE, SIG_IGN); }

bool StdoutClosed() { return g_stdout_closed; }

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
  if (sig == SIGHUP) return "SIGHUP";
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
