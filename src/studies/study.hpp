#pragma once
// One study = one class (registry.cpp lists them by -study name). Run() owns
// the lifecycle every study shares: the timer, the log stages (Setup, Solve,
// Write: -log_view shows where the time goes), the output file (a temporary
// renamed at commit, io/output.hpp), its provenance and cost card (written by
// OutputFile::Commit), the "wrote" line, and a stop signal's end (Solve
// returns the silent interrupt, core/signals.hpp: Run commits what Write gives
// as partial output when Interrupted says there is some, and fails with one
// line). A study supplies only what is its own: the options it reads, Build,
// Solve, Write and what an interruption leaves.
#include "io/output.hpp"
#include "io/output_claim.hpp"
#include <memory>
#include <string>

namespace nltopo {

class Study {
public:
  virtual ~Study() = default;
  // Every option block the study's components read and its solver prefixes
  // (core/options_audit.hpp): -help lists them, options none of them reads are
  // refused. ReadOptions with declaring_ set, then DeclareSolvers and the output options.
  PetscErrorCode DeclareOptions(MPI_Comm comm, const char *name);
  PetscErrorCode Run(MPI_Comm comm, const char *name);

protected:
  // Reads and checks the options, before any output exists. With declaring_
  // (DeclareOptions) it reads every block it may read and does no run-time work
  // (files, memory, computing).
  virtual PetscErrorCode ReadOptions() = 0;
  // The solver prefixes (DeclareTS, DeclareSNES, DeclareEPS), after ReadOptions under DeclareOptions.
  virtual PetscErrorCode DeclareSolvers(MPI_Comm comm) { return 0; }
  // The resource guards that the options decide (the memory of the lattice,
  // of dense matrices and of stored arrays), after ReadOptions and before the
  // Setup stage: a refusal comes before any set-up, as fast at 10^5 cells as
  // at 5. The same guards stay where the objects are allocated.
  virtual PetscErrorCode CheckResources() { return 0; }
  // The -output path; a study that resumes its own file says so here.
  virtual PetscErrorCode OutputPath(std::string *path);
  // The bytes the output will take (the free-space check at open).
  virtual double OutputBytes() const { return 0; }
  // The objects of the computation (Setup stage).
  virtual PetscErrorCode Build() = 0;
  // The computation (Solve stage). A stop signal: it keeps what is done (for
  // Write) and returns the interrupt (IsInterrupt).
  virtual PetscErrorCode Solve() = 0;
  // What an interrupted Solve leaves, for a study that leaves its end to Run
  // (true; false: Solve reports its interruption itself, as continuation's
  // does): whether Write has a partial output to commit (complete = 0), and
  // where the run stopped, for the one line "interrupted by SIGTERM <where>;
  // partial output x.h5.partial.h5 (complete = 0)<tail>" (or "...; no output written<tail>").
  struct Interruption {
    bool partial = false;
    std::string where, tail;
  };
  virtual bool Interrupted(Interruption *it) const { return false; }
  // The datasets (Write stage) into the output's viewer (v NULL when the study writes its own file).
  virtual PetscErrorCode Write(PetscViewer v) = 0;
  // A study whose ranks write and commit the file themselves (the sweep: rank
  // 0 merges the journals) gets no OutputFile.
  virtual bool WritesOwnFile() const { return false; }

  PetscReal Elapsed() const; // wall seconds since Run started
  // What Write gives so far, committed as complete = 0 at <output>.partial.h5
  // (a study stopped by a signal keeps its finished part; -output only ever
  // receives a complete output).
  PetscErrorCode CommitPartial();
  // After an interrupted Solve: the partial output if any, then the one line (always an error).
  PetscErrorCode EndInterrupted(const Interruption &it);
  bool declaring_ = false; // ReadOptions runs for DeclareOptions
  MPI_Comm comm_ = MPI_COMM_NULL;
  const char *name_ = "";
  std::string path_; // -output
  PetscLogDouble t_start_ = 0;

private:
  // Run's steps once -output is claimed.
  PetscErrorCode RunClaimed();
  OutputClaim claim_; // one run per -output (io/output_claim.hpp)
};

using StudyFactory = std::unique_ptr<Study> (*)();

// How many times a study has entered its Setup stage in this process (the
// bad-options tests: a refusal of the options comes before any set-up).
int SetupStagesEntered();

} // namespace nltopo
