#include "timeint/ts_symsplit.hpp"
#include "timeint/symsplit_schemes.hpp"
#include "core/ts_traits.hpp"
#include <petsc/private/tsimpl.h>
#include <cmath>
#include <cstring>
#include <utility>
#include <vector>

namespace nltopo {

namespace {

using symsplit::Scheme;
using symsplit::Schemes;

struct SymSplit {
  PetscInt scheme = 0;
  Vec z_prev = NULL;               // state at the step start
  std::vector<PetscScalar> a0, a1; // acceleration at the step start / end (a1: stages, then the end: FSAL)
  bool fsal = false;               // a1 holds a(t, u) of the current state
  PetscReal h_nominal = 0;         // the fixed step; events and the final time shorten single steps
  SecondOrderProblem p;            // owned positions, the acceleration
};

PetscErrorCode Accelerate(TS ts, SymSplit *d, PetscReal t, Vec z, PetscScalar *a) { return d->p.Evaluate(ts, t, z, a); }

PetscErrorCode TSStep_SymSplit(TS ts)
{
  SymSplit *d = static_cast<SymSplit *>(ts->data);
  const Scheme &s = Schemes()[d->scheme];
  const PetscReal h = ts->time_step, t0 = ts->ptime;
  const PetscInt n = d->p.n, stages = (PetscInt)s.drift.size();
  PetscReal next = h;
  PetscBool accept = PETSC_TRUE;
  PetscFunctionBegin;
  if (ts->steps == 0 && !ts->steprollback) d->h_nominal = h; // the step a solve starts with is the fixed step
  if (ts->steprollback || ts->steprestart || !d->fsal) PetscCall(Accelerate(ts, d, t0, ts->vec_sol, d->a0.data()));
  else std::swap(d->a0, d->a1); // the last step's final acceleration is this one's first
  PetscReal c = 0;              // drift time so far, in units of h
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
  PetscFunctionBegin;
  if (h <= 0) PetscCall(VecCopy(ts->vec_sol, X));
  else PetscCall(HermiteInterpolate(d->z_prev, ts->vec_sol, d->a0.data(), d->a1.data(), d->p.n, h, (t - ts->ptime_prev) / h, X));
  PetscFunctionReturn(0);
}

PetscErrorCode TSSetUp_SymSplit(TS ts)
{
  SymSplit *d = static_cast<SymSplit *>(ts->data);
  PetscBool none;
  PetscFunctionBegin;
  PetscCall(d->p.Setup(ts, TSSYMSPLIT));
  d->a0.assign(d->p.n, 0.0);
  d->a1.assign(d->p.n, 0.0);
  d->fsal = false;
  PetscCall(VecDuplicate(ts->vec_sol, &d->z_prev));
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
  PetscCall(d->p.Reset());
  d->a0.clear();
  d->a1.clear();
  PetscFunctionReturn(0);
}

PetscErrorCode TSSymSplitGetScheme_SymSplit(TS ts, const char **scheme)
{
  PetscFunctionBegin;
  *scheme = Schemes()[static_cast<SymSplit *>(ts->data)->scheme].name;
  PetscFunctionReturn(0);
}

PetscErrorCode TSDestroy_SymSplit(TS ts)
{
  PetscFunctionBegin;
  PetscCall(TSReset_SymSplit(ts));
  PetscCall(PetscObjectComposeFunction((PetscObject)ts, "TSSymSplitGetScheme_C", NULL));
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
  PetscCall(PetscOptionsEList(
      "-ts_symsplit_scheme",
      "Splitting scheme: verlet (order 2); yoshida4, yoshida6, yoshida8 (Yoshida's compositions of Verlet); bm4, bm6 (Blanes-Moan optimised RKN splittings, orders 4 and 6); ss8 (McLachlan's order-8 composition)",
      "", names.data(), (PetscInt)names.size(), names[d->scheme], &d->scheme, NULL));
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
  PetscCall(PetscObjectComposeFunction((PetscObject)ts, "TSSymSplitGetScheme_C", TSSymSplitGetScheme_SymSplit));
  PetscFunctionReturn(0);
}

} // namespace

PetscErrorCode TSSymSplitGetScheme(TS ts, const char **scheme) { return TSUseSchemeGetter(ts, "TSSymSplitGetScheme_C", scheme); }

PetscErrorCode TSSymSplitRegister()
{
  static bool done = false;
  PetscFunctionBegin;
  if (!done) {
    PetscCall(TSRegister(TSSYMSPLIT, TSCreate_SymSplit));
    // family, explicit, rollback, fixed step, position-only, acceleration, split RHS, interpolant order (quintic Hermite), scheme getter
    TSTraitsRegister({TSSYMSPLIT, TSSYMSPLIT, true, true, true, true, true, false, 5, "TSSymSplitGetScheme_C"});
  }
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
