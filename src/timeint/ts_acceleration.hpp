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

} // namespace nltopo
