#include "stability/floquet.hpp"
#include "core/errors.hpp"
#include "core/gather.hpp"
#include "core/lapack.hpp"
#include "core/log.hpp"
#include "core/option_table.hpp"
#include <algorithm>
#include <cmath>
#include <numeric>
#include <slepceps.h>

namespace nltopo {

static const auto &kFloquetTable =
    DeclareOptionTable<FloquetOptions>("floquet_", "Floquet multipliers (eigensolver options: -floquet_eps_*)", [](OptionTable<FloquetOptions> &t) {
      t.Real("tol", &FloquetOptions::tol, Open(0, 1), "A multiplier with |mu| > 1 + tol makes the orbit unstable")
          .Real("krein_tol", &FloquetOptions::krein_tol, Open(0, 1), "Krein signature 0 when |-i v^H J v| / |v|^2 is below this")
          .Int("edge_sites", &FloquetOptions::edge_sites, Closed(0, PETSC_MAX_INT), "Sites on each side of the interface cell that count as the edge region")
          .Real("edge_weight", &FloquetOptions::edge_weight, Open(0.5, 1),
                "Unstable eigenvector: edge (E-E) above this share of its displacement norm in the edge region, bulk (B-B) below 1 minus it, B-E between")
          .Why("edge above it and bulk below 1 minus it must not overlap")
          .Int("confirm_periods", &FloquetOptions::confirm_periods, Closed(1, 100000),
               "An unstable verdict is confirmed by integrating its eigenvector v this many periods k: |M^k v| = |mu|^k |v| (2k tangent integrations for a complex pair)")
          .Real("confirm_rtol", &FloquetOptions::confirm_rtol, Open(0, 1),
                "The growth rate per period measured over -floquet_confirm_periods must match ln|mu| to this relative tolerance, else the orbit is unresolved");
    });

PetscErrorCode FloquetOptionsFromOptions(MPI_Comm comm, FloquetOptions *o)
{
  PetscFunctionBeginUser;
  PetscCall(kFloquetTable.Read(comm, o));
  PetscFunctionReturn(0);
}

std::vector<PetscReal> RealPhase(const std::vector<std::complex<PetscReal>> &v)
{
  // e^{i phi} (a + i b) with the largest real part: tan 2 phi = -2 a.b / (|a|^2 - |b|^2).
  PetscReal ab = 0, aa = 0, bb = 0;
  for (const auto &x : v) ab += x.real() * x.imag(), aa += x.real() * x.real(), bb += x.imag() * x.imag();
  const PetscReal phi = -0.5 * std::atan2(2 * ab, aa - bb), c = std::cos(phi), s = std::sin(phi);
  std::vector<PetscReal> r(v.size());
  PetscReal norm = 0, big = 0;
  for (size_t i = 0; i < v.size(); i++) {
    r[i] = c * v[i].real() - s * v[i].imag();
    norm += r[i] * r[i];
    if (std::abs(r[i]) > std::abs(big)) big = r[i];
  }
  const PetscReal scale = (big < 0 ? -1 : 1) / (norm > 0 ? std::sqrt(norm) : 1);
  for (PetscReal &x : r) x *= scale;
  return r;
}

void KreinSums(const PetscScalar *a, const PetscScalar *b, PetscInt n, PetscReal sums[2])
{
  sums[0] = sums[1] = 0;
  for (PetscInt k = 0; k < n; k++) {
    sums[0] += 2 * (a[k] * b[n + k] - a[n + k] * b[k]);
    sums[1] += a[k] * a[k] + b[k] * b[k] + a[n + k] * a[n + k] + b[n + k] * b[n + k];
  }
}

PetscErrorCode GatherMonodromy(Mat S, PetscInt n, std::vector<PetscReal> *a)
{
  PetscMPIInt rank;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(PetscObjectComm((PetscObject)S), &rank));
  a->assign(rank == 0 ? (size_t)n * n : 0, 0.0);
  for (PetscInt c = 0; c < n; c++) {
    Vec col;
    std::vector<PetscReal> x;
    PetscCall(MatDenseGetColumnVecRead(S, c, &col));
    PetscCall(GatherVec(col, false, &x));
    PetscCall(MatDenseRestoreColumnVecRead(S, c, &col));
    if (rank == 0) std::copy(x.begin(), x.begin() + n, a->begin() + (size_t)c * n);
  }
  PetscFunctionReturn(0);
}

