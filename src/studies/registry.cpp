#include "studies/registry.hpp"
#include "core/option_help.hpp"
#include "core/option_reference.hpp"
#include "core/options_input.hpp"
#include <algorithm>
#include <cstring>
#include <cstdio>
#include <hdf5.h>
#include <slepcversion.h>
#include "timeint/ts_rkn.hpp"
#include "timeint/ts_symsplit.hpp"
#include "core/option_table.hpp"
#include "core/options_audit.hpp"
#include "io/output.hpp"
#include "io/output_reference.hpp"
#include "io/run_options.hpp"
#include <algorithm>
#include <sstream>
#include <string>

namespace nltopo {

#define NLTOPO_STUDY_ENTRY(name, Class, own, help) {name, own, help, Create##Class##Study},
static const StudyEntry kStudies[] = {NLTOPO_STUDIES(NLTOPO_STUDY_ENTRY)};
#undef NLTOPO_STUDY_ENTRY

std::string UsageText()
{
  std::string u = "nltopo: strongly nonlinear topological lattices on PETSc/SLEPc (version " NLTOPO_VERSION ")\n\n"
                  "usage: nltopo -study <name> [options]          one study, options on the command line\n"
                  "       nltopo -options_file options/<scene>.opts [options]   a scene (the options files set -study)\n"
                  "       mpiexec -n 2 nltopo ...                  the same on 2 ranks\n\nstudies:\n";
  for (const auto &s : kStudies) u += std::string("  ") + s.name + std::string(14 - std::min<size_t>(13, std::strlen(s.name)), ' ') + s.help + "\n";
  u += "\nexamples:\n"
       "  nltopo -options_file options/linear.opts                  bands, Zak phase, the insulated mode\n"
       "  nltopo -options_file options/simulate.opts                the paper's forced run at E* = 1\n"
       "  nltopo -options_file options/fep.opts -cont_bifurcations 0   the frequency-energy plot, fast\n"
       "  nltopo -study simulate -help                              the options of a study, and stop\n"
       "  nltopo -study simulate -help petsc                        ... with PETSc's and SLEPc's solver options\n"
       "  nltopo -version                                           version, libraries, license, how to cite\n\n"
       "docs: README.md (quick start, how do I), docs/ (model, one page per study, numerics),\n"
       "      docs/options.md (every option), docs/outputs.md (every output), docs/python.md (reading outputs)\n";
  return u;
}

std::string VersionText()
{
  char v[512];
  std::snprintf(v, sizeof v,
                "nltopo %s\nbuilt with PETSc %d.%d.%d, SLEPc %d.%d.%d, HDF5 %d.%d.%d; output format_version %d\n"
                "license BSD-2-Clause (LICENSE); cite the software and the paper (CITATION.cff)\n",
                NLTOPO_VERSION, PETSC_VERSION_MAJOR, PETSC_VERSION_MINOR, PETSC_VERSION_SUBMINOR, SLEPC_VERSION_MAJOR, SLEPC_VERSION_MINOR,
                SLEPC_VERSION_SUBMINOR, H5_VERS_MAJOR, H5_VERS_MINOR, H5_VERS_RELEASE, (int)kFormatVersion);
  return v;
}

#define NLTOPO_STUDY_CONTRACT(name, Class, own, help) Class##StudyContract,
static StudyContract (*const kContracts[])() = {NLTOPO_STUDIES(NLTOPO_STUDY_CONTRACT)};
#undef NLTOPO_STUDY_CONTRACT

void RegisterStudyContracts()
{
  static bool done = false;
  if (done) return;
  for (size_t i = 0; i < sizeof kContracts / sizeof kContracts[0]; i++) {
    const StudyContract c = kContracts[i]();
    RegisterComponentPrefixes(c.option_prefixes);
    RegisterSchemas(c.schemas, kStudies[i].name);
  }
  done = true;
}

namespace {
using namespace schema_names;
const Field kBandEdges[4] = {{"acoustic_bottom_inf", A, R, "scalar", "rad/time", "infinite lattice: acoustic band bottom (rad/s)"},
                             {"acoustic_top_inf", A, R, "scalar", "rad/time", "infinite lattice: acoustic band top"},
                             {"optical_bottom_inf", A, R, "scalar", "rad/time", "infinite lattice: optical band bottom"},
                             {"optical_top_inf", A, R, "scalar", "rad/time", "infinite lattice: optical band top"}};
} // namespace

std::vector<std::string> WithPrefixes(std::initializer_list<std::vector<std::string>> parts)
{
  std::vector<std::string> all;
  for (const auto &part : parts)
    for (const std::string &p : part)
      if (std::find(all.begin(), all.end(), p) == all.end()) all.push_back(p);
  return all;
}

std::vector<Field> WithBandEdges(std::vector<Field> f)
{
  f.insert(f.end(), std::begin(kBandEdges), std::end(kBandEdges));
  return f;
}

PetscErrorCode WriteBandEdges(PetscViewer v, const char *group, const BandEdges &be)
{
  const PetscReal values[4] = {be.acoustic_bottom, be.acoustic_top, be.optical_bottom, be.optical_top};
  PetscFunctionBeginUser;
  for (int k = 0; k < 4; k++) PetscCall(WriteAttr(v, group, kBandEdges[k].name, values[k]));
  PetscFunctionReturn(0);
}

std::map<std::string, OptionsFn> StudyOptionFunctions()
{
  std::map<std::string, OptionsFn> m;
  for (const auto &s : kStudies) m[s.name] = [&s](MPI_Comm c) { return s.create()->DeclareOptions(c, s.name); };
  return m;
}

static const StudyEntry *g_running = nullptr;
static bool g_audited = false;

PetscErrorCode AuditOptionsBeforeCommit(MPI_Comm comm)
{
  PetscFunctionBeginUser;
  if (!g_running || g_audited) PetscFunctionReturn(0);
  PetscCall(AuditUnusedOptions(comm, g_running->name, StudyOptionFunctions(), false));
  g_audited = true;
  PetscFunctionReturn(0);
}

namespace {
struct StudyOption {
  std::string name = "linear";
  std::string option_tables; // md or json: print the option tables and stop
  std::string output_schema; // md: print the outputs reference and stop
};

// -study: no prefix. Physics: a resume or an overwrite compares the study itself (io/run_options.hpp).
const auto &kStudyTable = DeclareOptionTable<StudyOption>("", "nltopo", [](OptionTable<StudyOption> &t) {
  std::string help = "Study to run:";
  for (const auto &s : kStudies) help += std::string(" ") + s.name + " (" + s.help + ");";
  t.String("study", &StudyOption::name, help.c_str());
  t.String("option_tables", &StudyOption::option_tables,
           "Print every option nltopo declares and stop: md (the options reference, docs/options.md) or json (for tools: "
           "tests/fuzz/fuzz.py)",
           OptionClass::Bookkeeping)
      .Default("(not given: run the study)")
      .String("output_schema", &StudyOption::output_schema,
              "Print every group, dataset and attribute nltopo writes, with type, shape, units and meaning, and stop: md (the outputs "
              "reference, docs/outputs.md)",
              OptionClass::Bookkeeping)
      .Default("(not given: run the study)");
});
} // namespace

PetscErrorCode RunStudyFromOptions(MPI_Comm comm)
{
  StudyOption study;
  std::string known;
  PetscBool list_help;
  PetscFunctionBeginUser;
  PetscCall(CheckOptionsAgree(comm)); // ranks started with different options fail together (core/options_input.hpp)
  RegisterStudyContracts();           // its schemas and compared option prefixes
  PetscCall(TSSymSplitRegister()); // nltopo's TS types, before any -*ts_type is read
  PetscCall(TSRknRegister());
  for (const auto &s : kStudies) known += std::string(known.empty() ? "" : ", ") + s.name;
  std::vector<PetscBool> set;
  PetscCall(kStudyTable.Read(comm, &study, &set));
  PetscCall(PetscOptionsHasHelp(NULL, &list_help)); // -help petsc: PETSc's own listing
  if (OwnHelp()) list_help = PETSC_TRUE;            // -help: nltopo's (core/option_help.hpp)
  if (!study.option_tables.empty()) {
    const bool md = study.option_tables == "md";
    PetscCheck(md || study.option_tables == "json", comm, PETSC_ERR_USER, "-option_tables %s: md or json", study.option_tables.c_str());
    PetscCall(PetscPrintf(comm, "%s", (md ? OptionReferenceMarkdown() : OptionReferenceJson()).c_str()));
    PetscFunctionReturn(0);
  }
  if (!study.output_schema.empty()) {
    PetscCheck(study.output_schema == "md", comm, PETSC_ERR_USER, "-output_schema %s: md", study.output_schema.c_str());
    PetscCall(PetscPrintf(comm, "%s", OutputReferenceMarkdown().c_str()));
    PetscFunctionReturn(0);
  }
  // a run names its study: options without one (a typo in an options file's first line, a forgotten -study) are not a linear run
  PetscCheck(kStudyTable.Given(set, "study") || list_help, comm, PETSC_ERR_USER, "no -study given (one of: %s); nltopo alone prints usage", known.c_str());
  const char *name = study.name.c_str();
  const StudyEntry *entry = nullptr;
  for (const auto &s : kStudies)
    if (study.name == s.name) entry = &s;
  PetscCheck(entry, comm, PETSC_ERR_USER, "unknown -study %s (available: %s)", name, known.c_str());
  OptionList given;
  PetscCall(ListGivenOptions(&given));
  PetscCall(CheckFiniteOptionValues(comm, given, true));                              // nan/inf in solver options, whose own checks do not name them
  PetscCall(CheckOptionValueShapes(comm, name, StudyOptionFunctions()[name], given)); // a missing value, an integer PETSc would wrap
  const OptionsFn options = StudyOptionFunctions()[name];
  if (OwnHelp()) StartHelpCollection();
  std::vector<std::string> solver_prefixes; // what the study's solver objects may read during the run
  {
    SolverPrefixCapture capture;
    PetscCall(options(comm)); // -help: prints them all; otherwise marks them read and checks their ranges
    solver_prefixes = capture.Prefixes();
  }
  PetscCall(CheckFiniteOptionValues(comm, given, false)); // nan/inf that no range check of nltopo's caught
  if (OwnHelp()) {
    std::vector<std::string> own;
    std::istringstream words(entry->own_prefixes);
    for (std::string w; words >> w;) own.push_back(w);
    PetscCall(PetscPrintf(comm, "%s", HelpText(name, own).c_str()));
    PetscFunctionReturn(0);
  }
  if (list_help) {
    PetscCall(PetscPrintf(comm, "nltopo: -help listed the options of -study %s; nothing was computed\n", name));
    PetscFunctionReturn(0);
  }
  g_running = entry;
  // misspelt, foreign and unknown options fail before any work (only the solver objects' wait for the end-of-run audit)
  PetscCall(AuditUnusedOptions(comm, name, StudyOptionFunctions(), true, solver_prefixes));
  PetscCall(SetCommitGuard(AuditOptionsBeforeCommit));
  PetscCall(entry->create()->Run(comm, entry->name));
  PetscFunctionReturn(0);
}

} // namespace nltopo
