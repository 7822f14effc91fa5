#include "timeint/ts_acceleration.hpp"
#include <petsc/private/tsimpl.h> // PetscUseMethod

namespace nltopo {

namespace {

struct Acceleration {
  AccelerationFn fn = nullptr;
  void *ctx = nullptr;
};

PetscErrorCode DestroyAcceleration(void *p)
{
  delete static_cast<Acceleration *>(p);
  return 0;
}

} // namespace

PetscErrorCode TSSetAcceleration(TS ts, AccelerationFn f, void *ctx)
{
  PetscContainer c;
  PetscFunctionBegin;
  PetscCall(PetscContainerCreate(PetscObjectComm((PetscObject)ts), &c));
  PetscCall(PetscContainerSetPointer(c, new Acceleration{f, ctx}));
  PetscCall(PetscContainerSetUserDestroy(c, DestroyAcceleration));
  PetscCall(PetscObjectCompose((PetscObject)ts, "nltopo_acceleration", (PetscObject)c));
  PetscCall(PetscContainerDestroy(&c));
  PetscFunctionReturn(0);
}

PetscErrorCode TSGetAcceleration(TS ts, AccelerationFn *f, void **ctx)
{
  PetscContainer c;
  PetscFunctionBegin;
  *f = nullptr;
  if (ctx) *ctx = nullptr;
  PetscCall(PetscObjectQuery((PetscObject)ts, "nltopo_acceleration", (PetscObject *)&c));
  if (c) {
    void *p;
    PetscCall(PetscContainerGetPointer(c, &p));
    *f = static_cast<Acceleration *>(p)->fn;
    if (ctx) *ctx = static_cast<Acceleration *>(p)->ctx;
  }
  PetscFunctionReturn(0);
}

PetscErrorCode TSUseSchemeGetter(TS ts, const char *composed, const char **scheme)
{
  PetscFunctionBegin;
  PetscValidHeaderSpecific(ts, TS_CLASSID, 1);
  PetscValidPointer(scheme, 3);
  PetscUseMethod(ts, composed, (TS, const char **), (ts, scheme));
  PetscFunctionReturn(0);
}

PetscErrorCode SecondOrderProblem::Setup(TS ts, const char *type)
{
  PetscInt nloc;
  Vec x;
  const char *prefix;
  PetscFunctionBegin;
  PetscCall(TSGetSolution(ts, &x));
  PetscCall(TSGetOptionsPrefix(ts, &prefix));
  PetscCall(VecGetLocalSize(x, &nloc));
  PetscCheck(nloc % 2 == 0, PetscObjectComm((PetscObject)ts), PETSC_ERR_ARG_SIZ,
             "-%sts_type %s needs a state [u, v] with both halves on every rank (local size %" PetscInt_FMT " is odd)", prefix ? prefix : "", type, nloc);
  n = nloc / 2;
  PetscCall(TSGetAcceleration(ts, &fn, &ctx));
  if (!fn) PetscCall(VecDuplicate(x, &f));
  PetscFunctionReturn(0);
}

PetscErrorCode SecondOrderProblem::Evaluate(TS ts, PetscReal t, Vec z, PetscScalar *a)
{
  PetscFunctionBegin;
  if (fn) {
    PetscCall(fn(ts, t, z, a, ctx));
  } else { // generic problem: the v part of the right-hand side
    const PetscScalar *y;
    PetscCall(TSComputeRHSFunction(ts, t, z, f));
    PetscCall(VecGetArrayRead(f, &y));
    for (PetscInt i = 0; i < n; i++) a[i] = y[n + i];
    PetscCall(VecRestoreArrayRead(f, &y));
  }
  PetscFunctionReturn(0);
}

PetscErrorCode SecondOrderProblem::Reset()
{
  PetscFunctionBegin;
  PetscCall(VecDestroy(&f));
  fn = nullptr;
  ctx = nullptr;
  PetscFunctionReturn(0);
}

PetscErrorCode HermiteInterpolate(Vec z0v, Vec z1v, const PetscScalar *a0, const PetscScalar *a1, PetscInt n, PetscReal h, PetscReal s, Vec X,
                                  bool positions_only)
{
  const PetscScalar *z0, *z1;
  PetscScalar *x;
  PetscFunctionBegin;
  const PetscReal s2 = s * s, s3 = s2 * s, s4 = s3 * s, s5 = s4 * s;
  const PetscReal H0 = 1 - 10 * s3 + 15 * s4 - 6 * s5, H1 = s - 6 * s3 + 8 * s4 - 3 * s5, H2 = 0.5 * (s2 - 3 * s3 + 3 * s4 - s5);
  const PetscReal H3 = 10 * s3 - 15 * s4 + 6 * s5, H4 = -4 * s3 + 7 * s4 - 3 * s5, H5 = 0.5 * (s3 - 2 * s4 + s5);
  const PetscReal D0 = -30 * s2 + 60 * s3 - 30 * s4, D1 = 1 - 18 * s2 + 32 * s3 - 15 * s4, D2 = 0.5 * (2 * s - 9 * s2 + 12 * s3 - 5 * s4);
  const PetscReal D4 = -12 * s2 + 28 * s3 - 15 * s4, D5 = 0.5 * (3 * s2 - 8 * s3 + 5 * s4);
  PetscCheck(X != z0v && X != z1v, PetscObjectComm((PetscObject)X), PETSC_ERR_ARG_IDN,
             "HermiteInterpolate: the output may not be an end state (u and v are written in separate passes)");
  PetscCall(VecGetArrayRead(z0v, &z0));
  PetscCall(VecGetArrayRead(z1v, &z1));
  PetscCall(VecGetArray(X, &x));
  const PetscReal hH1 = h * H1, hH4 = h * H4, h2H2 = h * h * H2, h2H5 = h * h * H5;
  for (PetscInt i = 0; i < n; i++) x[i] = H0 * z0[i] + H3 * z1[i] + hH1 * z0[n + i] + hH4 * z1[n + i] + h2H2 * a0[i] + h2H5 * a1[i];
  if (!positions_only) {
    const PetscReal D0h = D0 / h, hD2 = h * D2, hD5 = h * D5;
    for (PetscInt i = 0; i < n; i++) x[n + i] = D0h * (z0[i] - z1[i]) + D1 * z0[n + i] + D4 * z1[n + i] + hD2 * a0[i] + hD5 * a1[i];
  }
  PetscCall(VecRestoreArray(X, &x));
  PetscCall(VecRestoreArrayRead(z1v, &z1));
  PetscCall(VecRestoreArrayRead(z0v, &z0));
  PetscFunctionReturn(0);
}

} // namespace nltopo