// H = Q^T M Q of a (n x n, column-major; a keeps the reflectors below the
// subdiagonal, tau their factors), H into h and its eigenvalues wr + i wi
// (QR on a copy). work: LAPACK's workspace, kept for the later calls.
PetscErrorCode HessenbergEigenvalues(int n, PetscReal *a, std::vector<PetscReal> &tau, std::vector<PetscReal> &h, std::vector<PetscReal> &wr,
                                     std::vector<PetscReal> &wi, std::vector<PetscReal> &work)
{
  const int one = 1;
  int info = 0, lwork = -1;
  PetscReal wq;
  PetscFunctionBeginUser;
  tau.assign(std::max(1, n - 1), 0.0), wr.assign(n, 0.0), wi.assign(n, 0.0);
  dgehrd_(&n, &one, &n, a, &n, tau.data(), &wq, &lwork, &info);
  work.assign((size_t)wq + 1, 0.0);
  lwork = (int)work.size();
  dgehrd_(&n, &one, &n, a, &n, tau.data(), work.data(), &lwork, &info);
  PetscCheck(info == 0, PETSC_COMM_SELF, PETSC_ERR_LIB, "Floquet (dense): LAPACK dgehrd failed, info %d (2N = %d)", info, n);
  h.assign((size_t)n * n, 0.0);
  for (int c = 0; c < n; c++)
    for (int i = 0; i <= std::min(c + 1, n - 1); i++) h[(size_t)c * n + i] = a[(size_t)c * n + i];
  std::vector<PetscReal> hq = h; // eigenvalues only (QR overwrites its copy)
  lwork = -1;
  dhseqr_("E", "N", &n, &one, &n, hq.data(), &n, wr.data(), wi.data(), NULL, &one, &wq, &lwork, &info, 1, 1);
  work.resize(std::max<size_t>(work.size(), (size_t)wq + 1));
  lwork = (int)work.size();
  dhseqr_("E", "N", &n, &one, &n, hq.data(), &n, wr.data(), wi.data(), NULL, &one, work.data(), &lwork, &info, 1, 1);
  PetscCheck(info == 0, PETSC_COMM_SELF, PETSC_ERR_LIB, "Floquet (dense): LAPACK dhseqr failed, info %d (2N = %d)", info, n);
  PetscFunctionReturn(0);
}

