#pragma once
// The raw-array acceleration of a second-order system u'' = a(t, u) with the
// state z = [u_local | v_local] on every rank, shared by nltopo's TS types
// for that class ("symsplit", timeint/ts_symsplit.hpp; "rkn",
// timeint/ts_rkn.hpp). Composed on the TS as "nltopo_acceleration", so it is
// kept across TSSetType.
#include <petscts.h>

namespace nltopo {

// a[i] = acceleration of owned site i (0-based local index) at time t for the
// u part of the state vector z.
using AccelerationFn = PetscErrorCode (*)(TS ts, PetscReal t, Vec z, PetscScalar *a, void *ctx);

// Sets the fast acceleration kernel of ts.
PetscErrorCode TSSetAcceleration(TS ts, AccelerationFn f, void *ctx);
// The kernel set by TSSetAcceleration, or *f = NULL (the types then use the v
// part of the TS right-hand side).
PetscErrorCode TSGetAcceleration(TS ts, AccelerationFn *f, void **ctx);

// The scheme ts runs, from the getter its type composes as `composed`
// ("TSRknGetScheme_C"): PETSc's PetscUseMethod, an error for another type.
PetscErrorCode TSUseSchemeGetter(TS ts, const char *composed, const char **scheme);

// What both types need of the problem: the owned positions n (half the local
// state, checked even) and the acceleration, from TSSetAcceleration or else the
// v part of the TS right-hand side (work vector f).
struct SecondOrderProblem {
  PetscInt n = 0;
  AccelerationFn fn = nullptr;
  void *ctx = nullptr;
  Vec f = NULL;
  PetscErrorCode Setup(TS ts, const char *type); // at TSSetUp: -<prefix>ts_type <type> named in errors
  PetscErrorCode Evaluate(TS ts, PetscReal t, Vec z, PetscScalar *a);
  PetscErrorCode Reset();
};

// The quintic Hermite interpolant at s in [0, 1] of a step of length h from the
// state z0 to z1 (layout [u | v], n owned positions) with accelerations a0, a1
// at its ends: u exact for polynomials of degree 5 (error O(h^6)), v its
// derivative.
// positions_only: X's v part is left as it was (callers that need u alone).
PetscErrorCode HermiteInterpolate(Vec z0, Vec z1, const PetscScalar *a0, const PetscScalar *a1, PetscInt n, PetscReal h, PetscReal s, Vec X,
                                  bool positions_only = false);

} // namespace nltopo
