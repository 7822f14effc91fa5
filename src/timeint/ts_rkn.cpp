#include "timeint/ts_rkn.hpp"
#include "timeint/rkn_schemes.hpp"
#include "core/ts_traits.hpp"
#include <petsc/private/tsimpl.h>
#include <algorithm>
#include <cstring>
#include <utility>
#include <vector>

namespace nltopo {

namespace {

using rkn::Pair;
using rkn::Pairs;

// Sites per block of the stage loops: the block of every stage array in L1/L2.
constexpr PetscInt kBlock = 512;

struct Rkn {
  PetscInt pair = 0;
  Vec z_prev = NULL, stage = NULL, emb = NULL; // step start; stage state; embedded solution
  std::vector<std::vector<PetscScalar>> k;     // stage accelerations k[i][site]
  std::vector<PetscScalar> a_end;              // a(t + h, u1) of the last accepted step (pairs without FSAL)
  bool end_ready = false;                      // the end acceleration of the last step is that of the current state
  SecondOrderProblem p;                        // owned positions, the acceleration
  TSStepStatus status = TS_STEP_COMPLETE;
  // per pair: nonzero A_ij of each row (j, A_ij); the four weight sets in one array per stage
  std::vector<std::vector<std::pair<PetscInt, PetscReal>>> rows;
  std::vector<PetscReal> dbar, db; // bbar - bhatbar, b - bhat (the error weights)
  std::vector<PetscInt> weighted;  // the stages Combine reads (e.g. dep86's stage 1 has four zero weights)
  // The weighted 2-norm of (propagated - embedded), computed in Combine's last
  // pass when the tolerances are scalars (else TSErrorWeightedNorm).
  bool fused_norm = false;
  PetscReal wlte2 = -1;
  // A quadrature TS integrated forward (TSCreateQuadratureTS): this step's
  // sum of b_i r(U_i), and the step it was added with (for a rollback).
  Vec qstep = NULL;
  PetscReal qh = 0;

