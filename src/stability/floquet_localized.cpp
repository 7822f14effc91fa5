#include "stability/floquet_localized.hpp"
#include "core/errors.hpp"
#include "core/lapack.hpp"
#include "core/log.hpp"
#include "core/option_table.hpp"
#include "effects/rhs.hpp"
#include "orbits/period_ts.hpp"
#include "timeint/symsplit_schemes.hpp"
#include "timeint/ts_symsplit.hpp"
#include <algorithm>
#include <cmath>
#include <cstring>
#include <numeric>
#include <limits>
#include <sstream>

namespace nltopo {

static const auto &kLocalizedTable = DeclareOptionTable<LocalizedOptions>(
    "floquet_loc_", "Localized Floquet route (-floquet_mf_which localized): the tangent equations damped outside a window around the interface",
    [](OptionTable<LocalizedOptions> &t) {
      t.Int("window", &LocalizedOptions::window, Closed(1, 1000000), "Undamped cells on each side of the interface cell (the localized modes must fit in it)")
          .Int("ramp", &LocalizedOptions::ramp, Closed(1, 1000000),
               "Cells over which the tangent damping rises smoothly (3x^2 - 2x^3) from 0 to -floquet_loc_damping (a sharp step reflects)")
          .Int("pad", &LocalizedOptions::pad, Closed(-1, 1000000), "Cells at the full damping beyond the ramp; -1: to the lattice's ends (no truncation)")
          .Real("damping", &LocalizedOptions::damping, Open(0, 1000), "Damping rate c of the tangent equations beyond the ramp, per unit time")
          .Bool("resolve", &LocalizedOptions::resolve,
                "At every orbit, solve again with the window halved (about half the cost once more): delta, the resolution of the verdict, is at least "
                "the change of the leading |mu|")
          .Bool(
              "check", &LocalizedOptions::check,
              "At every orbit, solve again with the window and the damping halved and doubled and raise delta to the largest change of the leading multiplier "
              "(five times the cost)");
    });

PetscErrorCode LocalizedOptionsFromOptions(MPI_Comm comm, LocalizedOptions *o)
{
  PetscFunctionBeginUser;
  PetscCall(kLocalizedTable.Read(comm, o));
  PetscFunctionReturn(0);
}

// The route's -log_view event (registered on first use).
static PetscErrorCode LocalizedEvent(PetscLogEvent *ev)
{
  static PetscLogEvent e = -1;
  PetscFunctionBeginUser;
  if (e < 0) PetscCall(PetscLogEventRegister("FloquetLocal", Log().classid, &e));
  *ev = e;
  PetscFunctionReturn(0);
}

LocalizedRegion MakeLocalizedRegion(PetscInt N, PetscInt iface, const LocalizedOptions &o)
{
  LocalizedRegion r;
  const PetscInt w = 2 * o.window, ramp = 2 * o.ramp; // in sites
  const PetscInt reach = o.pad < 0 ? N : w + ramp + 2 * o.pad;
  r.iface = iface;
  r.lo = std::max<PetscInt>(0, iface - reach);
  r.hi = std::min<PetscInt>(N - 1, iface + 1 + reach);
  r.c.assign(r.Sites(), 0.0);
  for (PetscInt i = r.lo; i <= r.hi; i++) {
    const PetscInt d = i < iface ? iface - i : (i > iface + 1 ? i - iface - 1 : 0); // sites from the interface cell
    const PetscReal x = std::min<PetscReal>(1, std::max<PetscReal>(0, (PetscReal)(d - w) / ramp));
    r.c[i - r.lo] = o.damping * x * x * (3 - 2 * x);
  }
  return r;
}


namespace {

// ---- the orbit: one integration on the whole lattice recording K_T on the region ----

// The orbit's TS (the flow's type and scheme, -nnm_ts_*) whose acceleration
// also records the tangent stiffness of the region's sites and bonds at every
// evaluation: rec[e * 2n + s] = K_T(lo + s, lo + s), rec[e * 2n + n + s] =
// K_T(lo + s, lo + s + 1), e the evaluation (0 at the start, then one after
// every drift: FSAL).
struct Recorder {
  const EffectList *fx;
  Rhs *rhs;
  const LocalizedRegion *reg;
  std::vector<PetscReal> rec, kd, kb;
  PetscInt evals = 0, capacity = 0;
};

PetscErrorCode RecorderRhs(TS, PetscReal t, Vec z, Vec f, void *ctx)
{
  PetscFunctionBeginUser;
  PetscCall(static_cast<Recorder *>(ctx)->rhs->Evaluate(t, z, f));
  PetscFunctionReturn(0);
}

PetscErrorCode RecorderAcceleration(TS, PetscReal t, Vec z, PetscScalar *a, void *ctx)
{
  Recorder &R = *static_cast<Recorder *>(ctx);
  const Lattice &lat = R.fx->Lat();
  const PetscInt xs = lat.OwnedStart(), xm = lat.OwnedCount(), n = R.reg->Sites(), lo = R.reg->lo, hi = R.reg->hi;
  const PetscScalar *u;
  Vec ul;
  PetscFunctionBeginUser;
  PetscCall(R.rhs->Acceleration(t, z, a));
  PetscCheck(R.evals < R.capacity, lat.Comm(), PETSC_ERR_PLIB, "localized Floquet: more accelerations than the scheme's stages (%" PetscInt_FMT ")",
             R.capacity);
  PetscCall(lat.GetGhostedU(z, &ul, &u));
  R.fx->Stiffness(u, R.kd.data() - xs, R.kb.data() + 1 - xs); // kd by owned site, kb by bond xs-1 .. xs+xm-1
  PetscCall(lat.RestoreGhostedU(z, &ul, &u));
  PetscReal *row = R.rec.data() + (size_t)R.evals * 2 * n;
  for (PetscInt i = std::max(lo, xs); i <= std::min(hi, xs + xm - 1); i++) {
    row[i - lo] = R.kd[i - xs];
    if (i < hi) row[n + i - lo] = R.kb[i - xs + 1]; // bond (i, i + 1), owned with site i
  }
  R.evals++;
  PetscFunctionReturn(0);
}

// K_T of the region at every stage of one period (every rank), and the scheme.
PetscErrorCode RecordStiffness(PeriodicFlow &flow, Vec z0, PetscReal T, const LocalizedRegion &reg, std::vector<PetscReal> *rec, const symsplit::Scheme **sch)
{
  const Lattice &lat = flow.Lat();
  const MPI_Comm comm = lat.Comm();
  Rhs rhs(flow.Effects());
  Recorder R{&flow.Effects(), &rhs, &reg, {}, {}, {}};
  OwnedTS ts;
  OwnedVec z;
  const char *name;
  PetscFunctionBeginUser;
  PetscCheck(flow.Symplectic(), comm, PETSC_ERR_USER,
             "-floquet_mf_which localized integrates the tangent map of the symplectic splitting: it needs -nnm_ts_type symsplit (the default)");
  PetscCall(CreatePeriodTS(comm, TSSYMSPLIT, RecorderRhs, &R, ts.out()));
  PetscCall(TSSetAcceleration(ts, RecorderAcceleration, &R));
  PetscCall(TSSetFromOptions(ts));
  PetscCall(TSSymSplitGetScheme(ts, &name));
  *sch = nullptr;
  for (const auto &s : symsplit::Schemes())
    if (!std::strcmp(s.name, name)) *sch = &s;
  PetscCheck(*sch, comm, PETSC_ERR_PLIB, "localized Floquet: unknown symsplit scheme %s", name);
  const PetscInt n = reg.Sites(), steps = flow.Steps(), stages = (PetscInt)(*sch)->drift.size();
  R.capacity = 1 + steps * stages;
  R.rec.assign((size_t)R.capacity * 2 * n, 0.0);
  R.kd.assign(lat.OwnedCount(), 0.0);
  R.kb.assign(lat.OwnedCount() + 1, 0.0);
  PetscCall(VecDuplicate(z0, z.out()));
  PetscCall(VecCopy(z0, z));
  PetscCall(SolvePeriod(ts, z, T, steps, "localized Floquet orbit"));
  PetscCheck(R.evals == R.capacity, comm, PETSC_ERR_PLIB, "localized Floquet: %" PetscInt_FMT " accelerations, %" PetscInt_FMT " expected", R.evals,
             R.capacity);
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, R.rec.data(), (PetscMPIInt)R.rec.size(), MPIU_REAL, MPI_SUM, comm)); // each entry has one owner
  *rec = std::move(R.rec);
  PetscFunctionReturn(0);
}

