#include "timeint/ts_symsplit.hpp"
#include "timeint/symsplit_schemes.hpp"
#include <petsc/private/tsimpl.h>
#include <cmath>
#include <cstring>
#include <utility>
#include <vector>

namespace nltopo {

namespace {

using symsplit::Scheme;
using symsplit::Schemes;

struct Acceleration {
  AccelerationFn fn = nullptr;
  void *ctx = nullptr;
};

struct SymSplit {
  PetscInt scheme = 0;
  Vec z_prev = NULL, f = NULL;             // state at the step start; RHS work vector (no TSSetAcceleration)
  std::vector<PetscScalar> a0, a1;         // acceleration at the step start / end (a1: stages, then the end: FSAL)
  bool fsal = false;                       // a1 holds a(t, u) of the current state
  PetscReal h_nominal = 0;                 // the fixed step; events and the final time shorten single steps
  PetscInt n = 0;                          // owned positions
  Acceleration acc;
};

PetscErrorCode Accelerate(TS ts, SymSplit *d, PetscReal t, Vec z, PetscScalar *a)
{
  PetscFunctionBegin;
  if (d->acc.fn) {
    PetscCall(d->acc.fn(ts, t, z, a, d->acc.ctx));
  } else { // generic problem: the v part of the right-hand side
    const PetscScalar *f;
    PetscCall(TSComputeRHSFunction(ts, t, z, d->f));
    PetscCall(VecGetArrayRead(d->f, &f));
    for (PetscInt i = 0; i < d->n; i++) a[i] = f[d->n + i];
    PetscCall(VecRestoreArrayRead(d->f, &f));
  }
  PetscFunctionReturn(0);
}

PetscErrorCode TSStep_SymSplit(TS ts)
{
  SymSplit *d = static_cast<SymSplit *>(ts->data);
  const Scheme &s = Schemes()[d->scheme];
  const PetscReal h = ts->time_step, t0 = ts->ptime;
  const PetscInt n = d->n, stages = (PetscInt)s.drift.size();
  PetscReal next = h;
  PetscBool accept = PETSC_TRUE;
  PetscFunctionBegin;
  if (ts->steps == 0 && !ts->steprollback) d->h_nominal = h; // the step a solve starts with is the fixed step
  if (ts->steprollback || ts->steprestart || !d->fsal) PetscCall(Accelerate(ts, d, t0, ts->vec_sol, d->a0.data()));
  else std::swap(d->a0, d->a1); // the last step's final acceleration is this one's first
  PetscReal c = 0;             // drift time so far, in units of h
  for (PetscInt k = 0; k < stages; k++) {
    PetscScalar *z, *zp;
    const PetscScalar *a = k == 0 ? d->a0.data() : d->a1.data();
    const PetscReal bh = s.kick[k] * h, ch = s.drift[k] * h;
    PetscCall(VecGetArray(ts->vec_sol, &z));
    PetscScalar *u = z, *v = z + n;
    if (k == 0) { // keep the start state (rollback, interpolation) in the same pass
      PetscCall(VecGetArray(d->z_prev, &zp));
      for (PetscInt i = 0; i < n; i++) {
        zp[i] = u[i];
        zp[n + i] = v[i];
        v[i] += bh * a[i];
        u[i] += ch * v[i];
      }
      PetscCall(VecRestoreArray(d->z_prev, &zp));
    } else {
      for (PetscInt i = 0; i < n; i++) {
        v[i] += bh * a[i];
        u[i] += ch * v[i];
      }
    }
    PetscCall(VecRestoreArray(ts->vec_sol, &z));
    c += s.drift[k];
    PetscCall(Accelerate(ts, d, k + 1 == stages ? t0 + h : t0 + c * h, ts->vec_sol, d->a1.data()));
  }
  {
    PetscScalar *z;
    const PetscReal bh = s.kick[stages] * h;
    PetscCall(VecGetArray(ts->vec_sol, &z));
    PetscScalar *v = z + n;
    for (PetscInt i = 0; i < n; i++) v[i] += bh * d->a1[i];
    PetscCall(VecRestoreArray(ts->vec_sol, &z));
  }
  d->fsal = true;
  PetscCall(PetscLogFlops(4.0 * n * stages + 2.0 * n));
  // The next step: the fixed one, shortened by TSAdapt to land on the final time.
  PetscCall(TSAdaptChoose(ts->adapt, ts, d->h_nominal > 0 ? d->h_nominal : h, NULL, &next, &accept));
  ts->ptime += h;
  ts->time_step = next;
  PetscFunctionReturn(0);
}

PetscErrorCode TSRollBack_SymSplit(TS ts)
{
  SymSplit *d = static_cast<SymSplit *>(ts->data);
  PetscFunctionBegin;
  PetscCall(VecCopy(d->z_prev, ts->vec_sol));
  d->fsal = false;
  PetscFunctionReturn(0);
}

// Quintic Hermite interpolation on u from (u, v, a) at both ends of the last
// step, v its derivative: exact for polynomials of degree 5 (error O(h^6)).
PetscErrorCode TSInterpolate_SymSplit(TS ts, PetscReal t, Vec X)
{
  SymSplit *d = static_cast<SymSplit *>(ts->data);
  const PetscReal h = ts->ptime - ts->ptime_prev;
  const PetscInt n = d->n;
  const PetscScalar *z0, *z1;
  PetscScalar *x;
  PetscFunctionBegin;
  if (h <= 0) {
    PetscCall(VecCopy(ts->vec_sol, X));
    PetscFunctionReturn(0);
  }
  const PetscReal s = (t - ts->ptime_prev) / h, s2 = s * s, s3 = s2 * s, s4 = s3 * s, s5 = s4 * s;
  const PetscReal H0 = 1 - 10 * s3 + 15 * s4 - 6 * s5, H1 = s - 6 * s3 + 8 * s4 - 3 * s5, H2 = 0.5 * (s2 - 3 * s3 + 3 * s4 - s5);
  const PetscReal H3 = 10 * s3 - 15 * s4 + 6 * s5, H4 = -4 * s3 + 7 * s4 - 3 * s5, H5 = 0.5 * (s3 - 2 * s4 + s5);
  const PetscReal D0 = -30 * s2 + 60 * s3 - 30 * s4, D1 = 1 - 18 * s2 + 32 * s3 - 15 * s4, D2 = 0.5 * (2 * s - 9 * s2 + 12 * s3 - 5 * s4);
  const PetscReal D4 = -12 * s2 + 28 * s3 - 15 * s4, D5 = 0.5 * (3 * s2 - 8 * s3 + 5 * s4);
  PetscCall(VecGetArrayRead(d->z_prev, &z0));
  PetscCall(VecGetArrayRead(ts->vec_sol, &z1));
  PetscCall(VecGetArray(X, &x));
  for (PetscInt i = 0; i < n; i++) {
    const PetscReal u0 = z0[i], v0 = z0[n + i], u1 = z1[i], v1 = z1[n + i], a0 = d->a0[i], a1 = d->a1[i];
    x[i] = H0 * u0 + H3 * u1 + h * (H1 * v0 + H4 * v1) + h * h * (H2 * a0 + H5 * a1);
    x[n + i] = D0 * (u0 - u1) / h + D1 * v0 + D4 * v1 + h * (D2 * a0 + D5 * a1);
  }
  PetscCall(VecRestoreArray(X, &x));
  PetscCall(VecRestoreArrayRead(ts->vec_sol, &z1));
  PetscCall(VecRestoreArrayRead(d->z_prev, &z0));
  PetscFunctionReturn(0);
}

PetscErrorCode TSSetUp_SymSplit(TS ts)
{
  SymSplit *d = static_cast<SymSplit *>(ts->data);
  PetscInt nloc;
  PetscBool none;
  PetscFunctionBegin;
  PetscCall(VecGetLocalSize(ts->vec_sol, &nloc));
  PetscCheck(nloc % 2 == 0, PetscObjectComm((PetscObject)ts), PETSC_ERR_ARG_SIZ,
             "-%sts_type symsplit needs a state [u, v] with both halves on every rank (local size %" PetscInt_FMT " is odd)",
             ((PetscObject)ts)->prefix ? ((PetscObject)ts)->prefix : "", nloc);
  d->n = nloc / 2;
  d->a0.assign(d->n, 0.0);
  d->a1.assign(d->n, 0.0);
  d->fsal = false;
  PetscCall(VecDuplicate(ts->vec_sol, &d->z_prev));
  PetscCall(TSGetAcceleration(ts, &d->acc.fn, &d->acc.ctx));
  if (!d->acc.fn) PetscCall(VecDuplicate(ts->vec_sol, &d->f));
  PetscCall(TSGetAdapt(ts, &ts->adapt));
  PetscCall(PetscObjectTypeCompare((PetscObject)ts->adapt, TSADAPTNONE, &none));
  PetscCheck(none, PetscObjectComm((PetscObject)ts), PETSC_ERR_USER, "-%sts_adapt_type %s: symsplit is a fixed-step method (the step is -%sts_dt)",
             ((PetscObject)ts)->prefix ? ((PetscObject)ts)->prefix : "", ((PetscObject)ts->adapt)->type_name,
             ((PetscObject)ts)->prefix ? ((PetscObject)ts)->prefix : "");
  PetscCall(TSAdaptCandidatesClear(ts->adapt));
  PetscFunctionReturn(0);
}

PetscErrorCode TSReset_SymSplit(TS ts)
{
  SymSplit *d = static_cast<SymSplit *>(ts->data);
  PetscFunctionBegin;
  PetscCall(VecDestroy(&d->z_prev));
  PetscCall(VecDestroy(&d->f));
  d->a0.clear();
  d->a1.clear();
  PetscFunctionReturn(0);
}

PetscErrorCode TSDestroy_SymSplit(TS ts)
{
  PetscFunctionBegin;
  PetscCall(TSReset_SymSplit(ts));
  delete static_cast<SymSplit *>(ts->data);
  ts->data = NULL;
  PetscFunctionReturn(0);
}

PetscErrorCode TSSetFromOptions_SymSplit(TS ts, PetscOptionItems *PetscOptionsObject)
{
  SymSplit *d = static_cast<SymSplit *>(ts->data);
  std::vector<const char *> names;
  PetscFunctionBegin;
  for (const Scheme &s : Schemes()) names.push_back(s.name);
  PetscOptionsHeadBegin(PetscOptionsObject, "Symmetric symplectic splitting (nltopo)");
  PetscCall(PetscOptionsEList("-ts_symsplit_scheme", "Splitting scheme: verlet (order 2); yoshida4, yoshida6, yoshida8 (Yoshida's compositions of Verlet); bm4, bm6 (Blanes-Moan optimised RKN splittings, orders 4 and 6); ss8 (McLachlan's order-8 composition)", "",
                              names.data(), (PetscInt)names.size(), names[d->scheme], &d->scheme, NULL));
  PetscOptionsHeadEnd();
  PetscFunctionReturn(0);
}

PetscErrorCode TSView_SymSplit(TS ts, PetscViewer viewer)
{
  SymSplit *d = static_cast<SymSplit *>(ts->data);
  const Scheme &s = Schemes()[d->scheme];
  PetscBool ascii;
  PetscFunctionBegin;
  PetscCall(PetscObjectTypeCompare((PetscObject)viewer, PETSCVIEWERASCII, &ascii));
  if (ascii)
    PetscCall(PetscViewerASCIIPrintf(viewer, "  symsplit scheme %s: order %" PetscInt_FMT ", %d accelerations per step (%s)\n", s.name, s.order,
                                     (int)s.drift.size(), s.source));
  PetscFunctionReturn(0);
}

PetscErrorCode TSCreate_SymSplit(TS ts)
{
  PetscFunctionBegin;
  SymSplit *d = new SymSplit();
  for (PetscInt i = 0; i < (PetscInt)Schemes().size(); i++)
    if (!std::strcmp(Schemes()[i].name, "bm4")) d->scheme = i; // the cheapest at MCR ~1e-7 (benchmarks/README.md)
  ts->data = d;
  ts->ops->setup = TSSetUp_SymSplit;
  ts->ops->step = TSStep_SymSplit;
  ts->ops->reset = TSReset_SymSplit;
  ts->ops->destroy = TSDestroy_SymSplit;
  ts->ops->setfromoptions = TSSetFromOptions_SymSplit;
  ts->ops->view = TSView_SymSplit;
  ts->ops->interpolate = TSInterpolate_SymSplit;
  ts->ops->rollback = TSRollBack_SymSplit;
  ts->default_adapt_type = TSADAPTNONE;
  ts->usessnes = PETSC_FALSE;
  PetscFunctionReturn(0);
}

} // namespace

PetscErrorCode TSSymSplitRegister()
{
  static bool done = false;
  PetscFunctionBegin;
  if (!done) PetscCall(TSRegister(TSSYMSPLIT, TSCreate_SymSplit));
  done = true;
  PetscFunctionReturn(0);
}

PetscInt SymSplitSchemeCount() { return (PetscInt)Schemes().size(); }

SymSplitSchemeInfo SymSplitScheme(PetscInt i)
{
  const Scheme &s = Schemes()[i];
  return {s.name, s.order, (PetscInt)s.drift.size()};
}

} // namespace nltopo
