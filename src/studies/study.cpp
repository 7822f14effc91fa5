#include "studies/study.hpp"
#include "core/log.hpp"
#include "core/options_audit.hpp"
#include "core/signals.hpp"
#include <cstdlib>
#include <cstring>

namespace nltopo {

PetscErrorCode Study::OutputPath(std::string *path)
{
  PetscFunctionBeginUser;
  PetscCall(OutputPathFromOptions(comm_, name_, path));
  PetscFunctionReturn(0);
}

PetscErrorCode Study::DeclareOptions(MPI_Comm comm, const char *name)
{
  PetscFunctionBeginUser;
  comm_ = comm;
  name_ = name;
  declaring_ = true;
  PetscCall(ReadOptions());
  PetscCall(DeclareSolvers(comm));
  PetscCall(DeclareOutputOptions(comm, name));
  declaring_ = false;
  PetscFunctionReturn(0);
}

PetscReal Study::Elapsed() const
{
  PetscLogDouble now;
  PetscTime(&now);
  return (PetscReal)(now - t_start_);
}

PetscErrorCode Study::CommitPartial()
{
  OutputFile partial;
  PetscFunctionBeginUser;
  PetscCall(partial.Open(comm_, PartialPath(path_), "partial."));
  PetscCall(Write(partial.Viewer()));
  PetscCall(partial.Commit(name_, Elapsed(), false));
  PetscFunctionReturn(0);
}

PetscErrorCode Study::EndInterrupted(const Interruption &it)
{
  const char *sig = SignalName(StopSignalSeen());
  PetscFunctionBeginUser;
  PetscCheck(it.partial, comm_, PETSC_ERR_SIG, "interrupted by %s %s; no output written%s", sig, it.where.c_str(), it.tail.c_str());
  // stdout says it too (issue 34, class 9): the summaries above covered only what was done
  PetscCall(PetscPrintf(comm_, "  partial result: interrupted by %s %s; what was done is written with complete = 0, and nothing is concluded about the rest\n", sig,
                        it.where.c_str()));
  PetscCall(CommitPartial());
  SETERRQ(comm_, PETSC_ERR_SIG, "interrupted by %s %s; partial output %s (complete = 0)%s", sig, it.where.c_str(), PartialPath(path_).c_str(), it.tail.c_str());
}

// NLTOPO_TEST_LATE_ERROR=1 (the tests' hook, docs/errors.md): an error after
// the computation, before the output is written, as an error found at the end
// of a long run would be.
static PetscErrorCode TestLateError(MPI_Comm comm)
{
  PetscFunctionBeginUser;
  const char *e = std::getenv("NLTOPO_TEST_LATE_ERROR");
  PetscCheck(!e || std::strcmp(e, "1"), comm, PETSC_ERR_USER, "NLTOPO_TEST_LATE_ERROR=1: an error after the computation (a test hook)");
  PetscFunctionReturn(0);
}

static int g_setup_stages = 0;

int SetupStagesEntered() { return g_setup_stages; }

PetscErrorCode Study::Run(MPI_Comm comm, const char *name)
{
  PetscFunctionBeginUser;
  comm_ = comm;
  name_ = name;
  PetscCall(PetscTime(&t_start_));
  PetscCall(LogRegister());
  // What the options decide is refused in the Main Stage, before any set-up:
  // their values and combinations, the memory they ask for, the output path.
  PetscCall(ReadOptions());
  PetscCall(CheckResources());
  PetscCall(OutputPathOption(comm, name, &path_));
  PetscCall(claim_.Acquire(comm, path_)); // one run per -output, before anything there is read or written
  const PetscErrorCode ierr = RunClaimed();
  claim_.Release(!ierr ? RunEnd::Complete : IsInterrupt(ierr) ? RunEnd::Interrupted : RunEnd::Failed); // however the run ended
  PetscFunctionReturn(ierr);
}

PetscErrorCode Study::RunClaimed()
{
  OutputFile out;
  PetscFunctionBeginUser;
  PetscCall(OutputPath(&path_));
  claim_.RecordFound(); // again: -output_overwrite may have discarded an earlier partial output
  PetscCall(PetscLogStagePush(Log().setup));
  g_setup_stages++;
  if (!WritesOwnFile()) PetscCall(out.Open(comm_, path_, "", OutputBytes()));
  PetscCall(Build());
  PetscCall(PetscLogStagePop());

  PetscCall(PetscLogStagePush(Log().solve));
  {
    const PetscErrorCode isolve = Solve();
    Interruption it;
    if (IsInterrupt(isolve) && Interrupted(&it)) PetscCall(EndInterrupted(it));
    PetscCall(isolve);
  }
  PetscCall(PetscLogStagePop());

  PetscCall(TestLateError(comm_));
  PetscCall(PetscLogStagePush(Log().write));
  if (WritesOwnFile()) PetscCall(Write(NULL));
  else {
    PetscCall(Write(out.Viewer()));
    PetscCall(out.Commit(name_, Elapsed()));
  }
  PetscCall(PetscLogStagePop());
  if (!WritesOwnFile()) PetscCall(PetscPrintf(comm_, "  wrote %s\n", path_.c_str()));
  PetscFunctionReturn(0);
}

} // namespace nltopo
