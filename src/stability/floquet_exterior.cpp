#include "stability/floquet_exterior.hpp"
#include "core/errors.hpp"
#include "core/lapack.hpp"
#include "core/log.hpp"
#include "stability/region_map.hpp"
#include <algorithm>
#include <cmath>
#include <sstream>

namespace nltopo {

namespace {

using cplx = std::complex<double>;

// ---- the linear lattice: its modes and their one-period maps ----

// K = Z diag(w2) Z^T (column q of Z the mode q, unit norm), on rank 0, kept
// while K is the same (the modes of a branch's lattice are computed once).
struct ModeBasis {
  std::vector<double> kd, kb; // the K they belong to
  std::vector<double> w2, Z;  // eigenvalues, N x N column-major eigenvectors
  int N() const { return (int)kd.size(); }
};

PetscErrorCode ComputeModes(const std::vector<double> &kd, const std::vector<double> &kb, ModeBasis *mb)
{
  const int n = (int)kd.size();
  int info = 0, lwork = -1, liwork = -1, iq;
  double wq;
  PetscFunctionBeginUser;
  mb->kd = kd, mb->kb = kb, mb->w2 = kd, mb->Z.assign((size_t)n * n, 0.0);
  std::vector<double> e = kb;
  e.resize(std::max(n, 1));
  dstevd_("V", &n, mb->w2.data(), e.data(), mb->Z.data(), &n, &wq, &lwork, &iq, &liwork, &info, 1);
  std::vector<double> work((size_t)wq + 1);
  std::vector<int> iwork(iq + 1);
  lwork = (int)work.size(), liwork = (int)iwork.size();
  dstevd_("V", &n, mb->w2.data(), e.data(), mb->Z.data(), &n, work.data(), &lwork, iwork.data(), &liwork, &info, 1);
  PetscCheck(info == 0, PETSC_COMM_SELF, PETSC_ERR_LIB, "exterior Floquet: LAPACK dstevd failed on K, info %d (N = %d)", info, n);
  PetscFunctionReturn(0);
}

// One mode's map over a period, its multipliers lam[0] = e^{+i theta},
// lam[1] = e^{-i theta} and spectral projectors P[0], P[1] (2 x 2 row-major):
// (R - mu)^-1 = P[0] / (lam[0] - mu) + P[1] / (lam[1] - mu).
struct ModeMap {
  double R[4];
  cplx lam[2], P[2][4];
  bool split = true; // lam[0] and lam[1] apart (not both at +-1): its poles may be kept apart near mu0
};

// The splitting's kicks and drifts on q'' = -w2 q, exactly as the region map
// takes them (stability/region_map.cpp), n steps of h.
ModeMap OscillatorMap(double w2, const symsplit::Scheme &s, PetscInt steps, double h)
{
  double a = 1, b = 0, c = 0, d = 1; // [q; p] = [[a, b], [c, d]] [q0; p0]
  const size_t st = s.drift.size();
  for (size_t k = 0; k <= st; k++) {
    const double kh = s.kick[k] * h * w2;
    c -= kh * a, d -= kh * b;
    if (k < st) a += s.drift[k] * h * c, b += s.drift[k] * h * d;
  }
  double R[4] = {1, 0, 0, 1};
  for (PetscInt i = 0; i < steps; i++) {
    const double r0 = a * R[0] + b * R[2], r1 = a * R[1] + b * R[3], r2 = c * R[0] + d * R[2], r3 = c * R[1] + d * R[3];
    R[0] = r0, R[1] = r1, R[2] = r2, R[3] = r3;
  }
  ModeMap m;
  std::copy(R, R + 4, m.R);
  const double half = 0.5 * (R[0] + R[3]);
  const cplx root = std::sqrt(cplx(half * half - 1, 0));
  m.lam[0] = half + root, m.lam[1] = half - root;
  if (m.lam[0].imag() < 0) std::swap(m.lam[0], m.lam[1]);
  // a mode whose multipliers nearly meet at +-1 (the linear interface mode at the branch's start, theta = 2 pi):
  // its projectors blow up, so its resolvent is never split into poles (it stays in the linearized part)
  m.split = std::abs(m.lam[0] - m.lam[1]) > 1e-4;
  for (int k = 0; k < 2; k++) { // P_k = (R - lam_other) / (lam_k - lam_other)
    const cplx o = m.lam[1 - k], den = m.lam[k] - o;
    m.P[k][0] = (R[0] - o) / den, m.P[k][1] = R[1] / den, m.P[k][2] = R[2] / den, m.P[k][3] = (R[3] - o) / den;
  }
  return m;
}

// ---- the secular problem (I + G(mu) W) y = 0 on rank 0 ----

class Secular {
public:
  // win: the window's first lattice site and its site count; W: c x c, column-major, window layout [u | v].
  Secular(const ModeBasis &mb, const std::vector<ModeMap> &maps, PetscInt win0, int nw, std::vector<double> W)
      : mb_(mb), maps_(maps), nw_(nw), c_(2 * nw), W_(std::move(W))
  {
    const int N = mb.N();
    phi_.resize((size_t)nw * N);
    for (int q = 0; q < N; q++)
      for (int i = 0; i < nw; i++) phi_[(size_t)q * nw + i] = mb.Z[(size_t)q * N + win0 + i];
  }
  int Size() const { return c_; }
  // The eigenvalues of the local problem at mu0 (and, with vectors, the
  // window part y of each right eigenvector: c values per eigenvalue).
  PetscErrorCode Local(cplx mu0, double arc, std::vector<cplx> *mu, std::vector<cplx> *y);
  PetscInt solves = 0;

private:
  void Block(const std::vector<cplx> &g, int ab, std::vector<cplx> *G) const; // G's (a, b) block += Phi_w diag(g) Phi_w^T
  const ModeBasis &mb_;
  const std::vector<ModeMap> &maps_;
  int nw_, c_;
  std::vector<double> W_, phi_; // phi_: nw x N column-major (the window rows of Z)
};

void Secular::Block(const std::vector<cplx> &g, int ab, std::vector<cplx> *G) const
{
  const int N = mb_.N(), a = ab / 2, b = ab % 2;
  const double one = 1, zero = 0;
  std::vector<double> s((size_t)nw_ * N), out((size_t)nw_ * nw_);
  for (int part = 0; part < 2; part++) {
    for (int q = 0; q < N; q++) {
      const double x = part ? g[q].imag() : g[q].real();
      for (int i = 0; i < nw_; i++) s[(size_t)q * nw_ + i] = phi_[(size_t)q * nw_ + i] * x;
    }
    dgemm_("N", "T", &nw_, &nw_, &N, &one, s.data(), &nw_, phi_.data(), &nw_, &zero, out.data(), &nw_, 1, 1);
    for (int j = 0; j < nw_; j++)
      for (int i = 0; i < nw_; i++) (*G)[(size_t)(b * nw_ + j) * c_ + a * nw_ + i] += part ? cplx(0, out[(size_t)j * nw_ + i]) : out[(size_t)j * nw_ + i];
  }
}

PetscErrorCode Secular::Local(cplx mu0, double arc, std::vector<cplx> *mu, std::vector<cplx> *y)
{
  const int N = mb_.N(), c = c_;
  PetscFunctionBeginUser;
  // far parts of (R_q - mu0)^-1 and its square per mode; the near poles apart
  std::vector<cplx> x[4], d[4];
  for (int e = 0; e < 4; e++) x[e].assign(N, 0.0), d[e].assign(N, 0.0);
  struct Pole {
    int q, k;
  };
  std::vector<Pole> near;
  for (int q = 0; q < N; q++) {
    const double *R = maps_[q].R;
    const cplx det = (R[0] - mu0) * (R[3] - mu0) - R[1] * R[2];
    cplx X[4] = {(R[3] - mu0) / det, -R[1] / det, -R[2] / det, (R[0] - mu0) / det};
    cplx Y[4] = {X[0] * X[0] + X[1] * X[2], X[0] * X[1] + X[1] * X[3], X[2] * X[0] + X[3] * X[2], X[2] * X[1] + X[3] * X[3]};
    for (int k = 0; k < 2; k++) {
      const cplx dl = maps_[q].lam[k] - mu0;
      if (std::abs(dl) >= arc || !maps_[q].split) continue;
      near.push_back({q, k});
      for (int e = 0; e < 4; e++) X[e] -= maps_[q].P[k][e] / dl, Y[e] -= maps_[q].P[k][e] / (dl * dl);
    }
    for (int e = 0; e < 4; e++) x[e][q] = X[e], d[e][q] = Y[e];
  }
  std::vector<cplx> G0((size_t)c * c, 0.0), G1((size_t)c * c, 0.0);
  for (int e = 0; e < 4; e++) Block(x[e], e, &G0), Block(d[e], e, &G1);
  // A z = mu B z, z = (y, s): [[I + (G0 - mu0 G1) W, a], [-b^T W, diag(lam)]], B = [[-G1 W, 0], [0, I]]
  const int nq = (int)near.size(), K = c + nq;
  std::vector<cplx> A((size_t)K * K, 0.0), B((size_t)K * K, 0.0);
  for (int j = 0; j < c; j++)
    for (int i = 0; i < c; i++) {
      cplx s0 = 0, s1 = 0;
      for (int l = 0; l < c; l++) {
        const double w = W_[(size_t)j * c + l];
        if (w != 0) s0 += (G0[(size_t)l * c + i] - mu0 * G1[(size_t)l * c + i]) * w, s1 += G1[(size_t)l * c + i] * w;
      }
      A[(size_t)j * K + i] = s0 + (i == j ? 1.0 : 0.0), B[(size_t)j * K + i] = -s1;
    }
  for (int k = 0; k < nq; k++) {
    const ModeMap &m = maps_[near[k].q];
    const cplx *P = m.P[near[k].k];
    const int jj = std::abs(P[0]) >= std::abs(P[3]) ? 0 : 1; // P = x y^T, rank 1: x its column jj, y its row jj / P(jj, jj)
    const cplx xs[2] = {P[jj], P[2 + jj]}, ys[2] = {P[2 * jj] / P[3 * jj], P[2 * jj + 1] / P[3 * jj]};
    const double *ph = &phi_[(size_t)near[k].q * nw_];
    for (int half = 0; half < 2; half++)
      for (int i = 0; i < nw_; i++) A[(size_t)(c + k) * K + half * nw_ + i] = ph[i] * xs[half]; // a_k
    for (int j = 0; j < c; j++) { // -(b_k^T W)_j
      cplx s = 0;
      for (int half = 0; half < 2; half++)
        for (int i = 0; i < nw_; i++) s += ph[i] * ys[half] * W_[(size_t)j * c + half * nw_ + i];
      A[(size_t)j * K + c + k] = -s;
    }
    A[(size_t)(c + k) * K + c + k] = m.lam[near[k].k];
    B[(size_t)(c + k) * K + c + k] = 1;
  }
  std::vector<cplx> alpha(K), beta(K), vr(y ? (size_t)K * K : 1), work(1);
  std::vector<double> rwork(8 * (size_t)K);
  int info = 0, lwork = -1, one = 1;
  const char *jv = y ? "V" : "N";
  zggev_("N", jv, &K, A.data(), &K, B.data(), &K, alpha.data(), beta.data(), nullptr, &one, vr.data(), &K, work.data(), &lwork, rwork.data(), &info, 1, 1);
  work.resize((size_t)work[0].real() + 1);
  lwork = (int)work.size();
  zggev_("N", jv, &K, A.data(), &K, B.data(), &K, alpha.data(), beta.data(), nullptr, &one, vr.data(), &K, work.data(), &lwork, rwork.data(), &info, 1, 1);
  PetscCheck(info == 0, PETSC_COMM_SELF, PETSC_ERR_LIB, "exterior Floquet: LAPACK zggev failed, info %d (size %d)", info, K);
  solves++;
  mu->clear();
  if (y) y->clear();
  for (int i = 0; i < K; i++) {
    if (std::abs(beta[i]) <= 1e-14 * std::abs(alpha[i])) continue; // infinite (B is singular)
    mu->push_back(alpha[i] / beta[i]);
    if (y) y->insert(y->end(), vr.begin() + (size_t)i * K, vr.begin() + (size_t)i * K + c);
  }
  PetscFunctionReturn(0);
}

// ---- roots: refinement and the scan ----

// Successive local problems from mu: moves mu0 to the local eigenvalue
// nearest it until it stops moving. False when it does not converge.
PetscErrorCode Refine(Secular &sec, double arc, cplx *mu, bool *ok)
{
  std::vector<cplx> ev;
  PetscFunctionBeginUser;
  *ok = false;
  double step = INFINITY;
  for (int it = 0; it < 30; it++) {
    PetscCall(sec.Local(*mu, arc, &ev, nullptr));
    if (ev.empty()) PetscFunctionReturn(0);
    cplx best = ev[0];
    for (const cplx &e : ev)
      if (std::abs(e - *mu) < std::abs(best - *mu)) best = e;
    step = std::abs(best - *mu);
    *mu = best;
    if (step <= 1e-13 * std::abs(best)) {
      *ok = true;
      break;
    }
    if (step > arc) PetscFunctionReturn(0); // left the neighbourhood where it was found
  }
  *ok = step <= 1e-10 * std::abs(*mu); // 30 steps: accepted if the last one was small (the convergence stalls at rounding)
  PetscFunctionReturn(0);
}

// Every root beyond 1 + floor in the closed upper half plane, by modulus.
PetscErrorCode Scan(Secular &sec, double arc, double floor, std::vector<cplx> *roots, PetscInt *centres)
{
  std::vector<cplx> ev;
  PetscFunctionBeginUser;
  roots->clear();
  const int nc = (int)std::ceil(M_PI / (0.5 * arc)) + 1;
  *centres = nc;
  for (int j = 0; j < nc; j++) {
    const cplx mu0 = std::polar(1.0, M_PI * j / (nc - 1));
    PetscCall(sec.Local(mu0, arc, &ev, nullptr));
    for (cplx mu : ev) {
      if (std::abs(mu - mu0) > 0.6 * arc || std::abs(mu) <= 1 + floor || mu.imag() < -1e-12) continue;
      bool seen = false;
      for (const cplx &r : *roots) seen = seen || std::abs(r - mu) < 1e-6 * arc;
      if (seen) continue;
      bool ok;
      PetscCall(Refine(sec, arc, &mu, &ok));
      if (!ok || std::abs(mu) <= 1 + floor) continue;
      if (mu.imag() < 0) mu = std::conj(mu);
      seen = false;
      for (const cplx &r : *roots) seen = seen || std::abs(r - mu) < 1e-9;
      if (!seen) roots->push_back(mu);
    }
  }
  std::sort(roots->begin(), roots->end(), [](const cplx &a, const cplx &b) { return std::abs(a) > std::abs(b); });
  PetscFunctionReturn(0);
}

// The whole lattice's eigenvector v = -(M_lin - mu)^-1 P W y (natural state
// layout [u_1..u_N, v_1..v_N]), its edge share and |P^T v - y| / |y|.
void WholeVector(const ModeBasis &mb, const std::vector<ModeMap> &maps, PetscInt win0, int nw, const std::vector<double> &W, cplx mu,
                 const std::vector<cplx> &y, PetscInt iface, PetscInt edge_sites, std::vector<cplx> *v, double *edge, double *residual)
{
  const int N = mb.N(), c = 2 * nw;
  std::vector<cplx> wy(c, 0.0);
  for (int j = 0; j < c; j++)
    for (int i = 0; i < c; i++) wy[i] += W[(size_t)j * c + i] * y[j];
  v->assign(2 * (size_t)N, 0.0);
  for (int q = 0; q < N; q++) {
    const double *z = &mb.Z[(size_t)q * N], *R = maps[q].R;
    cplx fu = 0, fv = 0;
    for (int i = 0; i < nw; i++) fu += z[win0 + i] * wy[i], fv += z[win0 + i] * wy[nw + i];
    const cplx det = (R[0] - mu) * (R[3] - mu) - R[1] * R[2];
    const cplx cu = -((R[3] - mu) * fu - R[1] * fv) / det, cv = -(-R[2] * fu + (R[0] - mu) * fv) / det;
    for (int s = 0; s < N; s++) (*v)[s] += z[s] * cu, (*v)[N + s] += z[s] * cv;
  }
  double near = 0, disp = 0, dy = 0, ny = 0;
  for (int s = 0; s < N; s++) {
    const double a = std::norm((*v)[s]);
    disp += a;
    if (InEdgeRegion(s, iface, edge_sites)) near += a;
  }
  for (int i = 0; i < nw; i++) {
    dy += std::norm((*v)[win0 + i] - y[i]) + std::norm((*v)[N + win0 + i] - y[nw + i]);
    ny += std::norm(y[i]) + std::norm(y[nw + i]);
  }
  *edge = disp > 0 ? near / disp : 0;
  *residual = ny > 0 ? std::sqrt(dy / ny) : NAN;
}

} // namespace

namespace {

ModeBasis &ModeCache()
{
  static ModeBasis mb; // rank 0's modes of the last lattice seen
  return mb;
}

// Rank 0's part: the window of D = M - M_lin (a: M's region map, al: M_lin's),
// the modes, the scan, the leading root's whole vector (vec, 2N).
PetscErrorCode SolveOnRoot(const std::vector<double> &a, const std::vector<double> &al, const LocalizedRegion &reg, const symsplit::Scheme &sch,
                           PetscInt steps, PetscReal T, const std::vector<double> &kd, const std::vector<double> &kb, const FloquetOptions &fo,
                           const LocalizedOptions &lo, ExteriorResult *r, std::vector<cplx> *vec)
{
  const int n = (int)reg.Sites(), n2 = 2 * n;
  PetscFunctionBeginUser;
  double scale = 0;
  for (double x : a) scale = std::max(scale, std::abs(x));
  std::vector<double> site(n, 0.0); // the largest |D| entry in each site's rows and columns
  for (int j = 0; j < n2; j++)
    for (int i = 0; i < n2; i++) {
      const double d = std::abs(a[(size_t)j * n2 + i] - al[(size_t)j * n2 + i]);
      site[i % n] = std::max(site[i % n], d), site[j % n] = std::max(site[j % n], d);
    }
  int first = -1, last = -1;
  for (int s = 0; s < n; s++)
    if (site[s] > lo.exterior_tol * scale) first = first < 0 ? s : first, last = s;
  r->region_sites = n, r->floor = fo.tol / 10, r->resolved = true;
  if (first < 0) PetscFunctionReturn(0); // M = M_lin to the tolerance: every multiplier on the circle
  const bool left = reg.lo == 0 || first >= n / 4, right = reg.hi == (PetscInt)kd.size() - 1 || n - 1 - last >= n / 4;
  if (!left || !right) {
    std::ostringstream w;
    w << "M - M_lin reaches " << std::max(reg.iface - reg.lo - first, last - (reg.iface + 1 - reg.lo)) << " sites from the interface, beyond half of the "
      << n << "-site region (-floquet_loc_exterior_cells " << lo.exterior_cells << "): the orbit is not localized";
    r->resolved = false, r->why = w.str();
    PetscFunctionReturn(0);
  }
  const int nw = last - first + 1, c = 2 * nw;
  r->window_sites = nw;
  std::vector<double> W((size_t)c * c);
  for (int j = 0; j < c; j++)
    for (int i = 0; i < c; i++) {
      const int ri = (i < nw ? 0 : n) + first + i % nw, cj = (j < nw ? 0 : n) + first + j % nw;
      W[(size_t)j * c + i] = a[(size_t)cj * n2 + ri] - al[(size_t)cj * n2 + ri];
    }
  ModeBasis &mb = ModeCache();
  if (mb.kd != kd || mb.kb != kb) PetscCall(ComputeModes(kd, kb, &mb));
  std::vector<ModeMap> maps;
  for (int q = 0; q < mb.N(); q++) {
    maps.push_back(OscillatorMap(mb.w2[q], sch, steps, T / steps));
    const double half = 0.5 * (maps.back().R[0] + maps.back().R[3]);
    PetscCheck(std::abs(half) <= 1, PETSC_COMM_SELF, PETSC_ERR_USER,
               "-floquet_loc_exterior: linear mode %d (w^2 = %g) is not elliptic over the period (trace/2 = %.15g): the route needs every mode of K on the "
               "unit circle (-lattice_gamma0 > 0)",
               q, mb.w2[q], half);
  }
  Secular sec(mb, maps, reg.lo + first, nw, W);
  std::vector<cplx> roots, ev, y;
  // the arc: the far poles' linearization must place a root's first estimate within half a pole spacing of it
  // (the refinement follows the nearest local eigenvalue), so it shrinks with the spacing 2 pi / 2N
  const double arc = lo.exterior_arc > 0 ? lo.exterior_arc : std::min(0.1, 10 * M_PI / mb.N());
  r->arc = arc;
  PetscCall(Scan(sec, arc, r->floor, &roots, &r->centres));
  for (size_t k = 0; k < roots.size(); k++) {
    PetscCall(sec.Local(roots[k], arc, &ev, &y));
    size_t best = 0;
    for (size_t i = 1; i < ev.size(); i++)
      if (std::abs(ev[i] - roots[k]) < std::abs(ev[best] - roots[k])) best = i;
    std::vector<cplx> yk(y.begin() + best * c, y.begin() + (best + 1) * c), v;
    double edge, res;
    WholeVector(mb, maps, reg.lo + first, nw, W, roots[k], yk, reg.iface, fo.edge_sites, &v, &edge, &res);
    r->mu.push_back(roots[k]), r->edge.push_back(edge);
    if (k == 0) r->residual = res, *vec = std::move(v);
  }
  r->solves = sec.solves;
  PetscFunctionReturn(0);
}

// rank 0's result on every rank (vec too, 2N complex, when vr is wanted).
PetscErrorCode BroadcastResult(MPI_Comm comm, ExteriorResult *r, std::vector<cplx> *vec, PetscInt N)
{
  PetscMPIInt rank;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscInt head[6] = {r->resolved, r->window_sites, r->region_sites, (PetscInt)r->mu.size(), r->centres, r->solves};
  PetscCallMPI(MPI_Bcast(head, 6, MPIU_INT, 0, comm));
  char why[512] = "";
  if (rank == 0) std::snprintf(why, sizeof why, "%s", r->why.c_str());
  PetscCallMPI(MPI_Bcast(why, sizeof why, MPI_CHAR, 0, comm));
  const PetscInt k = head[3];
  std::vector<double> buf(3 * (size_t)k + 3 + (k > 0 ? 4 * (size_t)N : 0));
  if (rank == 0) {
    buf[0] = r->floor, buf[1] = r->residual, buf.back() = r->arc;
    for (PetscInt i = 0; i < k; i++) buf[2 + 3 * i] = r->mu[i].real(), buf[3 + 3 * i] = r->mu[i].imag(), buf[4 + 3 * i] = r->edge[i];
    for (PetscInt i = 0; k > 0 && i < 2 * N; i++) buf[2 + 3 * k + 2 * i] = (*vec)[i].real(), buf[3 + 3 * k + 2 * i] = (*vec)[i].imag();
  }
  PetscCallMPI(MPI_Bcast(buf.data(), (PetscMPIInt)buf.size(), MPI_DOUBLE, 0, comm));
  r->resolved = head[0], r->window_sites = head[1], r->region_sites = head[2], r->centres = head[4], r->solves = head[5], r->why = why;
  r->floor = buf[0], r->residual = buf[1], r->arc = buf.back();
  r->mu.resize(k), r->edge.resize(k), vec->resize(k > 0 ? 2 * N : 0);
  for (PetscInt i = 0; i < k; i++) r->mu[i] = {buf[2 + 3 * i], buf[3 + 3 * i]}, r->edge[i] = buf[4 + 3 * i];
  for (PetscInt i = 0; k > 0 && i < 2 * N; i++) (*vec)[i] = {buf[2 + 3 * k + 2 * i], buf[3 + 3 * k + 2 * i]};
  PetscFunctionReturn(0);
}

// The whole vector (natural layout) into state vectors vr, vi.
PetscErrorCode ScatterWhole(const Lattice &lat, const std::vector<cplx> &v, Vec vr, Vec vi)
{
  const PetscInt N = lat.N(), xs = lat.OwnedStart(), xm = lat.OwnedCount();
  PetscFunctionBeginUser;
  for (int part = 0; part < 2; part++) {
    Vec x = part ? vi : vr;
    if (!x) continue;
    PetscCall(VecZeroEntries(x));
    if (v.empty()) continue;
    PetscScalar *xa;
    PetscCall(VecGetArray(x, &xa));
    for (PetscInt i = xs; i < xs + xm; i++) {
      const cplx u = v[i], w = v[N + i];
      xa[i - xs] = part ? u.imag() : u.real(), xa[xm + i - xs] = part ? w.imag() : w.real();
    }
    PetscCall(VecRestoreArray(x, &xa));
  }
  PetscFunctionReturn(0);
}

} // namespace

PetscErrorCode FloquetExterior(PeriodicFlow &flow, Vec z0, PetscReal T, const FloquetOptions &fo, const LocalizedOptions &lo, ExteriorResult *r, Vec vr,
                               Vec vi)
{
  const Lattice &lat = flow.Lat();
  const MPI_Comm comm = lat.Comm();
  const PetscInt N = lat.N(), iface = lat.Params().InterfaceSite(), reach = 2 * lo.exterior_cells;
  PetscMPIInt rank;
  PetscLogEvent ev;
  PetscFunctionBeginUser;
  PetscCheck(N <= kExteriorMaxSites, comm, PETSC_ERR_USER,
             "-floquet_loc_exterior keeps the linear modes of the whole lattice on rank 0: N = %" PetscInt_FMT " sites is beyond %" PetscInt_FMT
             " (-lattice_cells at most 1499, or -floquet_loc_exterior 0)",
             N, kExteriorMaxSites);
  PetscCall(NamedLogEvent("FloquetExterior", &ev));
  PetscCall(PetscLogEventBegin(ev, 0, 0, 0, 0));
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  LocalizedRegion reg;
  reg.iface = iface, reg.lo = std::max<PetscInt>(0, iface - reach), reg.hi = std::min<PetscInt>(N - 1, iface + 1 + reach);
  reg.c.assign(reg.Sites(), 0.0);
  const PetscInt n = reg.Sites();
  std::vector<PetscReal> rec, lin(2 * (size_t)n, 0.0), kd, kb, a, al;
  const symsplit::Scheme *sch;
  PetscCall(RecordStiffness(flow, z0, T, reg, &rec, &sch));
  PetscCall(LinearStiffness(flow, &kd, &kb));
  for (PetscInt s = 0; s < n; s++) lin[s] = kd[reg.lo + s], lin[n + s] = reg.lo + s < N - 1 ? kb[reg.lo + s] : 0;
  PetscCall(RegionMapOnRoot(comm, reg, rec, 2 * n, *sch, flow.Steps(), T, &a));
  PetscCall(RegionMapOnRoot(comm, reg, lin, 0, *sch, flow.Steps(), T, &al));
  *r = ExteriorResult();
  std::vector<cplx> vec;
  PetscErrorCode code = 0;
  char msg[256] = "";
  if (rank == 0) PetscCall(CaptureError([&]() { return SolveOnRoot(a, al, reg, *sch, flow.Steps(), T, kd, kb, fo, lo, r, &vec); }, &code, msg, sizeof msg));
  PetscCallMPI(MPI_Bcast(&code, 1, MPI_INT, 0, comm));
  PetscCallMPI(MPI_Bcast(msg, sizeof msg, MPI_CHAR, 0, comm));
  PetscCall(FailTogether(comm, code, msg));
  PetscCall(BroadcastResult(comm, r, &vec, N));
  PetscCall(ScatterWhole(lat, vec, vr, vi));
  PetscCall(PetscLogEventEnd(ev, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

} // namespace nltopo