// ---- the damped region map, column by column ----

// Columns c0 .. c0+m-1 of the damped region map (unit start vectors in region
// layout), site-major q[s * m + j], p[s * m + j]: the splitting's kicks with
// the recorded K_T, then exp(-c h) on p after every step.
void DampedColumns(const LocalizedRegion &reg, const std::vector<PetscReal> &rec, const symsplit::Scheme &sch, PetscInt steps, PetscReal T, PetscInt c0,
                   PetscInt m, std::vector<PetscReal> *q, std::vector<PetscReal> *p)
{
  const PetscInt n = reg.Sites(), stages = (PetscInt)sch.drift.size();
  const PetscReal h = T / steps;
  q->assign((size_t)n * m, 0.0), p->assign((size_t)n * m, 0.0);
  for (PetscInt j = 0; j < m; j++) {
    const PetscInt c = c0 + j;
    if (c < n) (*q)[(size_t)c * m + j] = 1;
    else (*p)[(size_t)(c - n) * m + j] = 1;
  }
  std::vector<PetscReal> fac(n);
  for (PetscInt s = 0; s < n; s++) fac[s] = std::exp(-reg.c[s] * h);
  PetscReal *Q = q->data(), *P = p->data();
  auto kick = [&](PetscInt e, PetscReal bh) {
    const PetscReal *kd = rec.data() + (size_t)e * 2 * n, *kb = kd + n;
    for (PetscInt s = 0; s < n; s++) {
      const PetscReal l = s > 0 ? kb[s - 1] : 0, d = kd[s], r = s < n - 1 ? kb[s] : 0;
      const PetscReal *Ql = s > 0 ? Q + (s - 1) * m : Q, *Qs = Q + s * m, *Qr = s < n - 1 ? Q + (s + 1) * m : Q;
      PetscReal *Ps = P + s * m;
      for (PetscInt j = 0; j < m; j++) Ps[j] -= bh * (l * Ql[j] + d * Qs[j] + r * Qr[j]);
    }
  };
  for (PetscInt st = 0; st < steps; st++) {
    for (PetscInt k = 0; k < stages; k++) {
      kick(st * stages + k, sch.kick[k] * h);
      const PetscReal ch = sch.drift[k] * h;
      for (size_t x = 0; x < q->size(); x++) Q[x] += ch * P[x];
    }
    kick((st + 1) * stages, sch.kick[stages] * h);
    for (PetscInt s = 0; s < n; s++)
      if (fac[s] != 1)
        for (PetscInt j = 0; j < m; j++) P[s * m + j] *= fac[s];
  }
}

} // namespace

