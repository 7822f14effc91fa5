#include "studies/registry.hpp"
#include <string>

namespace nltopo {

static const StudyEntry kStudies[] = {
  {"linear", "linear modes of K, named modes, Bloch bands and Zak phases", LinearStudy},
  {"simulate", "one forced tone-burst run with energy cut-off", SimulateStudy},
  {"continuation", "NNM branches by shooting and pseudo-arclength continuation", ContinuationStudy},
  {"sweep", "a grid of forced runs (omega_ext x E*) scored by MCR, 0-1 test and energy ratio; parallel, resumable", SweepStudy},
  {"zak", "the half-lattice phase experiment: phi_0, phi_pi and the energy where they stop being distinct", ZakStudy},
  {"perturb", "chiral and achiral spring-perturbation ensembles: insulated frequency and MCR along the insulated NNM", PerturbStudy},
  {"stability", "perturbed insulated-branch NNMs integrated for many periods: does the standing wave persist", StabilityStudy},
};

PetscErrorCode RunStudyFromOptions(MPI_Comm comm)
{
  char name[64] = "linear";
  std::string known, help = "Study to run:";
  PetscFunctionBeginUser;
  for (const auto &s : kStudies) {
    known += std::string(known.empty() ? "" : ", ") + s.name;
    help += std::string(" ") + s.name + " (" + s.help + ");";
  }
  PetscOptionsBegin(comm, NULL, "nltopo", NULL);
  PetscCall(PetscOptionsString("-study", help.c_str(), NULL, name, name, sizeof(name), NULL));
  PetscOptionsEnd();
  for (const auto &s : kStudies) {
    PetscBool match;
    PetscCall(PetscStrcmp(name, s.name, &match));
    if (match) {
      PetscCall(s.run(comm));
      PetscFunctionReturn(0);
    }
  }
  SETERRQ(comm, PETSC_ERR_USER, "unknown -study %s (available: %s)", name, known.c_str());
}

} // namespace nltopo
