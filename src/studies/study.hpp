#pragma once
// One study = one class (registry.cpp lists them by -study name). Run() owns
// the lifecycle every study shares: the timer, the log stages (Setup, Solve,
// Write: -log_view shows where the time goes), the output file (a temporary
// renamed at commit, io/output.hpp), its provenance and cost card (written by
// OutputFile::Commit), and the "wrote" line. A study supplies only what is
// its own: the options it reads, Build, Solve and Write.
#include "io/output.hpp"
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
  // The solvers of a forced run (timeint/simulation.hpp): -linear_eps_* (the
  // mode profiles and the amplitude rule) and -sim_ts_*.
  static PetscErrorCode DeclareForcedRunSolvers(MPI_Comm comm);
  // The -output path; a study that resumes its own file says so here.
  virtual PetscErrorCode OutputPath(std::string *path);
  // The bytes the output will take (the free-space check at open).
  virtual double OutputBytes() const { return 0; }
  // The objects of the computation (Setup stage).
  virtual PetscErrorCode Build() = 0;
  // The computation (Solve stage).
  virtual PetscErrorCode Solve() = 0;
  // The datasets (Write stage) into the output's viewer (v NULL when the study writes its own file).
  virtual PetscErrorCode Write(PetscViewer v) = 0;
  // A study whose ranks write and commit the file themselves (the sweep: rank
  // 0 merges the journals) gets no OutputFile.
  virtual bool WritesOwnFile() const { return false; }

  PetscReal Elapsed() const; // wall seconds since Run started
  // What Write gives so far, committed at -output as complete = 0 (a study
  // stopped by a signal keeps its finished part; Run commits complete outputs only).
  PetscErrorCode CommitPartial();
  bool declaring_ = false; // ReadOptions runs for DeclareOptions
  MPI_Comm comm_ = MPI_COMM_NULL;
  const char *name_ = "";
  std::string path_; // -output
  PetscLogDouble t_start_ = 0;
};

using StudyFactory = std::unique_ptr<Study> (*)();

} // namespace nltopo
