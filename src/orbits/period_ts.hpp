#pragma once
// The TS of one period in fixed steps, shared by the periodic-orbit flow
// (orbits/flow.hpp) and its variational flows (orbits/variational.hpp,
// orbits/variational_symplectic.hpp): prefix -nnm_ts_, TSAdapt none (steps
// T / n: the flow is then a smooth function of T), the final time matched, a
// stop signal ending the integration at a step.
#include <petscts.h>

namespace nltopo {

// A TS of `type` (rk: 5dp) on comm with the right-hand side f; the caller adds
// its own pieces, then calls TSSetFromOptions.
PetscErrorCode CreatePeriodTS(MPI_Comm comm, TSType type, TSRHSFunction f, void *ctx, TS *ts);

// y <- y(T) by n steps of T / n; `what` names the integration if it fails.
PetscErrorCode SolvePeriod(TS ts, Vec y, PetscReal T, PetscInt n, const char *what);

} // namespace nltopo
