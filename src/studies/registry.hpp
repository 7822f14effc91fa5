#pragma once
// Studies registered by name (-study); main.cpp looks the name up and runs it.
#include <petscsys.h>

namespace nltopo {

using StudyFn = PetscErrorCode (*)(MPI_Comm);

struct StudyEntry {
  const char *name, *help;
  StudyFn run;
};

PetscErrorCode LinearStudy(MPI_Comm comm);
PetscErrorCode SimulateStudy(MPI_Comm comm);
PetscErrorCode ContinuationStudy(MPI_Comm comm);
PetscErrorCode StabilityStudy(MPI_Comm comm);
PetscErrorCode SweepStudy(MPI_Comm comm);
PetscErrorCode ZakStudy(MPI_Comm comm);
PetscErrorCode PerturbStudy(MPI_Comm comm);

// Reads -study (default linear) and runs it; an unknown name is an error listing the known ones.
PetscErrorCode RunStudyFromOptions(MPI_Comm comm);

} // namespace nltopo
