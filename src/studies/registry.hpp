#pragma once
// Studies registered by name (-study); main.cpp looks the name up and runs it.
// Each study also has an options function that reads every option block of
// its components and declares its solver prefixes (core/options_audit.hpp):
// -help runs only that and exits, and options it does not read are refused.
#include "studies/study.hpp"

namespace nltopo {

using StudyFn = PetscErrorCode (*)(MPI_Comm);

struct StudyEntry {
  const char *name, *help;
  StudyFactory create; // a Study class (studies/study.hpp)
  StudyFn run, options; // not yet a class
};

std::unique_ptr<Study> CreateSimulateStudy();
std::unique_ptr<Study> CreateLinearStudy();
std::unique_ptr<Study> CreateZakStudy();
std::unique_ptr<Study> CreatePerturbStudy();
std::unique_ptr<Study> CreateStabilityStudy();

#define NLTOPO_STUDY(Name) \
  PetscErrorCode Name##Study(MPI_Comm comm); \
  PetscErrorCode Name##StudyOptions(MPI_Comm comm)
NLTOPO_STUDY(Continuation);
NLTOPO_STUDY(Sweep);
NLTOPO_STUDY(Workprecision);
#undef NLTOPO_STUDY

// Reads -study (default linear), checks the options (finite values, no option
// the study does not read), and runs it; with -help it lists the study's
// options and returns without computing. An unknown name is an error listing
// the known ones.
PetscErrorCode RunStudyFromOptions(MPI_Comm comm);

// The end-of-run check of unused options, on the study's communicator (all
// ranks): OutputFile::Commit calls it before a complete output is committed;
// a study whose ranks commit on their own (sweep) calls it itself first.
PetscErrorCode AuditOptionsBeforeCommit(MPI_Comm comm);

} // namespace nltopo
