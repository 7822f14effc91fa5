#include "orbits/period_ts.hpp"
#include "core/cost.hpp"
#include "core/signals.hpp"

namespace nltopo {

PetscErrorCode CreatePeriodTS(MPI_Comm comm, TSType type, TSRHSFunction f, void *ctx, TS *ts)
{
  TSAdapt adapt;
  PetscFunctionBeginUser;
  PetscCall(TSCreate(comm, ts));
  PetscCall(TSSetOptionsPrefix(*ts, "nnm_"));
  PetscCall(TSSetProblemType(*ts, TS_NONLINEAR));
  PetscCall(TSSetType(*ts, type));
  PetscCall(TSRKSetType(*ts, TSRK5DP)); // rk's tableau unless -nnm_ts_rk_type (no-op for other types)
  PetscCall(TSGetAdapt(*ts, &adapt));
  PetscCall(TSAdaptSetType(adapt, TSADAPTNONE));
  PetscCall(TSSetRHSFunction(*ts, NULL, f, ctx));
  PetscCall(TSSetPostStep(*ts, TSInterruptPostStep)); // a stop signal ends the integration at a step
  PetscCall(TSSetExactFinalTime(*ts, TS_EXACTFINALTIME_MATCHSTEP));
  PetscFunctionReturn(0);
}

PetscErrorCode SolvePeriod(TS ts, Vec y, PetscReal T, PetscInt n, const char *what)
{
  TSConvergedReason reason;
  PetscFunctionBeginUser;
  PetscCall(TSSetTime(ts, 0.0));
  PetscCall(TSSetStepNumber(ts, 0));
  PetscCall(TSSetTimeStep(ts, T / n));
  PetscCall(TSSetMaxTime(ts, T));
  PetscCall(TSSetMaxSteps(ts, n));
  PetscCall(TSSolve(ts, y));
  PetscCall(CostRecordSolve(ts, -1));
  PetscCall(TSGetConvergedReason(ts, &reason));
  PetscCheck(reason >= 0, PetscObjectComm((PetscObject)ts), PETSC_ERR_NOT_CONVERGED, "%s integration failed: %s", what, TSConvergedReasons[reason]);
  PetscFunctionReturn(0);
}

} // namespace nltopo
