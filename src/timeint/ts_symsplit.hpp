#pragma once
// TS type "symsplit": fixed-step symmetric symplectic splitting methods for
// second-order systems u'' = a(t, u) written as z = [u, v] (docs/integrators.md). Registered with TSRegister, so -<prefix>ts_type symsplit,
// -ts_dt, -ts_monitor, TSEvent (rollback) and TSInterpolate work as for the
// built-in types; the method is chosen with -<prefix>ts_symsplit_scheme.
//
// Layout: each rank owns [u_local | v_local] of the solution vector (the
// lattice's state layout, lattice/lattice.hpp). The step is kick-drift-...-kick
// (v += b_k h a(t_k, u), u += a_k h v) on raw arrays, one fused loop per stage;
// the last kick's acceleration is the next step's first (FSAL), so a scheme of
// s drifts costs s accelerations per step.
//
// The acceleration comes from TSSetAcceleration (raw array, no Vec calls), or,
// if none was set, from the v part of the TS right-hand side.
#include "timeint/ts_acceleration.hpp" // AccelerationFn, TSSetAcceleration
#include <petscts.h>

namespace nltopo {

#define TSSYMSPLIT "symsplit"

// Registers "symsplit" once (safe to call repeatedly), with its row of the
// integrator table (core/ts_traits.hpp).
PetscErrorCode TSSymSplitRegister();

// The scheme ts runs ("bm4", ... as -ts_symsplit_scheme names it): the default
// or the one TSSetFromOptions chose. Composed on the TS as
// "TSSymSplitGetScheme_C", as PETSc's TSRKGetType; an error for a TS of
// another type.
PetscErrorCode TSSymSplitGetScheme(TS ts, const char **scheme);

// The schemes: name, order, accelerations per step (for tests and benchmarks).
struct SymSplitSchemeInfo {
  const char *name;
  PetscInt order, evals;
};
PetscInt SymSplitSchemeCount();
SymSplitSchemeInfo SymSplitScheme(PetscInt i);

} // namespace nltopo