PetscErrorCode LocalizedMonodromy(PeriodicFlow &flow, Vec z0, PetscReal T, PetscReal, const LocalizedRegion &reg, std::vector<PetscReal> *a,
                                  std::vector<PetscReal> *f)
{
  const Lattice &lat = flow.Lat();
  const MPI_Comm comm = lat.Comm();
  const PetscInt n = reg.Sites(), n2 = 2 * n;
  PetscMPIInt rank, size;
  std::vector<PetscReal> rec, q, p;
  const symsplit::Scheme *sch;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCallMPI(MPI_Comm_size(comm, &size));
  // beta: the multipliers are those of the free flow (beta = 0), as FloquetBeta takes them on the symplectic route
  PetscCall(RecordStiffness(flow, z0, T, reg, &rec, &sch));
  const PetscInt c0 = n2 * rank / size, c1 = n2 * (rank + 1) / size, m = c1 - c0;
  DampedColumns(reg, rec, *sch, flow.Steps(), T, c0, m, &q, &p);
  PetscCall(PetscLogFlops(10.0 * n * m * flow.Steps() * (sch->drift.size() + 1)));
  std::vector<PetscReal> mine((size_t)n2 * m); // column-major block
  for (PetscInt j = 0; j < m; j++)
    for (PetscInt s = 0; s < n; s++) mine[(size_t)j * n2 + s] = q[(size_t)s * m + j], mine[(size_t)j * n2 + n + s] = p[(size_t)s * m + j];
  std::vector<int> counts(size), displs(size);
  for (PetscMPIInt r = 0; r < size; r++) counts[r] = (int)(n2 * (n2 * (r + 1) / size - n2 * r / size)), displs[r] = (int)(n2 * (n2 * r / size));
  a->assign(rank == 0 ? (size_t)n2 * n2 : 0, 0.0);
  PetscCallMPI(MPI_Gatherv(mine.data(), (int)mine.size(), MPIU_REAL, a->data(), counts.data(), displs.data(), MPIU_REAL, 0, comm));
  // f(z0) on the region, every rank
  OwnedVec fz;
  const PetscScalar *fa;
  const PetscInt xs = lat.OwnedStart(), xm = lat.OwnedCount();
  PetscCall(VecDuplicate(z0, fz.out()));
  PetscCall(flow.Field(z0, fz));
  f->assign(n2, 0.0);
  PetscCall(VecGetArrayRead(fz, &fa));
  for (PetscInt i = std::max(reg.lo, xs); i <= std::min(reg.hi, xs + xm - 1); i++) (*f)[i - reg.lo] = fa[i - xs], (*f)[n + i - reg.lo] = fa[xm + i - xs];
  PetscCall(VecRestoreArrayRead(fz, &fa));
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, f->data(), (PetscMPIInt)n2, MPIU_REAL, MPI_SUM, comm));
  PetscFunctionReturn(0);
}

