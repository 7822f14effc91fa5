#pragma once
// The options contract (README.md "Error contract"):
// - every value that parses as a number must be finite (no nan, inf);
// - an option that no component of the running study reads is an error, with
//   the closest known option as a suggestion ("did you mean -force_omega?");
// - -help lists the study's options and exits without computing.
// A study declares what it reads with an options function (registry.hpp):
// it reads every option block of its components and calls SetFromOptions on a
// throw-away solver object for each solver prefix, so that under -help PETSc
// prints them all and otherwise marks them used.
#include <petscsys.h>
#include <map>
#include <set>
#include <string>

namespace nltopo {

using OptionsFn = PetscErrorCode (*)(MPI_Comm);

// Throw-away solver objects with a prefix, configured from the options
// database (lists their options under -help, marks them used otherwise).
PetscErrorCode DeclareTS(MPI_Comm comm, const char *prefix);
PetscErrorCode DeclareSNES(MPI_Comm comm, const char *prefix);
PetscErrorCode DeclareEPS(MPI_Comm comm, const char *prefix);

// One line naming the first option whose value (or a comma-separated item of
// it) parses completely as a non-finite number.
PetscErrorCode CheckFiniteOptionValues(MPI_Comm comm);

// The option names each options function would print under -help, without
// printing anything (known[name] = the option names of that study).
PetscErrorCode CollectKnownOptions(MPI_Comm comm, const std::map<std::string, OptionsFn> &studies, std::map<std::string, std::set<std::string>> *known);

// Unused options of the database (set, never queried). early: only those the
// options functions are complete for (nltopo's own component prefixes, not the
// solver objects' and PETSc's own), checked before anything is computed;
// otherwise every unused option except PETSc's own, checked before the output
// is committed. Each gets one line; the run fails on the first problem.
PetscErrorCode AuditUnusedOptions(MPI_Comm comm, const char *study, const std::map<std::string, OptionsFn> &studies, bool early);

// Closest name by edit distance (Damerau-Levenshtein), "" if none is close.
std::string ClosestOption(const std::string &name, const std::set<std::string> &candidates);

} // namespace nltopo
