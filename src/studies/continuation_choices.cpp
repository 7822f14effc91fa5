#include "studies/continuation_choices.hpp"
#include "core/option_table.hpp"
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
    PetscCheck(modes.Insulated(), comm, PETSC_ERR_USER, "-cont_branch insulated: no insulated mode: %s", NoInsulatedModeReason(lat.Params()).c_str());
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
    // k counts all N modes: the shift-invert path holds only those near the band edges, whose k-th is another mode
    PetscCheck(modes.Complete(), comm, PETSC_ERR_USER,
               "-cont_branch %s: linear mode indices count all N = %" PetscInt_FMT
               " modes, but N > -linear_dense_max computes only those near the band edges; name the branch (insulated, interface, acoustic_top, "
               "optical_bottom, optical_top) or raise -linear_dense_max to at least N",
               name, lat.N());
  }
  PetscCheck(j >= 0 && j < (PetscInt)modes.Omega().size(), comm, PETSC_ERR_USER, "-cont_branch %s: no such linear mode in this lattice", name);
  PetscCall(modes.CopyMode(j, u));
  *omega = modes.Omega()[j];
  PetscFunctionReturn(0);
}

namespace {
// The output label of a -cont_branch entry as BranchStart gives it: mode<k> for k, mode<k> or mode0<k>; the name otherwise.
std::string BranchLabel(const std::string &name)
{
  const char *s = !std::strncmp(name.c_str(), "mode", 4) ? name.c_str() + 4 : name.c_str();
  char *end;
  const long k = std::strtol(s, &end, 10);
  return *s && !*end ? "mode" + std::to_string(k) : name;
}

struct FloquetChoice {
  PetscBool floquet = PETSC_FALSE, floquet_mf = PETSC_FALSE;
};
struct BranchChoices {
  std::vector<std::string> branch = {"insulated"};
  PetscReal checkpoint_seconds = 0;
  std::string resume; // an earlier -output
};
} // namespace

static const auto &kFloquetChoiceTable = DeclareOptionTable<FloquetChoice>(NULL, "Floquet stability along the branches", [](OptionTable<FloquetChoice> &t) {
  t.Bool("floquet", &FloquetChoice::floquet, "Add Floquet multipliers, Krein signatures and stability to every orbit (-floquet_* options)")
      .Bool("floquet_mf", &FloquetChoice::floquet_mf,
            "With -floquet: only the -floquet_mf_nev leading multiplier pairs (long lattices): from the dense monodromy up to 2N = "
            "-floquet_mf_dense_max, matrix-free beyond (no stable verdict there)");
});

// Which branches a run follows is its extent (a resume may add branches); checkpoints and the resume file are bookkeeping.
static const auto &kBranchChoiceTable = DeclareOptionTable<BranchChoices>("cont_", "NNM branches", [](OptionTable<BranchChoices> &t) {
  t.StringList("branch", &BranchChoices::branch, 16, "Comma-separated branches: insulated, interface, acoustic_top, optical_bottom, optical_top, mode<k> or k",
               OptionClass::Extent)
      .Real("checkpoint_seconds", &BranchChoices::checkpoint_seconds, Closed(0, 1e7),
            "Write <output>.partial.h5 with the points so far (root attribute complete = 0) at most this often, so that a killed run keeps "
            "them (0: only at the end)",
            OptionClass::Bookkeeping)
      .String("resume", &BranchChoices::resume,
              "Continue the branches of this earlier output (complete, or a <output>.partial.h5) from their last points, keeping their "
              "points; branches it lacks start afresh",
              OptionClass::Bookkeeping)
      .Default("none");
});

PetscErrorCode CheckDistinctBranches(const Lattice &lat, const LinearModes &modes, const StudyChoices &c)
{
  const NamedModes &nm = modes.Named();
  std::vector<PetscInt> index(c.nb, -1);
  PetscFunctionBeginUser;
  for (PetscInt k = 0; k < c.nb; k++) {
    const std::string n = c.names[k], label = BranchLabel(n);
    if (n == "interface") index[k] = nm.interface;
    else if (n == "acoustic_top") index[k] = nm.acoustic_top;
    else if (n == "optical_bottom") index[k] = nm.optical_bottom;
    else if (n == "optical_top") index[k] = nm.optical_top;
    else if (label != n || !std::strncmp(n.c_str(), "mode", 4)) index[k] = std::atol(label.c_str() + 4);
    for (PetscInt j = 0; j < k && index[k] >= 0; j++)
      PetscCheck(index[j] != index[k], lat.Comm(), PETSC_ERR_USER,
                 "-cont_branch: %s and %s are the same linear mode (mode%" PetscInt_FMT "); each branch is computed once, list it once", c.names[j], c.names[k],
                 index[k]);
  }
  PetscFunctionReturn(0);
}

PetscErrorCode ReadStudyChoices(MPI_Comm comm, StudyChoices *c)
{
  FloquetChoice f;
  BranchChoices b;
  std::vector<PetscBool> set;
  PetscFunctionBeginUser;
  f.floquet = c->floquet;
  f.floquet_mf = c->floquet_mf;
  PetscCall(kFloquetChoiceTable.Read(comm, &f));
  c->floquet = f.floquet;
  c->floquet_mf = f.floquet_mf;
  b.checkpoint_seconds = c->checkpoint_seconds;
  b.resume = c->resume_file;
  PetscCall(kBranchChoiceTable.Read(comm, &b, &set));
  PetscCheck(!b.branch.empty(), comm, PETSC_ERR_USER, "-cont_branch needs at least one branch name");
  // A branch listed twice would be computed twice (k and mode<k> are one branch; a
  // named mode that is also mode<k> is found once the modes are known: CheckDistinctBranches)
  for (size_t i = 0; i < b.branch.size(); i++)
    for (size_t j = 0; j < i; j++)
      PetscCheck(BranchLabel(b.branch[i]) != BranchLabel(b.branch[j]), comm, PETSC_ERR_USER,
                 "-cont_branch: %s%s%s%s is listed twice; each branch is computed once, list it once", b.branch[j].c_str(),
                 b.branch[i] == b.branch[j] ? "" : " (as ", b.branch[i] == b.branch[j] ? "" : b.branch[i].c_str(), b.branch[i] == b.branch[j] ? "" : " too)");
  c->checkpoint_seconds = b.checkpoint_seconds;
  for (char *&n : c->names) PetscCall(PetscFree(n));
  c->nb = (PetscInt)b.branch.size();
  for (PetscInt k = 0; k < c->nb; k++) PetscCall(PetscStrallocpy(b.branch[k].c_str(), &c->names[k]));
  c->resume = (PetscBool)kBranchChoiceTable.Given(set, "resume");
  PetscCall(PetscStrncpy(c->resume_file, b.resume.c_str(), sizeof(c->resume_file)));
  PetscFunctionReturn(0);
}

} // namespace nltopo