namespace {

// Eigenvectors of the selected eigenvalues (sel: indices into wr/wi with wi >=
// 0) of the Hessenberg form h (a, tau: its reflectors): cols[k] = the
// eigenvector of sel[k], [re | im] (im zero for a real one), 2 x n2 values.
PetscErrorCode SelectedVectors(int n, const PetscReal *a, const std::vector<PetscReal> &tau, const std::vector<PetscReal> &h, const std::vector<PetscReal> &wr,
                               const std::vector<PetscReal> &wi, const std::vector<int> &sel, std::vector<std::vector<PetscReal>> *cols)
{
  const int one = 1;
  int info = 0, lwork = -1, cnt = 0, got = 0;
  PetscReal wq;
  PetscFunctionBeginUser;
  cols->clear();
  if (sel.empty()) PetscFunctionReturn(0);
  std::vector<int> select(n, 0), first(n, -1);
  for (int i : sel) select[i] = 1;
  for (int i = 0; i < n; i++)
    if (select[i]) first[i] = cnt, cnt += wi[i] != 0 ? 2 : 1;
  std::vector<PetscReal> vr((size_t)n * cnt), hw((size_t)(n + 2) * n), wr2 = wr;
  std::vector<int> ifl(cnt), ifr(cnt);
  dhsein_("R", "Q", "N", select.data(), &n, h.data(), &n, wr2.data(), wi.data(), NULL, &one, vr.data(), &n, &cnt, &got, hw.data(), ifl.data(), ifr.data(),
          &info, 1, 1, 1);
  PetscCheck(info >= 0 && got == cnt, PETSC_COMM_SELF, PETSC_ERR_LIB, "localized Floquet: LAPACK dhsein failed, info %d (2n = %d)", info, n);
  dormhr_("L", "N", &n, &cnt, &one, &n, a, &n, tau.data(), vr.data(), &n, &wq, &lwork, &info, 1, 1);
  std::vector<PetscReal> work((size_t)wq + 1);
  lwork = (int)work.size();
  dormhr_("L", "N", &n, &cnt, &one, &n, a, &n, tau.data(), vr.data(), &n, work.data(), &lwork, &info, 1, 1);
  PetscCheck(info == 0, PETSC_COMM_SELF, PETSC_ERR_LIB, "localized Floquet: LAPACK dormhr failed, info %d", info);
  for (int i : sel) {
    std::vector<PetscReal> v(2 * (size_t)n, 0.0);
    const PetscReal *x = &vr[(size_t)first[i] * n];
    std::copy(x, x + n, v.begin());
    if (wi[i] != 0) std::copy(x + n, x + 2 * n, v.begin() + n);
    cols->push_back(std::move(v));
  }
  PetscFunctionReturn(0);
}

// |<v, f>| / (|v| |f|) for v = [re | im] (2 x n2) and real f (n2).
PetscReal Alignment(const std::vector<PetscReal> &v, const std::vector<PetscReal> &f)
{
  const size_t n2 = f.size();
  PetscReal dr = 0, di = 0, nv = 0, nf = 0;
  for (size_t k = 0; k < n2; k++) dr += v[k] * f[k], di += v[n2 + k] * f[k], nv += v[k] * v[k] + v[n2 + k] * v[n2 + k], nf += f[k] * f[k];
  return nv > 0 && nf > 0 ? std::hypot(dr, di) / std::sqrt(nv * nf) : 0;
}

// Edge share, window share and Krein value of v = [re | im] in region layout.
void VectorShares(const std::vector<PetscReal> &v, const LocalizedRegion &reg, const FloquetOptions &fo, PetscReal *edge, PetscReal *inside, PetscReal *kappa)
{
  const PetscInt n = reg.Sites(), n2 = 2 * n;
  PetscReal disp = 0, near = 0, win = 0, sums[2];
  for (PetscInt s = 0; s < n; s++) {
    const PetscReal d = v[s] * v[s] + v[n2 + s] * v[n2 + s];
    disp += d;
    if (InEdgeRegion(reg.lo + s, reg.iface, fo.edge_sites)) near += d;
    if (reg.InWindow(s)) win += d;
  }
  KreinSums(v.data(), v.data() + n2, n, sums);
  *edge = disp > 0 ? near / disp : 0;
  *inside = disp > 0 ? win / disp : 0;
  *kappa = sums[1] > 0 ? sums[0] / sums[1] : 0;
}

} // namespace

