#pragma once
// The integrator seam: what nltopo needs to know of a TS type, one row per
// type. Code that behaves differently by integrator asks the row of its TS
// (TSGetTraits) or of an option's value (TSTraitsFind); nothing else compares
// type names.
//
// Rows: PETSc 3.18's types that integrate nltopo's problems (the first-order
// system z' = f(t, z), z = [u, v], with the state Jacobian for the implicit
// types; basicsymplectic on the split right-hand side) and nltopo's own "rkn"
// and "symsplit", whose rows TSRknRegister and TSSymSplitRegister add
// (timeint/ts_rkn.hpp, timeint/ts_symsplit.hpp).
//
// A type missing from the table is refused, in one line naming the option:
// "-sim_ts_type mprk: not in nltopo's integrator table (rk, rkn, ...)". A
// generic row would have to guess whether the type needs the Jacobian or can
// roll a step back, and a wrong guess fails far from the option.
//
// The table is in core because the cost ledger (core/cost.cpp) and the options
// audit (core/options_audit.cpp) read it; it names PETSc's types and composed
// functions only, so it depends on no later layer.
#include <petscts.h>
#include <string>

namespace nltopo {

struct TSTraits {
  const char *type;   // the TSType name
  const char *family; // the type's own options block, -<prefix>ts_<family>_* ("theta" for cn and beuler); NULL: none
  bool explicit_step; // integrates without the state Jacobian (no SNES)
  bool rolls_back;    // TSRollBack: a TS event can locate a crossing inside a step
  bool fixed_step;    // a fixed-step method: nltopo sets its step (-<prefix>ts_dt), not an error estimate
  bool position_only; // integrates u'' = a(t, u): the forces must not depend on the velocity
  bool acceleration;  // reads the raw-array acceleration of TSSetAcceleration (timeint/ts_acceleration.hpp)
  bool split_rhs;     // integrates the TSRHSSplit functions "position" and "momentum"
  // Order of TSInterpolate's u (its error inside a step goes as h^(order + 1)),
  // the lowest over the type's schemes; 0: some scheme has no interpolant.
  PetscInt interpolant_order;
  // The composed function (TS, const char **) that gives the scheme in use
  // ("TSRKGetType_C", "TSRknGetScheme_C"); NULL: the type has one scheme.
  const char *scheme_getter;
};

// The row of a type, NULL if the table has none.
const TSTraits *TSTraitsFind(const char *type);
// The row of ts's type (set it first: TSSetType or TSSetFromOptions); a type
// the table does not have is an error naming -<prefix>ts_type.
PetscErrorCode TSGetTraits(TS ts, const TSTraits **traits);
// Adds the row of a type nltopo registers with TSRegister (replaces a row of
// the same name).
void TSTraitsRegister(const TSTraits &row);
// The rows in table order.
size_t TSTraitsCount();
const TSTraits &TSTraitsAt(size_t i);
// The list of the table's type names, "rk, rkn, ..." (for messages).
std::string TSTraitsNames();

// The scheme ts runs (its tableau, pair or splitting: "5dp", "dep64"), as the
// type's getter reports it after TSSetFromOptions or the default; "" for a
// type with one scheme.
PetscErrorCode TSGetSchemeName(TS ts, std::string *scheme);
// "<type> <scheme>" (the type alone for a type with one scheme): the
// integrator the cost card records.
PetscErrorCode TSGetIntegratorName(TS ts, std::string *name);

// The TS type an nltopo prefix ("sim_", "nnm_") runs when -<prefix>ts_type is
// not given: the one place that states these defaults (NULL for another prefix).
const char *TSDefaultType(const char *prefix);

} // namespace nltopo
