#include "stability/floquet_localized.hpp"
#include "stability/floquet_exterior.hpp"
#include "stability/region_map.hpp"
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
              "(five times the cost)")
          .Bool("exterior", &LocalizedOptions::exterior,
                "Where M - M_lin fits in the region of -floquet_loc_exterior_cells, take the verdict from the exterior route: every multiplier of the "
                "whole finite lattice beyond 1 + -floquet_tol / 10, from the window of M - M_lin and the linear modes (needs N <= 6000)")
          .Int("exterior_cells", &LocalizedOptions::exterior_cells, Closed(4, 100000),
               "Exterior route: cells on each side of the interface cell in the region where M - M_lin is integrated (its window must reach at most "
               "half-way to the region's ends)")
          .Real("exterior_tol", &LocalizedOptions::exterior_tol, Open(0, 1e-3),
                "Exterior route: entries of M - M_lin below this times max |M| lie outside the window")
          .Real("exterior_arc", &LocalizedOptions::exterior_arc, RightOpen(0, 1),
                "Exterior route: the multipliers of the linear lattice within this distance of a scan point are kept exactly in its local problem, the "
                "others linearized (scan points every half arc along the unit semicircle); 0: 10 pi / N (five mean pole spacings), at most 0.1");
    });

PetscErrorCode LocalizedOptionsFromOptions(MPI_Comm comm, LocalizedOptions *o)
{
  PetscFunctionBeginUser;
  PetscCall(kLocalizedTable.Read(comm, o));
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


PetscErrorCode LocalizedMonodromy(PeriodicFlow &flow, Vec z0, PetscReal T, PetscReal, const LocalizedRegion &reg, std::vector<PetscReal> *a,
                                  std::vector<PetscReal> *f)
{
  const Lattice &lat = flow.Lat();
  const MPI_Comm comm = lat.Comm();
  const PetscInt n = reg.Sites(), n2 = 2 * n;
  std::vector<PetscReal> rec;
  const symsplit::Scheme *sch;
  PetscFunctionBeginUser;
  // beta: the multipliers are those of the free flow (beta = 0), as FloquetBeta takes them on the symplectic route
  PetscCall(RecordStiffness(flow, z0, T, reg, &rec, &sch));
  PetscCall(RegionMapOnRoot(comm, reg, rec, 2 * n, *sch, flow.Steps(), T, a));
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
  const int n = (int)n2_;
  std::vector<PetscReal> tau, h, wr, wi, work;
  PetscFunctionBeginUser;
  PetscCall(HessenbergEigenvalues(n, a, tau, h, wr, wi, work));
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
  if (v->whole_lattice_vector) { // the exterior route's eigenvector of the finite lattice: it grows as a whole
    PetscCall(ConfirmGrowth(flow, z0, T, beta, vr, vi, o, v));
    PetscFunctionReturn(0);
  }
  for (PetscInt s = 0; s < reg.Sites(); s++)
    if (reg.InWindow(s)) window[0] = window[0] < 0 ? reg.lo + s : window[0], window[1] = reg.lo + s;
  PetscCall(ConfirmGrowth(flow, z0, T, beta, vr, vi, o, v, window));
  PetscFunctionReturn(0);
}

namespace {

// -floquet_loc_exterior: where M - M_lin fits in its region, the verdict and
// the multipliers are the finite lattice's (the exterior route); the damped
// route's answer (the long-lattice limit) stays in the reason. Elsewhere the
// damped verdict stands, the reason saying why. Collective.
PetscErrorCode ExteriorVerdict(PeriodicFlow &flow, Vec z0, PetscReal T, const FloquetOptions &fo, const LocalizedOptions &lo, PetscInt nev,
                               const std::string &damped, LeadingMultipliers *r, OrbitVerdict *v, Vec vr, Vec vi)
{
  ExteriorResult ex;
  OwnedVec xr, xi;
  PetscFunctionBeginUser;
  if (vr) PetscCall(VecDuplicate(vr, xr.out()));
  if (vi) PetscCall(VecDuplicate(vi, xi.out()));
  PetscCall(FloquetExterior(flow, z0, T, fo, lo, &ex, xr, xi));
  r->products += 4 * ex.region_sites;
  if (!ex.resolved) {
    v->reason += "; exterior route not used: " + ex.why;
    PetscFunctionReturn(0);
  }
  std::ostringstream head;
  head << "exterior route (M - M_lin on " << ex.window_sites << " window sites of a " << ex.region_sites << "-site region, " << ex.centres
       << " scan points on arcs of " << ex.arc << ", " << ex.solves << " local eigenproblems): ";
  const std::string tail = "; the damped " + damped.substr(std::string("localized ").size());
  r->re.assign(nev, NAN), r->im.assign(nev, NAN), r->resolution.assign(nev, fo.tol), r->krein.assign(nev, 0);
  r->converged = std::min<PetscInt>(nev, (PetscInt)ex.mu.size());
  for (PetscInt k = 0; k < r->converged; k++) r->re[k] = ex.mu[k].real(), r->im[k] = ex.mu[k].imag();
  r->max_modulus = ex.mu.empty() ? 1 : std::abs(ex.mu[0]);
  if (!ex.mu.empty() && std::abs(ex.mu[0]) > 1 + fo.tol) {
    const PetscInt cls = Localisation(fo, ex.edge[0]);
    head << "|mu| = " << std::abs(ex.mu[0]) << ", edge share " << ex.edge[0] << " (window part of v against y: " << ex.residual << ")";
    *v = UnstableVerdict(ex.mu[0], cls, head.str() + tail);
    v->whole_lattice_vector = true;
    r->verdict = kUnstable, r->instability = cls;
    if (vr) PetscCall(VecCopy(xr, vr));
    if (vi) PetscCall(VecCopy(xi, vi));
  } else {
    head << "no multiplier of the " << flow.Lat().N() << "-site lattice beyond 1 + " << fo.tol;
    if (!ex.mu.empty()) head << " (largest |mu| = " << std::abs(ex.mu[0]) << ")";
    *v = StableToVerdict(fo.tol, head.str() + tail);
    r->verdict = kUndecided, r->instability = 0;
    if (vr) PetscCall(VecZeroEntries(vr));
    if (vi) PetscCall(VecZeroEntries(vi));
  }
  PetscFunctionReturn(0);
}

} // namespace

PetscErrorCode FloquetLocalized(PeriodicFlow &flow, Vec z0, PetscReal T, PetscReal beta, const FloquetOptions &fo, const LocalizedOptions &lo, PetscInt nev,
                                LeadingMultipliers *r, OrbitVerdict *v, Vec vr, Vec vi)
{
  const Lattice &lat = flow.Lat();
  LocalizedSpectrum s;
  PetscErrorCode code;
  char msg[256] = "";
  PetscLogEvent ev;
  PetscFunctionBeginUser;
  PetscCall(NamedLogEvent("FloquetLocal", &ev));
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
  if (lo.exterior) PetscCall(ExteriorVerdict(flow, z0, T, fo, lo, nev, head.str(), r, v, vr, vi));
  PetscCall(PetscLogEventEnd(ev, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

} // namespace nltopo