PetscErrorCode LocalizedEigen(PetscInt n2_, PetscReal *a, const LocalizedRegion &reg, const std::vector<PetscReal> &f, PetscInt nev, const FloquetOptions &fo,
                              LocalizedSpectrum *out)
{
  const int n = (int)n2_, one = 1;
  int info = 0, lwork = -1;
  PetscReal wq;
  PetscFunctionBeginUser;
  std::vector<PetscReal> tau(std::max(1, n - 1)), wr(n), wi(n);
  dgehrd_(&n, &one, &n, a, &n, tau.data(), &wq, &lwork, &info);
  std::vector<PetscReal> work((size_t)wq + 1);
  lwork = (int)work.size();
  dgehrd_(&n, &one, &n, a, &n, tau.data(), work.data(), &lwork, &info);
  PetscCheck(info == 0, PETSC_COMM_SELF, PETSC_ERR_LIB, "localized Floquet: LAPACK dgehrd failed, info %d (2n = %d)", info, n);
  std::vector<PetscReal> h((size_t)n * n, 0.0);
  for (int c = 0; c < n; c++)
    for (int i = 0; i <= std::min(c + 1, n - 1); i++) h[(size_t)c * n + i] = a[(size_t)c * n + i];
  std::vector<PetscReal> hq = h;
  lwork = -1;
  dhseqr_("E", "N", &n, &one, &n, hq.data(), &n, wr.data(), wi.data(), NULL, &one, &wq, &lwork, &info, 1, 1);
  work.resize(std::max<size_t>(work.size(), (size_t)wq + 1));
  lwork = (int)work.size();
  dhseqr_("E", "N", &n, &one, &n, hq.data(), &n, wr.data(), wi.data(), NULL, &one, work.data(), &lwork, &info, 1, 1);
  PetscCheck(info == 0, PETSC_COMM_SELF, PETSC_ERR_LIB, "localized Floquet: LAPACK dhseqr failed, info %d (2n = %d)", info, n);
  out->all.resize(n);
  for (int i = 0; i < n; i++) out->all[i] = {wr[i], wi[i]};
  // The trivial pair: within 1e-2 of 1 and along f(z0) (the time shift; its
  // Jordan partner splits from it as 1 +- sqrt(eps) when the damping touches f).
  std::vector<int> near1;
  for (int i = 0; i < n; i++)
    if (wi[i] >= 0 && std::abs(out->all[i] - 1.0) < 1e-2) near1.push_back(i);
  std::vector<std::vector<PetscReal>> vn;
  out->trivial.clear();
  if (!f.empty() && !near1.empty()) {
    PetscCall(SelectedVectors(n, a, tau, h, wr, wi, near1, &vn));
    std::vector<std::pair<PetscReal, int>> al;
    for (size_t k = 0; k < near1.size(); k++) al.push_back({Alignment(vn[k], f), near1[k]});
    std::sort(al.rbegin(), al.rend());
    for (size_t k = 0; k < al.size() && k < 2; k++)
      if (al[k].first >= 0.5) out->trivial.push_back(al[k].second);
  }
  std::vector<int> idx;
  for (int i = 0; i < n; i++)
    if (wi[i] >= 0 && std::find(out->trivial.begin(), out->trivial.end(), i) == out->trivial.end()) idx.push_back(i);
  std::stable_sort(idx.begin(), idx.end(), [&](int x, int y) { return std::abs(out->all[x]) > std::abs(out->all[y]); });
  if ((PetscInt)idx.size() > nev) idx.resize(nev);
  std::vector<std::vector<PetscReal>> vs;
  PetscCall(SelectedVectors(n, a, tau, h, wr, wi, idx, &vs));
  out->mu.clear(), out->edge.clear(), out->inside.clear(), out->kappa.clear(), out->vector.clear();
  for (size_t k = 0; k < idx.size(); k++) {
    PetscReal e, w, kap;
    VectorShares(vs[k], reg, fo, &e, &w, &kap);
    out->mu.push_back(out->all[idx[k]]), out->edge.push_back(e), out->inside.push_back(w), out->kappa.push_back(kap);
  }
  if (!vs.empty()) out->vector = vs[0];
  PetscFunctionReturn(0);
}

