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
// printing anything (known[name] = the option names of that study).
// kinds (optional): what kind each listed option is.
PetscErrorCode CollectKnownOptions(MPI_Comm comm, const std::map<std::string, OptionsFn> &studies, std::map<std::string, std::set<std::string>> *known,
                                   std::map<std::string, OptionKind> *kinds = nullptr);

// Unused options of the database (set, never queried). early: only those the
// options functions are complete for (nltopo's own component prefixes, not the
// solver objects' and PETSc's own), checked before anything is computed;
// otherwise every unused option except PETSc's own, checked before the output
// is committed. Each gets one line; the run fails on the first problem.
PetscErrorCode AuditUnusedOptions(MPI_Comm comm, const char *study, const std::map<std::string, OptionsFn> &studies, bool early);

// Closest name by edit distance (Damerau-Levenshtein), "" if none is close.
std::string ClosestOption(const std::string &name, const std::set<std::string> &candidates);

} // namespace nltopo