PetscErrorCode MonodromyMultipliers(Mat S, PetscInt n, std::vector<std::complex<PetscReal>> *mu)
{
  MPI_Comm comm = PetscObjectComm((PetscObject)S);
  PetscMPIInt rank;
  std::vector<PetscReal> a, tau, h, wr(n), wi(n), work;
  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(Log().floquet_eigenvalues, 0, 0, 0, 0));
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCall(GatherMonodromy(S, n, &a));
  PetscErrorCode ierr = 0;
  char msg[256] = "";
  if (rank == 0) PetscCall(CaptureError([&]() { return HessenbergEigenvalues((int)n, a.data(), tau, h, wr, wi, work); }, &ierr, msg, sizeof msg));
  PetscCall(FailTogether(comm, ierr, msg)); // (rank 0's LAPACK failure: every rank, not a wait in the broadcast)
  PetscCallMPI(MPI_Bcast(wr.data(), (PetscMPIInt)n, MPIU_REAL, 0, comm));
  PetscCallMPI(MPI_Bcast(wi.data(), (PetscMPIInt)n, MPIU_REAL, 0, comm));
  mu->resize(n);
  for (PetscInt i = 0; i < n; i++) (*mu)[i] = {wr[i], wi[i]};
  PetscCall(PetscLogEventEnd(Log().floquet_eigenvalues, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

namespace {

// Sums over the owned state entries of x (u part first, then v): -i v^H J v / |v|^2 for v = xr + i xi,
// which is 2 (xr_u . xi_v - xr_v . xi_u) / |v|^2, the edge share of the displacement norm, and
// the participation ratio over sites of the displacement (DisplacementParticipation).
PetscErrorCode KreinAndEdge(const Lattice &lat, Vec xr, Vec xi, PetscInt e, PetscReal *kappa, PetscReal *edge, PetscReal *participation)
{
  const PetscScalar *a, *b;
  const PetscInt xm = lat.OwnedCount(), xs = lat.OwnedStart();
  const bool iface = lat.Params().layout == Layout::Interface;
  const PetscInt m = lat.Params().InterfaceSite();
  PetscReal loc[5] = {0, 0, 0, 0, 0}, g[5];
  PetscFunctionBeginUser;
  PetscCall(VecGetArrayRead(xr, &a));
  PetscCall(VecGetArrayRead(xi, &b));
  KreinSums(a, b, xm, loc);
  for (PetscInt k = 0; k < xm; k++) {
    const PetscInt i = xs + k;
    const PetscReal d = a[k] * a[k] + b[k] * b[k];
    loc[2] += d;
    loc[4] += d * d;
    if (iface && InEdgeRegion(i, m, e)) loc[3] += d;
  }
  PetscCall(VecRestoreArrayRead(xi, &b));
  PetscCall(VecRestoreArrayRead(xr, &a));
  PetscCall(MPIU_Allreduce(loc, g, 5, MPIU_REAL, MPIU_SUM, lat.Comm()));
  *kappa = g[1] > 0 ? g[0] / g[1] : 0;
  *edge = g[2] > 0 ? g[3] / g[2] : 0;
  *participation = DisplacementParticipation(g[2], g[4]);
  PetscFunctionReturn(0);
}

// |det M - 1| by LU with partial pivoting in long double on rank 0 (M is
// 2N x 2N dense, small enough to gather where the dense route is used).
PetscErrorCode DeterminantError(Mat M, PetscInt n, PetscReal *err)
{
  PetscMPIInt rank;
  std::vector<long double> a;
  std::vector<PetscReal> cm;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(PetscObjectComm((PetscObject)M), &rank));
  PetscCall(GatherMonodromy(M, n, &cm));
  if (rank == 0) { // row-major in long double
    a.resize((size_t)n * n);
    for (PetscInt c = 0; c < n; c++)
      for (PetscInt r = 0; r < n; r++) a[(size_t)r * n + c] = cm[(size_t)c * n + r];
  }
  long double det = 1;
  if (rank == 0) {
    for (PetscInt k = 0; k < n; k++) {
      PetscInt p = k;
      for (PetscInt i = k + 1; i < n; i++)
        if (std::fabs(a[(size_t)i * n + k]) > std::fabs(a[(size_t)p * n + k])) p = i;
      if (p != k) {
        for (PetscInt j = 0; j < n; j++) std::swap(a[(size_t)p * n + j], a[(size_t)k * n + j]);
        det = -det;
      }
      const long double piv = a[(size_t)k * n + k];
      det *= piv;
      if (piv == 0) break;
      for (PetscInt i = k + 1; i < n; i++) {
        const long double l = a[(size_t)i * n + k] / piv;
        for (PetscInt j = k + 1; j < n; j++) a[(size_t)i * n + j] -= l * a[(size_t)k * n + j];
      }
    }
  }
  PetscReal e = (PetscReal)std::fabs(det - 1); // a row permutation of the state layout does not change det
  PetscCallMPI(MPI_Bcast(&e, 1, MPIU_REAL, 0, PetscObjectComm((PetscObject)M)));
  *err = e;
  PetscFunctionReturn(0);
}

// The eigenvector of eigenpair i of eps as a complex natural-order vector of unit norm, on every rank.
PetscErrorCode NaturalEigenvector(const Lattice &lat, EPS eps, PetscInt i, Vec xr, Vec xi, std::vector<std::complex<PetscReal>> *v)
{
  PetscScalar kr, ki;
  std::vector<PetscReal> a, b;
  PetscFunctionBeginUser;
  PetscCall(EPSGetEigenpair(eps, i, &kr, &ki, xr, xi));
  if (ki == 0) PetscCall(VecZeroEntries(xi));
  PetscCall(GatherVec(xr, true, &a));
  PetscCall(GatherVec(xi, true, &b));
  const PetscInt N = lat.N();
  v->assign(2 * N, 0);
  PetscReal norm = 0;
  for (PetscInt s = 0; s < N; s++)
    for (PetscInt part = 0; part < 2; part++) {
      const PetscInt j = part ? lat.StateIndexV(s) : lat.StateIndexU(s);
      (*v)[part * N + s] = {a[j], b[j]};
      norm += a[j] * a[j] + b[j] * b[j];
    }
  for (auto &x : *v) x /= norm > 0 ? std::sqrt(norm) : 1;
  PetscFunctionReturn(0);
}

// The eigenvector of the multiplier nearest target (see floquet.hpp).
PetscErrorCode CriticalVector(const Lattice &lat, EPS eps, const std::vector<PetscReal> &re, const std::vector<PetscReal> &im, const PetscReal *target, Vec xr,
                              Vec xi, std::vector<PetscReal> *vec)
{
  std::vector<std::complex<PetscReal>> v;
  PetscFunctionBeginUser;
  PetscCheck(target, lat.Comm(), PETSC_ERR_ARG_NULL, "FloquetAnalysis: an eigenvector needs a target multiplier");
  size_t k = 0;
  for (size_t i = 1; i < re.size(); i++)
    if (std::hypot(re[i] - target[0], im[i] - target[1]) < std::hypot(re[k] - target[0], im[k] - target[1])) k = i;
  PetscCall(NaturalEigenvector(lat, eps, (PetscInt)k, xr, xi, &v));
  *vec = RealPhase(v);
  PetscFunctionReturn(0);
}

} // namespace

PetscErrorCode EigenvectorShares(const Lattice &lat, Vec xr, Vec xi, PetscInt e, PetscReal *kappa, PetscReal *edge)
{
  PetscReal participation;
  PetscFunctionBeginUser;
  PetscCall(KreinAndEdge(lat, xr, xi, e, kappa, edge, &participation));
  PetscFunctionReturn(0);
}

PetscInt LeadingIndex(const std::vector<std::complex<PetscReal>> &mu, PetscReal tol)
{
  const PetscInt n = (PetscInt)mu.size();
  std::vector<PetscInt> idx(n);
  std::iota(idx.begin(), idx.end(), 0);
  std::sort(idx.begin(), idx.end(), [&](PetscInt x, PetscInt y) { return std::abs(mu[x] - 1.0) < std::abs(mu[y] - 1.0); });
  idx.erase(idx.begin(), idx.begin() + std::min<PetscInt>(2, n)); // the trivial pair
  PetscInt big = -1, circle = -1;
  for (PetscInt i : idx) {
    if (big < 0 || std::abs(mu[i]) > std::abs(mu[big])) big = i;
    if (mu[i].imag() >= 0 && std::abs(mu[i]) >= 1 - tol && (circle < 0 || std::abs(mu[i].real()) > std::abs(mu[circle].real()))) circle = i;
  }
  if (big >= 0 && std::abs(mu[big]) > 1 + tol) return big;
  return circle >= 0 ? circle : big;
}

PetscErrorCode FloquetAnalysis(const Lattice &lat, Mat S, const FloquetOptions &o, FloquetResult *r, const PetscReal *target, std::vector<PetscReal> *vec,
                               PetscReal circle_vectors, Vec worst_re, Vec worst_im)
{
  const PetscInt n = 2 * lat.N(), nl = 2 * lat.OwnedCount();
  OwnedMat M;
  OwnedEPS eps;
  OwnedVec xr, xi;
  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(Log().floquet, 0, 0, 0, 0));
  *r = FloquetResult();
  // M = the first 2N columns of S.
  PetscCall(MatCreateDense(lat.Comm(), nl, nl, n, n, NULL, M.out()));
  {
    const PetscScalar *s;
    PetscScalar *mm;
    PetscInt lds, ldm;
    PetscCall(MatDenseGetLDA(S, &lds));
    PetscCall(MatDenseGetLDA(M, &ldm));
    PetscCall(MatDenseGetArrayRead(S, &s));
    PetscCall(MatDenseGetArrayWrite(M, &mm));
    for (PetscInt c = 0; c < n; c++)
      for (PetscInt k = 0; k < nl; k++) mm[k + c * ldm] = s[k + c * lds];
    PetscCall(MatDenseRestoreArrayWrite(M, &mm));
    PetscCall(MatDenseRestoreArrayRead(S, &s));
  }
  PetscCall(MatAssemblyBegin(M, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(M, MAT_FINAL_ASSEMBLY));
  PetscCall(DeterminantError(M, n, &r->det_error));
  PetscCall(EPSCreate(lat.Comm(), eps.out()));
  PetscCall(EPSSetOptionsPrefix(eps, "floquet_"));
  PetscCall(EPSSetOperators(eps, M, NULL));
  PetscCall(EPSSetProblemType(eps, EPS_NHEP));
  PetscCall(EPSSetType(eps, EPSLAPACK));
  PetscCall(EPSSetWhichEigenpairs(eps, EPS_LARGEST_MAGNITUDE));
  PetscCall(EPSSetDimensions(eps, n, PETSC_DEFAULT, PETSC_DEFAULT));
  PetscCall(EPSSetFromOptions(eps));
  PetscCall(EPSSolve(eps));
  PetscInt nconv;
  PetscCall(EPSGetConverged(eps, &nconv));
  PetscCheck(nconv >= n, lat.Comm(), PETSC_ERR_NOT_CONVERGED, "Floquet: only %" PetscInt_FMT " of %" PetscInt_FMT " multipliers converged", nconv, n);
  PetscCall(MatCreateVecs(M, xr.out(), NULL));
  PetscCall(VecDuplicate(xr, xi.out()));
  std::vector<PetscReal> re(n), im(n), kap(n), edge(n), part(n);
  for (PetscInt i = 0; i < n; i++) {
    PetscScalar kr, ki;
    PetscCall(EPSGetEigenpair(eps, i, &kr, &ki, xr, xi));
    re[i] = kr;
    im[i] = ki;
    PetscCall(KreinAndEdge(lat, xr, xi, o.edge_sites, &kap[i], &edge[i], &part[i]));
  }
  {
    std::vector<std::complex<PetscReal>> mu(n);
    for (PetscInt i = 0; i < n; i++) mu[i] = {re[i], im[i]};
    const PetscInt lead = LeadingIndex(mu, o.tol);
    if (lead >= 0) r->leading_participation = part[lead], r->leading_edge = edge[lead];
  }
  std::vector<PetscInt> order(n);
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](PetscInt a, PetscInt b) {
    const PetscReal ta = std::atan2(im[a], re[a]), tb = std::atan2(im[b], re[b]);
    if (std::abs(ta - tb) > 1e-12) return ta < tb;
    return std::hypot(re[a], im[a]) < std::hypot(re[b], im[b]);
  });
  PetscInt worst = -1;
  for (PetscInt i : order) {
    const PetscReal mod = std::hypot(re[i], im[i]);
    r->re.push_back(re[i]);
    r->im.push_back(im[i]);
    r->krein.push_back(KreinSign(o, kap[i]));
    r->edge.push_back(edge[i]);
    r->kappa.push_back(kap[i]);
    if (std::hypot(re[i] - 1, im[i]) < 1e-4) r->trivial++;
    if (mod > r->max_modulus) {
      r->max_modulus = mod;
      worst = i;
    }
  }
  r->stable = r->max_modulus <= 1 + o.tol;
  if (worst >= 0) r->worst_re = re[worst], r->worst_im = std::abs(im[worst]);
  if (!r->stable) { // the kind, from the localisation of the most unstable eigenvector
    const PetscReal w = edge[worst];
    r->instability = Localisation(o, w);
    if (worst_re && worst_im) {
      PetscScalar kr, ki;
      PetscCall(EPSGetEigenpair(eps, worst, &kr, &ki, worst_re, worst_im));
      if (ki == 0) PetscCall(VecZeroEntries(worst_im));
    }
  }
  if (vec) PetscCall(CriticalVector(lat, eps, re, im, target, xr, xi, vec));
  if (circle_vectors >= 0) {
    r->vectors.assign(n, {});
    for (PetscInt k = 0; k < n; k++) {
      const PetscInt i = order[k];
      if (im[i] > 0 && std::abs(std::hypot(re[i], im[i]) - 1) <= o.tol && edge[i] >= circle_vectors)
        PetscCall(NaturalEigenvector(lat, eps, i, xr, xi, &r->vectors[k]));
    }
  }
  PetscCall(PetscLogEventEnd(Log().floquet, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

} // namespace nltopo