  std::vector<PetscScalar> &End() { return Pairs()[pair].fsal ? k.back() : a_end; }
};

const char *Prefix(TS ts) { return ((PetscObject)ts)->prefix ? ((PetscObject)ts)->prefix : ""; }

PetscErrorCode Accelerate(TS ts, Rkn *d, PetscReal t, Vec z, PetscScalar *a) { return d->p.Evaluate(ts, t, z, a); }

// The quadrature TS's rate r at stage i (state y, positions read), weighted by
// the stage's velocity weight b_i into qstep: as the velocity of P'' = r(u),
// its integral is of the pair's order.
PetscErrorCode QuadratureStage(TS ts, Rkn *d, PetscInt i, PetscReal ti, Vec y)
{
  TS quad = ts->quadraturets;
  const PetscReal b = Pairs()[d->pair].b[i];
  PetscFunctionBegin;
  if (!quad || !ts->costintegralfwd) PetscFunctionReturn(0);
  if (!d->qstep) PetscCall(VecDuplicate(quad->vec_sol, &d->qstep));
  if (i == 0) PetscCall(VecZeroEntries(d->qstep));
  if (b == 0) PetscFunctionReturn(0);
  PetscCall(TSComputeRHSFunction(quad, ti, y, ts->vec_costintegrand));
  PetscCall(VecAXPY(d->qstep, b, ts->vec_costintegrand));
  PetscFunctionReturn(0);
}

// The accepted step's quadrature (TSSolve calls it after each step); a
// rollback takes it back (h = 0).
PetscErrorCode QuadratureAdd(TS ts, Rkn *d, PetscReal h)
{
  PetscFunctionBegin;
  if (!d->qstep || !ts->quadraturets || !ts->costintegralfwd) PetscFunctionReturn(0);
  PetscCall(VecAXPY(ts->quadraturets->vec_sol, h != 0 ? h : -d->qh, d->qstep));
  d->qh = h;
  PetscFunctionReturn(0);
}

PetscErrorCode TSForwardCostIntegral_Rkn(TS ts) { return QuadratureAdd(ts, static_cast<Rkn *>(ts->data), ts->ptime - ts->ptime_prev); }

// The stages 1..s-1 from the step-start state ts->vec_sol and k[0]; false in
// *ok if TSAdaptCheckStage refuses a stage state.
PetscErrorCode Stages(TS ts, Rkn *d, PetscReal t0, PetscReal h, PetscBool *ok)
{
  const Pair &P = Pairs()[d->pair];
  const PetscInt n = d->p.n, s = P.stages;
  const PetscReal h2 = h * h;
  TSAdapt adapt;
  PetscFunctionBegin;
  *ok = PETSC_TRUE;
  PetscCall(TSGetAdapt(ts, &adapt));
  PetscCall(QuadratureStage(ts, d, 0, t0, ts->vec_sol));
  for (PetscInt i = 1; i < s; i++) {
    const PetscReal ch = P.c[i] * h, ti = t0 + P.c[i] * h;
    const PetscInt m = (PetscInt)d->rows[i].size();
    const PetscScalar *z;
    PetscScalar *y;
    PetscCall(TSPreStage(ts, ti));
    PetscCall(VecGetArrayRead(ts->vec_sol, &z));
    PetscCall(VecGetArray(d->stage, &y));
    const PetscScalar *u = z, *v = z + n;
    // y = u + c h v + h^2 sum_j A_ij k_j: one contiguous (vectorised) pass per
    // term over blocks that stay in cache on long lattices
    for (PetscInt q0 = 0; q0 < n; q0 += kBlock) {
      const PetscInt q1 = std::min(n, q0 + kBlock);
      for (PetscInt q = q0; q < q1; q++) y[q] = u[q] + ch * v[q];
      if (!d->p.fn) // the RHS fallback's input: v finite (a(t, u) does not read it)
        for (PetscInt q = q0; q < q1; q++) y[n + q] = v[q];
      // the terms four at a time: y is loaded and stored once per four (the
      // loop is bound by those loads and stores, not by the multiply-adds)
      const auto &row = d->rows[i];
      PetscInt j = 0;
      for (; j + 4 <= m; j += 4) {
        const PetscScalar *k0 = d->k[row[j].first].data(), *k1 = d->k[row[j + 1].first].data(), *k2 = d->k[row[j + 2].first].data(),
                          *k3 = d->k[row[j + 3].first].data();
        const PetscReal w0 = h2 * row[j].second, w1 = h2 * row[j + 1].second, w2 = h2 * row[j + 2].second, w3 = h2 * row[j + 3].second;
        for (PetscInt q = q0; q < q1; q++) y[q] += w0 * k0[q] + w1 * k1[q] + w2 * k2[q] + w3 * k3[q];
      }
      for (; j + 2 <= m; j += 2) {
        const PetscScalar *k0 = d->k[row[j].first].data(), *k1 = d->k[row[j + 1].first].data();
        const PetscReal w0 = h2 * row[j].second, w1 = h2 * row[j + 1].second;
        for (PetscInt q = q0; q < q1; q++) y[q] += w0 * k0[q] + w1 * k1[q];
      }
      for (; j < m; j++) {
        const PetscScalar *kj = d->k[row[j].first].data();
        const PetscReal wj = h2 * row[j].second;
        for (PetscInt q = q0; q < q1; q++) y[q] += wj * kj[q];
      }
    }
    PetscCall(VecRestoreArray(d->stage, &y));
    PetscCall(VecRestoreArrayRead(ts->vec_sol, &z));
    PetscCall(PetscLogFlops((2.0 * m + 4.0) * n));
    PetscCall(TSAdaptCheckStage(adapt, ts, ti, d->stage, ok));
    if (!*ok) PetscFunctionReturn(0);
    PetscCall(Accelerate(ts, d, ti, d->stage, d->k[i].data()));
    PetscCall(QuadratureStage(ts, d, i, ti, d->stage));
  }
  PetscFunctionReturn(0);
}

// ts->vec_sol <- (u1, v1), d->emb <- the embedded solution, d->z_prev <- the
// step start, in one pass.
PetscErrorCode Combine(TS ts, Rkn *d, PetscReal h)
{
  const Pair &P = Pairs()[d->pair];
  const PetscInt n = d->p.n, s = P.stages;
  const PetscReal h2 = h * h;
  PetscScalar *z, *zp, *e;
  PetscFunctionBegin;
  PetscCall(VecGetArray(ts->vec_sol, &z));
  PetscCall(VecGetArray(d->z_prev, &zp));
  PetscCall(VecGetArray(d->emb, &e));
  // Stage by stage into the four sums (zp and e hold them until the end), so
  // every pass is a contiguous, vectorised loop: zp <- sum bbar k, zp+n <- sum
  // b k, e <- sum (bbar - bhatbar) k, e+n <- sum (b - bhat) k.
  for (PetscInt q0 = 0; q0 < n; q0 += kBlock) {
    const PetscInt q1 = std::min(n, q0 + kBlock);
    for (PetscInt q = q0; q < q1; q++) zp[q] = zp[n + q] = e[q] = e[n + q] = 0;
    // stages with a nonzero weight in one of the four sums, two per pass (the
    // four sums are loaded and stored once per two stages)
    const std::vector<PetscInt> &w = d->weighted;
    size_t j = 0;
    for (; j + 2 <= w.size(); j += 2) {
      const PetscInt i0 = w[j], i1 = w[j + 1];
      const PetscScalar *a = d->k[i0].data(), *c = d->k[i1].data();
      const PetscReal wb0 = P.bbar[i0], wv0 = P.b[i0], eb0 = d->dbar[i0], ev0 = d->db[i0];
      const PetscReal wb1 = P.bbar[i1], wv1 = P.b[i1], eb1 = d->dbar[i1], ev1 = d->db[i1];
      for (PetscInt q = q0; q < q1; q++) {
        zp[q] += wb0 * a[q] + wb1 * c[q];
        zp[n + q] += wv0 * a[q] + wv1 * c[q];
        e[q] += eb0 * a[q] + eb1 * c[q];
        e[n + q] += ev0 * a[q] + ev1 * c[q];
      }
    }
    for (; j < w.size(); j++) {
      const PetscInt i = w[j];
      const PetscScalar *a = d->k[i].data();
      const PetscReal wb = P.bbar[i], wv = P.b[i], eb = d->dbar[i], ev = d->db[i];
      for (PetscInt q = q0; q < q1; q++) {
        zp[q] += wb * a[q];
        zp[n + q] += wv * a[q];
        e[q] += eb * a[q];
        e[n + q] += ev * a[q];
      }
    }
  }
  // The error norm as TSErrorWeightedNorm2 (PETSc 3.18) defines it, in the same
  // pass: the mean over the entries with tol > 0 of (|y - yhat| / tol)^2,
  // tol = atol + rtol max(|y|, |yhat|).
  const PetscReal atol = ts->atol, rtol = ts->rtol;
  PetscReal sum = 0, cnt = 0;
  d->fused_norm = !ts->vatol && !ts->vrtol && ts->adapt && ts->adapt->wnormtype == NORM_2 && ts->adapt->ignore_max <= 0;
  for (PetscInt q = 0; q < n; q++) {
    const PetscScalar u = z[q], v = z[n + q], u1 = u + h * v + h2 * zp[q], v1 = v + h * zp[n + q];
    const PetscScalar eu = u1 - h2 * e[q], ev = v1 - h * e[n + q];
    zp[q] = u;
    zp[n + q] = v;
    z[q] = u1;
    z[n + q] = v1;
    e[q] = eu; // read only by TSErrorWeightedNorm (not fused)
    e[n + q] = ev;
    if (d->fused_norm) {
      const PetscReal tu = atol + rtol * std::max(std::abs(u1), std::abs(eu)), tv = atol + rtol * std::max(std::abs(v1), std::abs(ev));
      if (tu > 0) sum += (std::abs(u1 - eu) / tu) * (std::abs(u1 - eu) / tu), cnt += 1;
      if (tv > 0) sum += (std::abs(v1 - ev) / tv) * (std::abs(v1 - ev) / tv), cnt += 1;
    }
  }
  if (d->fused_norm) {
    PetscReal loc[2] = {sum, cnt}, glob[2];
    PetscCall(MPIU_Allreduce(loc, glob, 2, MPIU_REAL, MPIU_SUM, PetscObjectComm((PetscObject)ts)));
    d->wlte2 = glob[1] > 0 ? std::sqrt(glob[0] / glob[1]) : 0;
  }
  PetscCall(VecRestoreArray(d->emb, &e));
  PetscCall(VecRestoreArray(d->z_prev, &zp));
  PetscCall(VecRestoreArray(ts->vec_sol, &z));
  PetscCall(PetscLogFlops((8.0 * s + 8.0) * n));
  PetscFunctionReturn(0);
}

PetscErrorCode TSRollBack_Rkn(TS ts)
{
  Rkn *d = static_cast<Rkn *>(ts->data);
  PetscFunctionBegin;
  PetscCall(VecCopy(d->z_prev, ts->vec_sol));
  PetscCall(QuadratureAdd(ts, d, 0));
  d->end_ready = false;
  PetscFunctionReturn(0);
}

PetscErrorCode TSStep_Rkn(TS ts)
{
  Rkn *d = static_cast<Rkn *>(ts->data);
  const Pair &P = Pairs()[d->pair];
  PetscInt rejections = 0;
  PetscBool accept = PETSC_TRUE;
  TSAdapt adapt;
  PetscFunctionBegin;
  // k[0] = a(t, u): the last step's end acceleration (FSAL / computed after
  // acceptance), unless the state was rolled back or changed (restart).
  if (ts->steprollback || ts->steprestart || !d->end_ready) PetscCall(Accelerate(ts, d, ts->ptime, ts->vec_sol, d->k[0].data()));
  else std::swap(d->k[0], d->End());
  d->end_ready = false;
  d->status = TS_STEP_INCOMPLETE;
  while (!ts->reason && d->status != TS_STEP_COMPLETE) {
    const PetscReal t0 = ts->ptime, h = ts->time_step;
    PetscReal next = h;
    PetscBool ok;
    PetscCall(Stages(ts, d, t0, h, &ok));
    if (ok) {
      PetscCall(Combine(ts, d, h));
      d->status = TS_STEP_PENDING;
      PetscCall(TSGetAdapt(ts, &adapt));
      PetscCall(TSAdaptCandidatesClear(adapt));
      PetscCall(TSAdaptCandidateAdd(adapt, P.label, P.order, 1, 1.0, (PetscReal)(P.fsal ? P.stages - 1 : P.stages), PETSC_TRUE));
      PetscCall(TSAdaptChoose(adapt, ts, h, NULL, &next, &accept));
      if (accept) {
        if (!P.fsal) PetscCall(Accelerate(ts, d, t0 + h, ts->vec_sol, d->a_end.data()));
        d->end_ready = true;
        d->status = TS_STEP_COMPLETE;
        ts->ptime += h;
        ts->time_step = next;
        break;
      }
      PetscCall(VecCopy(d->z_prev, ts->vec_sol)); // the step start again; k[0] still holds its acceleration
      ts->time_step = next;
      d->status = TS_STEP_INCOMPLETE;
    }
    // rejected (error estimate or stage check): retry with the new step
    ts->reject++;
    accept = PETSC_FALSE;
    if (!ts->reason && ++rejections > ts->max_reject && ts->max_reject >= 0) {
      ts->reason = TS_DIVERGED_STEP_REJECTED;
      PetscCall(PetscInfo(ts, "Step %" PetscInt_FMT ": %" PetscInt_FMT " rejections, more than -%sts_max_reject %" PetscInt_FMT "\n", ts->steps, rejections,
                          Prefix(ts), ts->max_reject));
    }
  }
  PetscFunctionReturn(0);
}

// The weighted norm of (propagated - embedded) of the last attempted step; its
// size goes as h^(q+1), q the embedded order.
PetscErrorCode TSEvaluateWLTE_Rkn(TS ts, NormType wnormtype, PetscInt *order, PetscReal *wlte)
{
  Rkn *d = static_cast<Rkn *>(ts->data);
  PetscReal wa, wr;
  PetscFunctionBegin;
  if (d->status != TS_STEP_PENDING && d->status != TS_STEP_COMPLETE) {
    *wlte = -1;
    PetscFunctionReturn(0);
  }
  if (d->fused_norm && wnormtype == NORM_2) *wlte = d->wlte2;
  else PetscCall(TSErrorWeightedNorm(ts, ts->vec_sol, d->emb, wnormtype, wlte, &wa, &wr));
  if (order) *order = Pairs()[d->pair].order_embedded + 1;
  PetscFunctionReturn(0);
}

// Quintic Hermite interpolation on u from (u, v, a) at both ends of the last
// step, v its derivative: exact for polynomials of degree 5 (error O(h^6)).
PetscErrorCode TSInterpolate_Rkn(TS ts, PetscReal t, Vec X)
{
  Rkn *d = static_cast<Rkn *>(ts->data);
  const PetscReal h = ts->ptime - ts->ptime_prev;
  PetscFunctionBegin;
  if (h <= 0 || !d->end_ready) PetscCall(VecCopy(ts->vec_sol, X));
  else PetscCall(HermiteInterpolate(d->z_prev, ts->vec_sol, d->k[0].data(), d->End().data(), d->p.n, h, (t - ts->ptime_prev) / h, X));
  PetscFunctionReturn(0);
}

PetscErrorCode TSReset_Rkn(TS ts)
{
  Rkn *d = static_cast<Rkn *>(ts->data);
  PetscFunctionBegin;
  PetscCall(VecDestroy(&d->z_prev));
  PetscCall(VecDestroy(&d->stage));
  PetscCall(VecDestroy(&d->emb));
  PetscCall(VecDestroy(&d->qstep));
  PetscCall(d->p.Reset());
  d->k.clear();
  d->a_end.clear();
  d->end_ready = false;
  PetscFunctionReturn(0);
}

PetscErrorCode TSSetUp_Rkn(TS ts)
{
  Rkn *d = static_cast<Rkn *>(ts->data);
  const Pair &P = Pairs()[d->pair];
  PetscFunctionBegin;
  PetscCall(TSReset_Rkn(ts));
  PetscCall(d->p.Setup(ts, TSRKN));
  d->k.assign(P.stages, std::vector<PetscScalar>(d->p.n, 0.0));
  d->a_end.assign(P.fsal ? 0 : d->p.n, 0.0);
  d->rows.assign(P.stages, {});
  for (PetscInt i = 0; i < P.stages; i++)
    for (PetscInt j = 0; j < i; j++)
      if (P.A[i * P.stages + j] != 0) d->rows[i].push_back({j, P.A[i * P.stages + j]});
  d->dbar.resize(P.stages);
  d->db.resize(P.stages);
  d->weighted.clear();
  for (PetscInt i = 0; i < P.stages; i++) {
    d->dbar[i] = P.bbar[i] - P.bhatbar[i];
    d->db[i] = P.b[i] - P.bhat[i];
    if (P.bbar[i] != 0 || P.b[i] != 0 || d->dbar[i] != 0 || d->db[i] != 0) d->weighted.push_back(i);
  }
  PetscCall(VecDuplicate(ts->vec_sol, &d->z_prev));
  PetscCall(VecDuplicate(ts->vec_sol, &d->stage));
  PetscCall(VecDuplicate(ts->vec_sol, &d->emb));
  PetscCall(TSGetAdapt(ts, &ts->adapt));
  PetscCall(TSAdaptCandidatesClear(ts->adapt));
  d->status = TS_STEP_COMPLETE;
  PetscFunctionReturn(0);
}

PetscErrorCode TSRknGetScheme_Rkn(TS ts, const char **scheme)
{
  PetscFunctionBegin;
  *scheme = Pairs()[static_cast<Rkn *>(ts->data)->pair].name;
  PetscFunctionReturn(0);
}

PetscErrorCode TSDestroy_Rkn(TS ts)
{
  PetscFunctionBegin;
  PetscCall(TSReset_Rkn(ts));
  PetscCall(PetscObjectComposeFunction((PetscObject)ts, "TSRknGetScheme_C", NULL));
  PetscCall(PetscObjectComposeFunction((PetscObject)ts, "TSForwardQuadratureRollsBack_C", NULL));
  delete static_cast<Rkn *>(ts->data);
  ts->data = NULL;
  PetscFunctionReturn(0);
}

PetscErrorCode TSSetFromOptions_Rkn(TS ts, PetscOptionItems *PetscOptionsObject)
{
  Rkn *d = static_cast<Rkn *>(ts->data);
  std::vector<const char *> names;
  char value[64] = "";
  PetscBool set;
  PetscFunctionBegin;
  for (const Pair &p : Pairs()) names.push_back(p.name);
  PetscOptionsHeadBegin(PetscOptionsObject, "Embedded Runge-Kutta-Nystrom pairs (nltopo)");
  PetscCall(PetscOptionsString("-ts_rkn_scheme", "Pair: dep64 = 6(4), dep86 = 8(6), dep1210 = 12(10) (Dormand, El-Mikkawy & Prince 1987)", "", names[d->pair],
                               value, sizeof(value), &set));
  PetscOptionsHeadEnd();
  if (set) {
    PetscInt found = -1;
    const char *alias[] = {"6(4)", "8(6)", "12(10)"}; // the pairs' orders as names
    for (PetscInt i = 0; i < (PetscInt)names.size(); i++)
      if (!std::strcmp(value, names[i]) || !std::strcmp(value, alias[i])) found = i;
    PetscCheck(found >= 0, PetscObjectComm((PetscObject)ts), PETSC_ERR_USER,
               "-%sts_rkn_scheme %s: unknown pair (dep64 or 6(4), dep86 or 8(6), dep1210 or 12(10))", Prefix(ts), value);
    if (found != d->pair && ts->setupcalled) { // another pair: other work sizes
      PetscCall(TSReset_Rkn(ts));
      ts->setupcalled = PETSC_FALSE;
    }
    d->pair = found;
  }
  PetscFunctionReturn(0);
}

PetscErrorCode TSView_Rkn(TS ts, PetscViewer viewer)
{
  Rkn *d = static_cast<Rkn *>(ts->data);
  const Pair &P = Pairs()[d->pair];
  PetscBool ascii;
  PetscFunctionBegin;
  PetscCall(PetscObjectTypeCompare((PetscObject)viewer, PETSCVIEWERASCII, &ascii));
  if (ascii)
    PetscCall(PetscViewerASCIIPrintf(viewer, "  rkn pair %s (%s): order %d, embedded %d, %d accelerations per accepted step%s\n", P.name, P.label, P.order,
                                     P.order_embedded, P.fsal ? P.stages - 1 : P.stages, P.fsal ? " (FSAL)" : ""));
  PetscFunctionReturn(0);
}

PetscErrorCode TSCreate_Rkn(TS ts)
{
  PetscFunctionBegin;
  ts->data = new Rkn();
  ts->ops->setup = TSSetUp_Rkn;
  ts->ops->step = TSStep_Rkn;
  ts->ops->reset = TSReset_Rkn;
  ts->ops->destroy = TSDestroy_Rkn;
  ts->ops->setfromoptions = TSSetFromOptions_Rkn;
  ts->ops->view = TSView_Rkn;
  ts->ops->interpolate = TSInterpolate_Rkn;
  ts->ops->rollback = TSRollBack_Rkn;
  ts->ops->evaluatewlte = TSEvaluateWLTE_Rkn;
  ts->ops->forwardintegral = TSForwardCostIntegral_Rkn;
  // the forward quadrature TS is integrated and rolled back with the step (PETSc 3.18's rk and theta
  // take back an integral on a rejected attempt that they never added): timeint/simulation.cpp asks
  PetscCall(PetscObjectComposeFunction((PetscObject)ts, "TSForwardQuadratureRollsBack_C", TSForwardCostIntegral_Rkn));
  ts->default_adapt_type = TSADAPTBASIC;
  ts->usessnes = PETSC_FALSE;
  PetscCall(PetscObjectComposeFunction((PetscObject)ts, "TSRknGetScheme_C", TSRknGetScheme_Rkn));
  PetscFunctionReturn(0);
}

} // namespace

PetscErrorCode TSRknGetScheme(TS ts, const char **scheme) { return TSUseSchemeGetter(ts, "TSRknGetScheme_C", scheme); }

PetscErrorCode TSRknRegister()
{
  static bool done = false;
  PetscFunctionBegin;
  if (!done) {
    PetscCall(TSRegister(TSRKN, TSCreate_Rkn));
    // family, explicit, rollback, fixed step, position-only, acceleration, split RHS, interpolant order (quintic Hermite), scheme getter
    TSTraitsRegister({TSRKN, TSRKN, true, true, false, true, true, false, 5, "TSRknGetScheme_C"});
  }
  done = true;
  PetscFunctionReturn(0);
}

PetscInt RknPairCount() { return (PetscInt)Pairs().size(); }

RknPairInfo RknPair(PetscInt i)
{
  const Pair &p = Pairs()[i];
  return {p.name, p.label, p.order, p.order_embedded, p.fsal ? p.stages - 1 : p.stages, p.fsal ? PETSC_TRUE : PETSC_FALSE};
}

} // namespace nltopo
