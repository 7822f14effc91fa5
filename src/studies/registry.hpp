#pragma once
// Studies registered by name (-study); main.cpp looks the name up and runs it.
// A study is a class (studies/study.hpp): a new one is one file plus one line
// in NLTOPO_STUDIES. Its DeclareOptions (Study's: its ReadOptions reading every
// option block of its components, then its solver prefixes, core/options_audit.hpp):
// -help runs only that and exits, and options it does not read are refused.
#include "studies/study.hpp"

namespace nltopo {

// The studies, one line each: -study name, class (its file defines
// Create<Class>Study), and the help line -help shows.
#define NLTOPO_STUDIES(X) \
  X("linear", Linear, "linear modes of K, named modes, Bloch bands and Zak phases") \
  X("simulate", Simulate, "one forced tone-burst run with energy cut-off") \
  X("continuation", Continuation, "NNM branches by shooting and pseudo-arclength continuation") \
  X("sweep", Sweep, "a grid of forced runs (omega_ext x E*) scored by MCR, 0-1 test and energy ratio; parallel, resumable") \
  X("zak", Zak, "the half-lattice phase experiment: phi_0, phi_pi and the energy where they stop being distinct") \
  X("perturb", Perturb, "chiral and achiral spring-perturbation ensembles: insulated frequency and MCR along the insulated NNM") \
  X("workprecision", Workprecision, "what accuracy costs for one forced run: integrator configurations timed and scored against a converged reference, and the predictability floor") \
  X("stability", Stability, "perturbed insulated-branch NNMs integrated for many periods: does the standing wave persist")

#define NLTOPO_DECLARE_STUDY(name, Class, help) std::unique_ptr<Study> Create##Class##Study();
NLTOPO_STUDIES(NLTOPO_DECLARE_STUDY)
#undef NLTOPO_DECLARE_STUDY

struct StudyEntry {
  const char *name, *help;
  StudyFactory create;
};

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