namespace {

// rank 0's spectrum on every rank (the leading part: mu, shares, vector; the count of all and trivial).
PetscErrorCode BroadcastSpectrum(MPI_Comm comm, LocalizedSpectrum *s, PetscInt n2)
{
  PetscMPIInt rank;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscInt k = (PetscInt)s->mu.size(), nt = (PetscInt)s->trivial.size(), nv = (PetscInt)s->vector.size();
  PetscInt head[3] = {k, nt, nv};
  PetscCallMPI(MPI_Bcast(head, 3, MPIU_INT, 0, comm));
  k = head[0], nt = head[1], nv = head[2];
  std::vector<PetscReal> buf;
  if (rank == 0) {
    for (PetscInt i = 0; i < k; i++) buf.insert(buf.end(), {s->mu[i].real(), s->mu[i].imag(), s->edge[i], s->inside[i], s->kappa[i]});
    for (PetscInt i = 0; i < nt; i++) buf.push_back(s->trivial[i]);
    for (PetscInt i = 0; i < n2; i++) buf.insert(buf.end(), {s->all[i].real(), s->all[i].imag()});
    buf.insert(buf.end(), s->vector.begin(), s->vector.end());
  }
  buf.resize(5 * k + nt + 2 * n2 + nv);
  PetscCallMPI(MPI_Bcast(buf.data(), (PetscMPIInt)buf.size(), MPIU_REAL, 0, comm));
  if (rank != 0) {
    const PetscReal *b = buf.data();
    s->mu.resize(k), s->edge.resize(k), s->inside.resize(k), s->kappa.resize(k), s->trivial.resize(nt), s->all.resize(n2);
    for (PetscInt i = 0; i < k; i++, b += 5) s->mu[i] = {b[0], b[1]}, s->edge[i] = b[2], s->inside[i] = b[3], s->kappa[i] = b[4];
    for (PetscInt i = 0; i < nt; i++) s->trivial[i] = (PetscInt)*b++;
    for (PetscInt i = 0; i < n2; i++, b += 2) s->all[i] = {b[0], b[1]};
    s->vector.assign(b, b + nv);
  }
  PetscFunctionReturn(0);
}

// The spectrum of the damped region map of one region (collective).
PetscErrorCode SolveRegion(PeriodicFlow &flow, Vec z0, PetscReal T, PetscReal beta, const LocalizedRegion &reg, const FloquetOptions &fo, PetscInt nev,
                           LocalizedSpectrum *s, PetscErrorCode *code, char *msg, size_t len)
{
  const MPI_Comm comm = flow.Lat().Comm();
  PetscMPIInt rank;
  std::vector<PetscReal> a, f;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCall(LocalizedMonodromy(flow, z0, T, beta, reg, &a, &f));
  *code = 0;
  if (rank == 0) PetscCall(CaptureError([&]() { return LocalizedEigen(2 * reg.Sites(), a.data(), reg, f, nev, fo, s); }, code, msg, len));
  PetscCallMPI(MPI_Bcast(code, 1, MPI_INT, 0, comm));
  PetscCallMPI(MPI_Bcast(msg, (PetscMPIInt)len, MPI_CHAR, 0, comm));
  if (*code) PetscFunctionReturn(0);
  PetscCall(BroadcastSpectrum(comm, s, 2 * reg.Sites()));
  PetscFunctionReturn(0);
}

// The leading multiplier of variant lo of the options, nearest mu0.
PetscErrorCode VariantMultiplier(PeriodicFlow &flow, Vec z0, PetscReal T, PetscReal beta, const FloquetOptions &fo, const LocalizedOptions &lo, PetscInt nev,
                                 std::complex<PetscReal> mu0, std::complex<PetscReal> *mu)
{
  LocalizedSpectrum s;
  PetscErrorCode code;
  char msg[256] = "";
  const Lattice &lat = flow.Lat();
  PetscFunctionBeginUser;
  const LocalizedRegion reg = MakeLocalizedRegion(lat.N(), lat.Params().InterfaceSite(), lo);
  PetscCall(SolveRegion(flow, z0, T, beta, reg, fo, nev, &s, &code, msg, sizeof msg));
  PetscCall(FailTogether(lat.Comm(), code, msg));
  *mu = std::complex<PetscReal>(NAN, NAN);
  for (const auto &m : s.mu)
    if (!(std::abs(m - mu0) >= std::abs(*mu - mu0))) *mu = m;
  PetscFunctionReturn(0);
}

// The eigenvector [re | im] in region layout into full-lattice state vectors.
PetscErrorCode ScatterVector(const Lattice &lat, const LocalizedRegion &reg, const std::vector<PetscReal> &v, Vec vr, Vec vi)
{
  const PetscInt n = reg.Sites(), n2 = 2 * n, xs = lat.OwnedStart(), xm = lat.OwnedCount();
  PetscFunctionBeginUser;
  for (int part = 0; part < 2; part++) {
    Vec x = part == 0 ? vr : vi;
    if (!x) continue;
    PetscScalar *xa;
    PetscCall(VecZeroEntries(x));
    if (v.empty()) continue;
    PetscCall(VecGetArray(x, &xa));
    const PetscReal *src = v.data() + part * n2;
    for (PetscInt i = std::max(reg.lo, xs); i <= std::min(reg.hi, xs + xm - 1); i++) xa[i - xs] = src[i - reg.lo], xa[xm + i - xs] = src[n + i - reg.lo];
    PetscCall(VecRestoreArray(x, &xa));
  }
  PetscFunctionReturn(0);
}

} // namespace

