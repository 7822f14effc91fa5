#pragma once
// Studies registered by name (-study); main.cpp looks the name up and runs it.
// A study is a class (studies/study.hpp): a new one is one file plus one line
// in NLTOPO_STUDIES. The file defines Create<Class>Study and
// <Class>StudyContract: the option prefixes two of its runs are compared by
// (io/run_options.hpp) and the schemas of the groups it writes (io/schema.hpp).
// Its DeclareOptions (Study's: its ReadOptions reading every option block of
// its components, then its solver prefixes, core/options_audit.hpp):
// -help runs only that and exits, and options it does not read are refused.
#include "bands/bloch.hpp"
#include "core/options_audit.hpp"
#include "io/schema.hpp"
#include "studies/study.hpp"
#include <initializer_list>
#include <string>
#include <vector>

namespace nltopo {

// The studies, one line each: -study name, class (its file defines
// Create<Class>Study and <Class>StudyContract), its own option prefixes
// (-help lists them first), and the help line -help shows.
#define NLTOPO_STUDIES(X)                                                                                                                                      \
  X("linear", Linear, "-linear_", "linear modes of K, named modes, Bloch bands and Zak phases")                                                                \
  X("simulate", Simulate, "-sim_", "one forced tone-burst run with energy cut-off")                                                                            \
  X("continuation", Continuation, "-cont_ -floquet", "NNM branches by shooting and pseudo-arclength continuation")                                             \
  X("sweep", Sweep, "-sweep_ -kcorr_", "a grid of forced runs (omega_ext x E*) scored by MCR, 0-1 test and energy ratio; parallel, resumable")                 \
  X("zak", Zak, "-zak_", "the half-lattice phase experiment: phi_0, phi_pi and the energy where they stop being distinct")                                     \
  X("perturb", Perturb, "-perturb_", "chiral and achiral spring-perturbation ensembles: insulated frequency and MCR along the insulated NNM")                  \
  X("workprecision", Workprecision, "-wp_",                                                                                                                    \
    "what accuracy costs for one forced run: integrator configurations timed and scored against a converged reference, and the predictability floor")          \
  X("stability", Stability, "-stability_", "perturbed insulated-branch NNMs integrated for many periods: does the standing wave persist")                      \
  X("floquet_scaling", FloquetScaling, "-scaling_",                                                                                                            \
    "one branch at several lattice sizes, dense Floquet: does an instability persist as N grows (envelope ~ N^-p)")                                            \
  X("stabilitymap", StabilityMap, "-smap_",                                                                                                                     \
    "where the NNMs of one branch are stable in (p, E): its events followed as curves in a second parameter, the regions they bound, brute-force checks") \
  X("merge", Merge, "-merge_", "joins the shard files of one sweep (-sweep_shard i/n) into its map")

// What a study adds to the output contract, stated in its own file.
struct StudyContract {
  // Every option prefix of what it reads, its own ("-wp_") and its components'
  // ("-lattice_", ...; ForcedScene::OptionPrefixes, NnmSetup::OptionPrefixes):
  // a resume or an overwrite compares the options under them.
  std::vector<std::string> option_prefixes;
  std::vector<Schema> schemas; // the groups it writes
};

// The prefixes of several parts, each once, in order.
std::vector<std::string> WithPrefixes(std::initializer_list<std::vector<std::string>> parts);

#define NLTOPO_DECLARE_STUDY(name, Class, own, help)                                                                                                           \
  std::unique_ptr<Study> Create##Class##Study();                                                                                                               \
  StudyContract Class##StudyContract();
NLTOPO_STUDIES(NLTOPO_DECLARE_STUDY)
#undef NLTOPO_DECLARE_STUDY

struct StudyEntry {
  const char *name, *own_prefixes, *help; // own_prefixes: space-separated
  StudyFactory create;
};

// Registers every study's option prefixes and schemas (io/run_options.hpp,
// io/schema.hpp); once, however often it is called. RunStudyFromOptions calls
// it first; so must any program that writes or compares outputs without it.
void RegisterStudyContracts();

// The four *_inf attributes of the infinite lattice's band edges (what the
// figure scripts draw), appended to a group's fields, and their writer.
std::vector<Field> WithBandEdges(std::vector<Field> fields);
PetscErrorCode WriteBandEdges(PetscViewer v, const char *group, const BandEdges &be);

// What `nltopo -version` prints: nltopo's version, the libraries it was built
// with, the output format version, the license and how to cite.
std::string VersionText();

// What `nltopo` alone prints: the studies, example commands, where the docs are.
std::string UsageText();

// Each study's options function (its DeclareOptions), by -study name.
std::map<std::string, OptionsFn> StudyOptionFunctions();

// Reads -study, checks the options (finite values, no option the study does
// not read), and runs it; with -help it lists the study's options (linear's
// without -study) and returns without computing. No -study, or an unknown
// one, is an error listing the known ones.
PetscErrorCode RunStudyFromOptions(MPI_Comm comm);

// The end-of-run check of unused options, on the study's communicator (all
// ranks): OutputFile::Commit calls it before a complete output is committed;
// a study whose ranks commit on their own (sweep) calls it itself first.
PetscErrorCode AuditOptionsBeforeCommit(MPI_Comm comm);

} // namespace nltopo
