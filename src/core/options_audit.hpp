#pragma once
// The options contract (docs/errors.md "The error contract"):
// - every value that parses as a number must be finite (no nan, inf);
// - an option that no component of the running study reads is an error, with
//   the closest known option as a suggestion ("did you mean -force_omega?");
// - -help lists the study's options and exits without computing.
// A study declares what it reads with an options function (registry.hpp):
// it reads every option block of its components and calls SetFromOptions on a
// throw-away solver object for each solver prefix, so that under -help PETSc
// prints them all and otherwise marks them used.
#include <petscsys.h>
#include <functional>
#include <map>
#include <set>
#include <string>
#include <utility>
#include <vector>

namespace nltopo {

using OptionsFn = std::function<PetscErrorCode(MPI_Comm)>;

// Options as given (name without the dash, value or ""), listed before anything reads them.
using OptionList = std::vector<std::pair<std::string, std::string>>;
PetscErrorCode ListGivenOptions(OptionList *given);

// Throw-away solver objects with a prefix, configured from the options
// database (lists their options under -help, marks them used otherwise).
PetscErrorCode DeclareTS(MPI_Comm comm, const char *prefix);
PetscErrorCode DeclareSNES(MPI_Comm comm, const char *prefix);
PetscErrorCode DeclareEPS(MPI_Comm comm, const char *prefix);

// What -help shows of an option: a flag (PetscOptionsBool, the value may be
// omitted), an integer (PetscOptionsInt: PETSc reads it into a 32-bit int and
// silently wraps larger values), or anything else (needs a value).
enum class OptionKind { Flag, Integer, Other };

// Before a study reads its options: one line for the first of its own options
// given without a value ("-lattice_k" with nothing after it would silently keep
// the default), and for an integer option whose value does not fit an int
// ("-lattice_cells 4294967301" would run 5 cells).
PetscErrorCode CheckOptionValueShapes(MPI_Comm comm, const char *study, OptionsFn options, const OptionList &given);

// One line naming the first option whose value (or a comma-separated item of
// it) parses completely as a non-finite number.
// solvers_only: only options that are not nltopo's own blocks (solver and
// PETSc options, whose own checks name no option), before the study reads
// anything; nltopo's own options are range-checked where they are read.
PetscErrorCode CheckFiniteOptionValues(MPI_Comm comm, const OptionList &given, bool solvers_only);

// The option names each options function would print under -help, without
// printing anything (known[name] = the option names of that study, lower
// case). What they mark used in the database is unmarked after: the run's
// database keeps its marks of what the run itself read.
// kinds (optional): what kind each listed option is.
PetscErrorCode CollectKnownOptions(MPI_Comm comm, const std::map<std::string, OptionsFn> &studies, std::map<std::string, std::set<std::string>> *known,
                                   std::map<std::string, OptionKind> *kinds = nullptr);

// Who reads an option (name without the dash, in any case: PETSc compares
// names case-insensitively, and so does every check here):
// - Petsc: PETSc itself (-log_view, -malloc_debug, -options_left, ...: PetscGlobalOption);
// - Nltopo: an option table's row, or a name under one of nltopo's component
//   prefixes (a misspelt -force_omgea is nltopo's, and unknown to it);
// - Solver: under a solver prefix the running study declared (solver_prefixes:
//   "sim_ts_", "nnm_ksp_", ...), or an option of the objects nltopo creates
//   without a prefix (-vec_*, -mat_*, -dm_*, -sf_*, -vecscatter_*, -is_*):
//   PETSc objects may read them during the run, so they are checked after it;
// - Unknown: anything else (-forc_energy, -ts_type): nothing in the run reads it.
enum class OptionOwner { Petsc, Nltopo, Solver, Unknown };
OptionOwner ClassifyOption(const std::string &name, const std::vector<std::string> &solver_prefixes);
// PETSc's and SLEPc's own options (read at start-up, at the end, or by the
// library itself), name without the dash, any case.
bool PetscGlobalOption(const std::string &name);

// While alive, records the option prefixes of the solver objects declared
// (DeclareTS, DeclareSNES, DeclareEPS), with the classes of the objects each
// creates: "sim_" TS gives "sim_ts_", "sim_snes_", "sim_ksp_", "sim_pc_", "sim_mat_".
class SolverPrefixCapture {
public:
  SolverPrefixCapture();
  ~SolverPrefixCapture();
  SolverPrefixCapture(const SolverPrefixCapture &) = delete;
  SolverPrefixCapture &operator=(const SolverPrefixCapture &) = delete;
  const std::vector<std::string> &Prefixes() const { return prefixes_; }

private:
  std::vector<std::string> prefixes_;
};

// Unused options of the database (set, never queried); each gets one line and
// the run fails on the first problem. early (before any work, after the study
// declared its options): every option except PETSc's own and those under the
// study's solver_prefixes (a type-mismatched -sim_ts_rk_type is refused too);
// otherwise (before the output is committed) every unused option except
// PETSc's own. Reading the values for the lines marks nothing used.
PetscErrorCode AuditUnusedOptions(MPI_Comm comm, const char *study, const std::map<std::string, OptionsFn> &studies, bool early,
                                  const std::vector<std::string> &solver_prefixes = {});

// Closest name by edit distance (Damerau-Levenshtein), "" if none is close.
std::string ClosestOption(const std::string &name, const std::set<std::string> &candidates);

} // namespace nltopo
