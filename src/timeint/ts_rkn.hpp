#pragma once
// TS type "rkn": adaptive embedded Runge-Kutta-Nystrom pairs for second-order
// systems u'' = a(t, u) written as z = [u, v] (docs/integrators.md), next
// to the fixed-step "symsplit" (timeint/ts_symsplit.hpp). Registered with
// TSRegister, so -<prefix>ts_type rkn, -ts_dt (the first step), -ts_rtol,
// -ts_atol, -ts_adapt_type (default basic; dsp, none, ...),
// -ts_adapt_wnormtype, -ts_max_reject, -ts_monitor, TSEvent (rollback) and
// TSInterpolate work as for PETSc's types. The pair is chosen with
// -<prefix>ts_rkn_scheme dep64 | dep86 | dep1210 (Dormand, El-Mikkawy & Prince
// 1987: RKN6(4)6FD, RKN8(6)9, RKN12(10)17M; coefficients in
// timeint/rkn_schemes.hpp), default dep64.
//
// Layout: each rank owns [u_local | v_local] of the solution vector. Stages
// are positions only, U_i = u + c_i h v + h^2 sum_j A_ij a_j, a_i = a(t + c_i h,
// U_i), one fused loop over raw arrays per stage; the solution, the embedded
// solution and the saved step start are written in one more loop. The error
// of the embedded solution (u and v) is weighted by TSErrorWeightedNorm and
// the step chosen by TSAdaptChoose; rejected steps are retried. The pairs
// dep64 and dep86 are FSAL (their last stage is a(t + h, u1)); for dep1210 the
// end acceleration is computed once the step is accepted and is the next
// step's first stage, so every pair hands (u, v, a) at both ends of the step
// to the quintic Hermite interpolant (TSInterpolate) at no extra cost. A
// forward quadrature TS (TSCreateQuadratureTS) is integrated with the pair's
// velocity weights at its stages and rolled back with the step.
//
// The acceleration comes from TSSetAcceleration (timeint/ts_acceleration.hpp),
// or, if none was set, from the v part of the TS right-hand side.
#include "timeint/ts_acceleration.hpp"
#include <petscts.h>

namespace nltopo {

#define TSRKN "rkn"

// Registers "rkn" once (safe to call repeatedly), with its row of the
// integrator table (core/ts_traits.hpp).
PetscErrorCode TSRknRegister();

// The pair ts runs ("dep64", ... as -ts_rkn_scheme names it): the default or
// the one TSSetFromOptions chose. Composed on the TS as "TSRknGetScheme_C", as
// PETSc's TSRKGetType; an error for a TS of another type.
PetscErrorCode TSRknGetScheme(TS ts, const char **scheme);

// The pairs: option name, orders, accelerations per accepted step (for tests
// and benchmarks).
struct RknPairInfo {
  const char *name, *label;
  PetscInt order, order_embedded, evals;
  PetscBool fsal;
};
PetscInt RknPairCount();
RknPairInfo RknPair(PetscInt i);

} // namespace nltopo
