#include "studies/continuation_choices.hpp"
#include <cstdlib>
#include <cstring>

namespace nltopo {

// Starting shape and linear frequency of a branch given by name or mode index.
PetscErrorCode BranchStart(const Lattice &lat, const LinearModes &modes, const char *name, Vec u, PetscReal *omega, std::string *label)
{
  const NamedModes &nm = modes.Named();
  MPI_Comm comm = lat.Comm();
  PetscInt j = -1;
  PetscFunctionBeginUser;
  *label = name;
  if (!std::strcmp(name, "insulated")) {
    PetscCheck(modes.Insulated(), comm, PETSC_ERR_USER, "-cont_branch insulated: this layout has no insulated mode");
    PetscCall(VecCopy(modes.Insulated(), u));
    *omega = nm.insulated_omega;
    PetscFunctionReturn(0);
  }
  if (!std::strcmp(name, "interface")) j = nm.interface;
  else if (!std::strcmp(name, "acoustic_top")) j = nm.acoustic_top;
  else if (!std::strcmp(name, "optical_bottom")) j = nm.optical_bottom;
  else if (!std::strcmp(name, "optical_top")) j = nm.optical_top;
  else {
    const char *s = !std::strncmp(name, "mode", 4) ? name + 4 : name;
    char *end;
    const long k = std::strtol(s, &end, 10);
    PetscCheck(*s && !*end, comm, PETSC_ERR_USER,
               "-cont_branch %s: not one of insulated, interface, acoustic_top, optical_bottom, optical_top, mode<k> or an index", name);
    j = (PetscInt)k;
    *label = "mode" + std::to_string(k);
  }
  PetscCheck(j >= 0 && j < (PetscInt)modes.Omega().size(), comm, PETSC_ERR_USER, "-cont_branch %s: no such linear mode in this lattice", name);
  PetscCall(modes.CopyMode(j, u));
  *omega = modes.Omega()[j];
  PetscFunctionReturn(0);
}

PetscErrorCode ReadStudyChoices(MPI_Comm comm, StudyChoices *c)
{
  PetscBool set;
  PetscFunctionBeginUser;
  PetscOptionsBegin(comm, NULL, "Floquet stability along the branches", NULL);
  PetscCall(PetscOptionsBool("-floquet", "Add Floquet multipliers, Krein signatures and stability to every orbit (-floquet_* options)", NULL, c->floquet,
                             &c->floquet, NULL));
  PetscCall(PetscOptionsBool("-floquet_mf",
                             "With -floquet: only the -floquet_mf_nev leading multiplier pairs (long lattices): from the dense monodromy up to 2N = "
                             "-floquet_mf_dense_max, matrix-free beyond (no stable verdict there)",
                             NULL, c->floquet_mf, &c->floquet_mf, NULL));
  PetscOptionsEnd();
  PetscOptionsBegin(comm, "cont_", "NNM branches", NULL);
  PetscCall(PetscOptionsStringArray("-branch", "Comma-separated branches: insulated, interface, acoustic_top, optical_bottom, optical_top, mode<k> or k", NULL,
                                    c->names, &c->nb, &set));
  PetscCall(PetscOptionsReal("-checkpoint_seconds",
                             "Write -output with the points so far (root attribute complete = 0) at most this often, so that a killed run keeps them "
                             "(0: only at the end)",
                             NULL, c->checkpoint_seconds, &c->checkpoint_seconds, NULL));
  PetscCall(PetscOptionsString("-resume",
                               "Continue the branches of this earlier -output (complete or a checkpoint) from their last points, keeping their "
                               "points; branches it lacks start afresh",
                               NULL, c->resume_file, c->resume_file, sizeof(c->resume_file), &c->resume));
  PetscOptionsEnd();
  PetscCheck(c->checkpoint_seconds >= 0 && c->checkpoint_seconds <= 1e7, comm, PETSC_ERR_USER, "-cont_checkpoint_seconds must lie in [0, 1e7], got %g",
             (double)c->checkpoint_seconds);
  if (!set) {
    PetscCall(PetscStrallocpy("insulated", &c->names[0]));
    c->nb = 1;
  }
  PetscCheck(c->nb >= 1, comm, PETSC_ERR_USER, "-cont_branch needs at least one branch name");
  PetscFunctionReturn(0);
}

} // namespace nltopo