PetscErrorCode LocalizedIndependence(PeriodicFlow &flow, Vec z0, PetscReal T, PetscReal beta, const FloquetOptions &fo, const LocalizedOptions &lo,
                                     PetscInt nev, LocalizedIndependenceResult *res)
{
  PetscFunctionBeginUser;
  const std::complex<PetscReal> none(NAN, NAN);
  { // the base solve's leading multiplier
    LocalizedSpectrum s;
    PetscErrorCode code;
    char msg[256] = "";
    const LocalizedRegion reg = MakeLocalizedRegion(flow.Lat().N(), flow.Lat().Params().InterfaceSite(), lo);
    PetscCall(SolveRegion(flow, z0, T, beta, reg, fo, nev, &s, &code, msg, sizeof msg));
    PetscCall(FailTogether(flow.Lat().Comm(), code, msg));
    res->mu0 = s.mu.empty() ? none : s.mu[0];
  }
  LocalizedOptions var[4] = {lo, lo, lo, lo};
  var[0].window = std::max<PetscInt>(1, lo.window / 2), var[1].window = 2 * lo.window;
  var[2].damping = lo.damping / 2, var[3].damping = 2 * lo.damping;
  res->mu.assign(4, none), res->change.assign(4, NAN);
  res->max_change = res->max_modulus_change = 0;
  for (int k = 0; k < 4; k++) {
    PetscCall(VariantMultiplier(flow, z0, T, beta, fo, var[k], nev, res->mu0, &res->mu[k]));
    res->change[k] = std::abs(res->mu[k] - res->mu0);
    res->max_change = std::max(res->max_change, res->change[k]); // NaN-safe: std::max keeps the first on NaN
    if (!std::isfinite(res->change[k])) res->max_change = PETSC_INFINITY;
    res->max_modulus_change = std::max(res->max_modulus_change, std::abs(std::abs(res->mu[k]) - std::abs(res->mu0)));
  }
  PetscFunctionReturn(0);
}

PetscInt LocalizedClass(const FloquetOptions &fo, PetscReal edge, PetscReal inside)
{
  const PetscInt cls = Localisation(fo, edge);
  return cls == 3 && 1 - inside > kRadiatingShare ? 2 : cls;
}

PetscErrorCode ConfirmLocalizedGrowth(PeriodicFlow &flow, Vec z0, PetscReal T, PetscReal beta, Vec vr, Vec vi, const LocalizedOptions &lo,
                                      const FloquetOptions &o, OrbitVerdict *v)
{
  const Lattice &lat = flow.Lat();
  const LocalizedRegion reg = MakeLocalizedRegion(lat.N(), lat.Params().InterfaceSite(), lo);
  PetscInt window[2] = {-1, -1}; // the undamped sites (contiguous around the interface)
  PetscFunctionBeginUser;
  for (PetscInt s = 0; s < reg.Sites(); s++)
    if (reg.InWindow(s)) window[0] = window[0] < 0 ? reg.lo + s : window[0], window[1] = reg.lo + s;
  PetscCall(ConfirmGrowth(flow, z0, T, beta, vr, vi, o, v, window));
  PetscFunctionReturn(0);
}

