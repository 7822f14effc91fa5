#pragma once
// The continuation study's own choices (-floquet, -floquet_mf, -cont_branch,
// -cont_checkpoint_seconds, -cont_resume) and the start of a branch named
// in -cont_branch.
#include "bands/linear_modes.hpp"
#include <petscsys.h>
#include <string>

namespace nltopo {

// Starting shape (into u, a site vector) and linear frequency of a branch
// given by name or mode index; label: its output name (mode<k> for k).
PetscErrorCode BranchStart(const Lattice &lat, const LinearModes &modes, const char *name, Vec u, PetscReal *omega, std::string *label);

// The study's own choices: Floquet on/off, the branches, checkpoints, resume.
struct StudyChoices {
  PetscBool floquet = PETSC_FALSE, floquet_mf = PETSC_FALSE;
  char *names[16] = {};
  PetscInt nb = 16;
  PetscReal checkpoint_seconds = 0;
  char resume_file[PETSC_MAX_PATH_LEN] = "";
  PetscBool resume = PETSC_FALSE;
  ~StudyChoices()
  {
    for (char *n : names) PetscFree(n);
  }
};
// (refuses a -cont_branch entry listed twice: "3" and "mode3" are one branch)
PetscErrorCode ReadStudyChoices(MPI_Comm comm, StudyChoices *c);
// Refuses two -cont_branch entries that are the same linear mode, which would
// be computed twice: a named mode (interface, ...) that is also a mode<k>,
// found once the modes are known.
PetscErrorCode CheckDistinctBranches(const Lattice &lat, const LinearModes &modes, const StudyChoices &c);

} // namespace nltopo