PetscErrorCode FloquetLocalized(PeriodicFlow &flow, Vec z0, PetscReal T, PetscReal beta, const FloquetOptions &fo, const LocalizedOptions &lo, PetscInt nev,
                                LeadingMultipliers *r, OrbitVerdict *v, Vec vr, Vec vi)
{
  const Lattice &lat = flow.Lat();
  LocalizedSpectrum s;
  PetscErrorCode code;
  char msg[256] = "";
  PetscLogEvent ev;
  PetscFunctionBeginUser;
  PetscCall(LocalizedEvent(&ev));
  PetscCall(PetscLogEventBegin(ev, 0, 0, 0, 0));
  PetscCheck(lat.Params().layout == Layout::Interface, lat.Comm(), PETSC_ERR_USER,
             "-floquet_mf_which localized damps the tangent equations outside a window around the interface: it needs -lattice_layout interface");
  const LocalizedRegion reg = MakeLocalizedRegion(lat.N(), lat.Params().InterfaceSite(), lo);
  PetscCall(SolveRegion(flow, z0, T, beta, reg, fo, nev, &s, &code, msg, sizeof msg));
  *r = LeadingMultipliers();
  r->re.assign(nev, NAN), r->im.assign(nev, NAN), r->krein.assign(nev, 0), r->resolution.assign(nev, NAN);
  r->products = 2 * reg.Sites();
  *v = OrbitVerdict();
  if (vr) PetscCall(VecZeroEntries(vr));
  if (vi) PetscCall(VecZeroEntries(vi));
  if (code) { // LAPACK failed on rank 0: no bound
    v->reason = std::string("localized route: ") + msg;
    r->max_modulus = NAN;
    PetscCall(PetscLogEventEnd(ev, 0, 0, 0, 0));
    PetscFunctionReturn(0);
  }
  // delta: what this orbit's answer is resolved to (docs/long-lattices.md "The localized route")
  PetscReal delta = fo.tol, sens = 0;
  std::ostringstream why;
  const PetscReal m = s.mu.empty() ? 0 : std::abs(s.mu[0]);
  if (lo.resolve && !s.mu.empty()) { // the window halved: how far the leading modulus depends on it
    LocalizedOptions half = lo;
    half.window = std::max<PetscInt>(1, lo.window / 2);
    LocalizedSpectrum sh;
    const LocalizedRegion rh = MakeLocalizedRegion(lat.N(), lat.Params().InterfaceSite(), half);
    PetscCall(SolveRegion(flow, z0, T, beta, rh, fo, nev, &sh, &code, msg, sizeof msg));
    sens = code || sh.mu.empty() ? PETSC_INFINITY : std::abs(std::abs(sh.mu[0]) - m);
    why << "; the window halved moves the leading |mu| by " << sens;
    code = 0;
  }
  if (lo.check && !s.mu.empty()) {
    LocalizedIndependenceResult ind;
    PetscCall(LocalizedIndependence(flow, z0, T, beta, fo, lo, nev, &ind));
    sens = std::max(sens, ind.max_modulus_change);
    why << "; W and c halved and doubled move it by " << ind.max_modulus_change;
  }
  delta = std::max(delta, sens);
  r->converged = (PetscInt)s.mu.size();
  r->max_modulus = m;
  for (size_t k = 0; k < s.mu.size(); k++) {
    r->re[k] = s.mu[k].real(), r->im[k] = s.mu[k].imag(), r->krein[k] = KreinSign(fo, s.kappa[k]), r->resolution[k] = delta;
  }
  std::ostringstream head;
  head << "localized route (window " << lo.window << " cells, ramp " << lo.ramp << ", damping " << lo.damping << ", " << 2 * reg.Sites()
       << " columns): leading |mu| = " << m;
  if (!s.mu.empty()) head << ", edge share " << s.edge[0] << ", window share " << s.inside[0];
  head << why.str();
  r->verdict = kUndecided, r->instability = -1;
  if (m > 1 + delta && s.inside[0] >= 0.5) {
    const PetscInt cls = LocalizedClass(fo, s.edge[0], s.inside[0]);
    *v = UnstableVerdict(s.mu[0], cls, head.str());
    r->verdict = kUnstable, r->instability = cls;
    PetscCall(ScatterVector(lat, reg, s.vector, vr, vi));
  } else if (m > 1 + delta) { // it lives where the tangent equations are damped: an artefact of the layer, not a mode of the lattice
    v->code = Verdict::Unresolved;
    v->bound = m - 1;
    v->reason = head.str() + ": the growing vector lies in the absorbing layer (raise -floquet_loc_damping or -floquet_loc_window)";
  } else if (m > 1 + fo.tol) { // beyond -floquet_tol, within the window's resolution
    v->code = Verdict::Unresolved;
    v->bound = m - 1 + sens;
    v->reason = head.str() + ": beyond 1 + -floquet_tol but not beyond the window's resolution (raise -floquet_loc_window)";
  } else {
    v->code = Verdict::StableTo;
    v->bound = delta;
    v->reason = head.str() + ": no damped multiplier beyond 1 + delta";
    r->instability = 0;
  }
  PetscCall(PetscLogEventEnd(ev, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

} // namespace nltopo
