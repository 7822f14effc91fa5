#include "stability/floquet_mf.hpp"
#include "core/lapack.hpp"
#include "core/errors.hpp"
#include "core/memory_guard.hpp"
#include "core/option_table.hpp"
#include "core/log.hpp"
#include <algorithm>
#include <cmath>
#include <complex>
#include <numeric>
#include <slepceps.h>

namespace nltopo {

static PetscErrorCode ShellMult(Mat M, Vec x, Vec y)
{
  MonodromyShell *s;
  PetscFunctionBeginUser;
  PetscCall(MatShellGetContext(M, &s));
  PetscCall(s->Mult(x, y));
  PetscFunctionReturn(0);
}

static const char *const kWhichNames[] = {"largest", "critical", "localized"};

static const auto &kFloquetMfTable = DeclareOptionTable<FloquetMfOptions>(
    "floquet_mf_", "Matrix-free Floquet multipliers (eigensolver options: -floquet_mf_eps_*)", [](OptionTable<FloquetMfOptions> &t) {
      t.Int("nev", &FloquetMfOptions::nev, Closed(1, 1000), "Leading multiplier pairs wanted per orbit (critical: one per distinct b)")
          .Enum("which", &FloquetMfOptions::which, kWhichNames, 3,
                "largest: largest modulus (Krylov-Schur on M); critical: nearest the critical points +-1 or off the unit circle "
                "(Krylov-Schur on (M + M^-1)/2); localized: the multipliers of perturbations localized at the interface, the tangent "
                "equations damped outside a window (-floquet_loc_*), all of them from a dense matrix of the window and its absorbing layer")
          .Real("circle_tol", &FloquetMfOptions::circle_tol, Open(0, 1),
                "critical: b = (mu + 1/mu)/2 within this of [-1, 1] is on the unit circle (|mu| - 1 is resolved down to sqrt(2 circle_tol))")
          .Int("dense_max", &FloquetMfOptions::dense_max, Closed(0, 20000),
               "Orbits with 2N at most this take the dense monodromy (all 2N multipliers: the only route that can call an orbit stable; "
               "its cost grows as (2N)^3); 0: always matrix-free")
          .Bool("deflate", &FloquetMfOptions::deflate,
                "Deflate the trivial pair mu = 1 (span of f(z0) and the family tangent) so that the nev multipliers are nontrivial");
    });

PetscErrorCode FloquetMfOptionsFromOptions(MPI_Comm comm, FloquetMfOptions *o)
{
  PetscFunctionBeginUser;
  PetscCall(kFloquetMfTable.Read(comm, o));
  PetscCall(LocalizedOptionsFromOptions(comm, &o->loc));
  PetscFunctionReturn(0);
}

PetscInt MatrixFreeVerdict(const LeadingMultipliers &r, PetscReal tol)
{
  for (size_t k = 0; k < r.re.size(); k++) {
    const PetscReal res = k < r.resolution.size() && std::isfinite(r.resolution[k]) ? r.resolution[k] : 0;
    if (std::hypot(r.re[k], r.im[k]) > 1 + std::max(tol, res)) return kUnstable; // NaN compares false
  }
  return kUndecided;
}


namespace {

// The nev leading pairs of the multipliers mu (indices, as DenseLeadingPairs
// orders them) and the largest nontrivial |mu|.
std::vector<int> PickLeadingPairs(const std::vector<std::complex<PetscReal>> &mu, PetscInt nev, PetscReal tol, PetscReal *max_modulus)
{
  const int n = (int)mu.size();
  std::vector<int> idx(n);
  std::iota(idx.begin(), idx.end(), 0);
  // the trivial pair: the two multipliers nearest 1
  std::sort(idx.begin(), idx.end(), [&](int x, int y) { return std::abs(mu[x] - 1.0) < std::abs(mu[y] - 1.0); });
  idx.erase(idx.begin(), idx.begin() + std::min(2, n));
  *max_modulus = 0;
  for (int i : idx) *max_modulus = std::max(*max_modulus, std::abs(mu[i]));
  // One member of each pair: the upper half plane (or real) member with
  // |mu| >= 1. Off the circle (beyond tol) that is the outer member; within
  // tol of it, a pair that is off the circle by more than rounding (1e-9) has
  // both mu and 1/conj(mu) in the upper half plane: the inner one is left out
  // when its partner is there (found within a tenth of its distance from the
  // circle). Distinct pairs with equal multipliers (a degenerate or colliding
  // pair) are both kept.
  std::vector<int> cand;
  for (int i : idx) {
    const PetscReal m = std::abs(mu[i]);
    if (mu[i].imag() < 0 || m < 1 - tol) continue;
    if (m < 1 - 1e-9) {
      const std::complex<PetscReal> partner = 1.0 / std::conj(mu[i]);
      bool outer = false;
      for (int j : idx)
        outer = outer || (j != i && mu[j].imag() >= 0 && std::abs(mu[j]) > 1 + 1e-9 && std::abs(mu[j] - partner) <= std::max(1e-7, 0.1 * (1 - m)));
      if (outer) continue;
    }
    cand.push_back(i);
  }
  std::stable_sort(cand.begin(), cand.end(), [&](int x, int y) {
    const bool ox = std::abs(mu[x]) > 1 + tol, oy = std::abs(mu[y]) > 1 + tol;
    if (ox != oy) return ox;
    return ox ? std::abs(mu[x]) > std::abs(mu[y]) : std::abs(mu[x].real()) > std::abs(mu[y].real());
  });
  // A real pair on the circle at +-1 is a double root (a Jordan block that
  // rounding may leave as two reals within 1e-6): keep one.
  std::vector<int> pick;
  for (int i : cand) {
    if ((PetscInt)pick.size() >= nev) break;
    const int p = pick.empty() ? -1 : pick.back();
    if (p >= 0 && std::abs(mu[i].imag()) <= 1e-7 && std::abs(mu[p].imag()) <= 1e-7 && std::abs(mu[i] - mu[p]) <= 1e-6) continue;
    pick.push_back(i);
  }
  return pick;
}

// The eigenvectors of the picked eigenvalues of H (h; a and tau: its
// reflectors): inverse iteration on H, then Q applied. vr: their columns in
// the order of the eigenvalues (a complex one: real and imaginary parts),
// first[i]: eigenvalue i's first column, ifr: each column's dhsein failure flag.
PetscErrorCode PairVectors(int n, const PetscReal *a, const std::vector<PetscReal> &tau, const std::vector<PetscReal> &h, const std::vector<PetscReal> &wr,
                           const std::vector<PetscReal> &wi, const std::vector<int> &pick, std::vector<PetscReal> &work, std::vector<PetscReal> *vr,
                           std::vector<int> *first, std::vector<int> *ifr)
{
  const int one = 1;
  int info = 0, lwork = -1;
  PetscReal wq;
  PetscFunctionBeginUser;
  std::vector<int> select(n, 0);
  int cols = 0;
  for (int i : pick) select[i] = 1, cols += wi[i] > 0 ? 2 : 1;
  vr->assign((size_t)n * std::max(cols, 1), 0.0);
  std::vector<PetscReal> hw((size_t)(n + 2) * n);
  std::vector<int> ifl(std::max(cols, 1));
  ifr->assign(std::max(cols, 1), 0);
  int got = 0;
  if (cols) {
    std::vector<PetscReal> wr2 = wr;
    dhsein_("R", "Q", "N", select.data(), &n, h.data(), &n, wr2.data(), wi.data(), NULL, &one, vr->data(), &n, &cols, &got, hw.data(), ifl.data(), ifr->data(),
            &info, 1, 1, 1);
    PetscCheck(info >= 0 && got == cols, PETSC_COMM_SELF, PETSC_ERR_LIB, "Floquet (dense): LAPACK dhsein failed, info %d, %d of %d columns (2N = %d)", info,
               got, cols, n);
    lwork = -1;
    dormhr_("L", "N", &n, &cols, &one, &n, a, &n, tau.data(), vr->data(), &n, &wq, &lwork, &info, 1, 1);
    work.resize(std::max<size_t>(work.size(), (size_t)wq + 1));
    lwork = (int)work.size();
    dormhr_("L", "N", &n, &cols, &one, &n, a, &n, tau.data(), vr->data(), &n, work.data(), &lwork, &info, 1, 1);
    PetscCheck(info == 0, PETSC_COMM_SELF, PETSC_ERR_LIB, "Floquet (dense): LAPACK dormhr failed, info %d (2N = %d)", info, n);
  }
  first->assign(n, -1);
  for (int i = 0, c = 0; i < n; i++)
    if (select[i]) (*first)[i] = c, c += wi[i] > 0 ? 2 : 1;
  PetscFunctionReturn(0);
}

// The Krein signature and edge share of the eigenvector xr + i xi (xi null:
// real), in PETSc state order (uidx, vidx: the rows of u_s, v_s).
void PairSignature(const PetscReal *xr, const PetscReal *xi, const FloquetOptions &o, const std::vector<PetscInt> &uidx, const std::vector<PetscInt> &vidx,
                   PetscInt iface, PetscInt *krein, PetscReal *edge)
{
  const PetscInt N = (PetscInt)uidx.size();
  std::vector<PetscScalar> re(2 * N), im(2 * N, 0.0);
  PetscReal disp = 0, near = 0;
  for (PetscInt s = 0; s < N; s++) {
    re[s] = xr[uidx[s]], re[N + s] = xr[vidx[s]];
    if (xi) im[s] = xi[uidx[s]], im[N + s] = xi[vidx[s]];
    const PetscReal d = re[s] * re[s] + im[s] * im[s];
    disp += d;
    if (iface >= 0 && InEdgeRegion(s, iface, o.edge_sites)) near += d;
  }
  PetscReal sums[2];
  KreinSums(re.data(), im.data(), N, sums);
  const PetscReal kappa = sums[1] > 0 ? sums[0] / sums[1] : 0;
  *krein = KreinSign(o, kappa);
  *edge = disp > 0 ? near / disp : 0;
}

// The participation ratio over sites of the eigenvector's displacement
// (xr + i xi, xi the next column when complex; floquet.hpp DisplacementParticipation).
PetscReal PairParticipation(const PetscReal *xr, bool complex, PetscInt n, const std::vector<PetscInt> &uidx)
{
  PetscReal disp = 0, disp2 = 0;
  for (PetscInt row : uidx) {
    const PetscReal a = xr[row], b = complex ? xr[n + row] : 0, d = a * a + b * b;
    disp += d, disp2 += d * d;
  }
  return DisplacementParticipation(disp, disp2);
}

} // namespace

PetscErrorCode DenseLeadingPairs(PetscInt n_, PetscReal *a, PetscInt nev, const FloquetOptions &o, const std::vector<PetscInt> &uidx,
                                 const std::vector<PetscInt> &vidx, PetscInt iface, LeadingPairs *out)
{
  const int n = (int)n_;
  std::vector<PetscReal> tau, h, wr, wi, work, vr;
  std::vector<int> first, ifr;
  PetscFunctionBeginUser;
  PetscCall(HessenbergEigenvalues(n, a, tau, h, wr, wi, work));
  std::vector<std::complex<PetscReal>> mu(n);
  for (int i = 0; i < n; i++) mu[i] = {wr[i], wi[i]};
  const std::vector<int> pick = PickLeadingPairs(mu, nev, o.tol, &out->max_modulus);
  PetscCall(PairVectors(n, a, tau, h, wr, wi, pick, work, &vr, &first, &ifr));
  out->mu.clear(), out->krein.clear(), out->edge.clear();
  for (int i : pick) {
    PetscInt krein = 0;
    PetscReal edge = NAN;
    if (ifr[first[i]] != 0) // inverse iteration did not converge (dhsein info > 0): no signature, no class
      PetscCall(PetscInfo(NULL, "Floquet (dense): no eigenvector for the multiplier %g%+gi (dhsein)\n", (double)mu[i].real(), (double)mu[i].imag()));
    else {
      const PetscReal *xr = &vr[(size_t)first[i] * n];
      PairSignature(xr, mu[i].imag() > 0 ? xr + n : nullptr, o, uidx, vidx, iface, &krein, &edge);
    }
    out->mu.push_back(mu[i]), out->krein.push_back(krein), out->edge.push_back(edge);
    if (out->mu.size() == 1 && ifr[first[i]] == 0)
      out->leading_edge = edge, out->leading_participation = PairParticipation(&vr[(size_t)first[i] * n], mu[i].imag() > 0, n, uidx);
  }
  out->instability = 0;
  out->lead_re.clear(), out->lead_im.clear();
  if (out->max_modulus > 1 + o.tol && !out->edge.empty()) { // the leading multiplier is then the most unstable
    const PetscReal w = out->edge[0];
    out->instability = std::isfinite(w) ? Localisation(o, w) : -1;
    if (std::isfinite(w)) {
      const PetscReal *xr = &vr[(size_t)first[pick[0]] * n];
      out->lead_re.assign(xr, xr + n);
      out->lead_im.assign(n, 0.0);
      if (mu[pick[0]].imag() > 0) out->lead_im.assign(xr + n, xr + 2 * n);
    }
  }
  PetscFunctionReturn(0);
}

PetscErrorCode CheckDenseMonodromyMemory(MPI_Comm comm, PetscInt N, const FloquetMfOptions &o)
{
  PetscMPIInt rank;
  const double n = 2.0 * (double)N;
  PetscFunctionBeginUser;
  if (n > o.dense_max) PetscFunctionReturn(0);
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  // rank 0 holds M, its Hessenberg form and a copy for the QR
  PetscCall(CheckMemory(comm, rank == 0 ? 3.0 * 8.0 * n * n : 0.0, "the dense monodromy's eigenvalues (2N <= -floquet_mf_dense_max)"));
  PetscFunctionReturn(0);
}

// Rank 0's vector x (global state order; empty: zero) into the distributed v.
static PetscErrorCode ScatterFromRoot(const std::vector<PetscReal> &x, Vec v)
{
  PetscFunctionBeginUser;
  PetscCall(VecZeroEntries(v));
  if (!x.empty()) {
    std::vector<PetscInt> idx(x.size());
    std::iota(idx.begin(), idx.end(), 0);
    PetscCall(VecSetValues(v, (PetscInt)x.size(), idx.data(), x.data(), INSERT_VALUES));
  }
  PetscCall(VecAssemblyBegin(v));
  PetscCall(VecAssemblyEnd(v));
  PetscFunctionReturn(0);
}

PetscErrorCode FloquetLeadingDense(const Lattice &lat, Mat S, PetscInt nev, const FloquetOptions &o, LeadingMultipliers *r, Vec lead_re, Vec lead_im)
{
  const PetscInt n = 2 * lat.N(), N = lat.N();
  const MPI_Comm comm = lat.Comm();
  PetscMPIInt rank;
  std::vector<PetscReal> a;
  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(Log().floquet, 0, 0, 0, 0));
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  // rank 0 holds M, its Hessenberg form and a copy for the QR
  PetscCall(CheckMemory(comm, rank == 0 ? 3.0 * 8.0 * (double)n * (double)n : 0.0, "the dense monodromy's eigenvalues (2N <= -floquet_mf_dense_max)"));
  PetscCall(GatherMonodromy(S, n, &a));
  // rank 0's answer, broadcast: per pair re, im, krein; then max |mu|, instability.
  // Its LAPACK work fails on rank 0 alone: the error is made collective.
  std::vector<PetscReal> out(3 * nev + 4, NAN); // then the leading vector's participation ratio and edge share
  PetscErrorCode code = 0;
  char msg[256] = "";
  LeadingPairs lead;
  if (rank == 0) {
    std::vector<PetscInt> u(N), v(N); // natural site -> PETSc state index
    for (PetscInt s = 0; s < N; s++) u[s] = lat.StateIndexU(s), v[s] = lat.StateIndexV(s);
    const PetscInt iface = lat.Params().layout == Layout::Interface ? lat.Params().InterfaceSite() : -1;
    PetscCall(CaptureError([&]() { return DenseLeadingPairs(n, a.data(), nev, o, u, v, iface, &lead); }, &code, msg, sizeof msg));
    for (PetscInt k = 0; k < (PetscInt)lead.mu.size(); k++) out[3 * k] = lead.mu[k].real(), out[3 * k + 1] = lead.mu[k].imag(), out[3 * k + 2] = lead.krein[k];
    out[3 * nev] = lead.max_modulus, out[3 * nev + 1] = lead.instability;
    out[3 * nev + 2] = lead.leading_participation, out[3 * nev + 3] = lead.leading_edge;
  }
  PetscCall(FailTogether(comm, code, msg));
  PetscCallMPI(MPI_Bcast(out.data(), (PetscMPIInt)out.size(), MPIU_REAL, 0, comm));
  r->re.assign(nev, NAN), r->im.assign(nev, NAN), r->krein.assign(nev, 0);
  r->converged = 0;
  for (PetscInt k = 0; k < nev; k++) {
    r->re[k] = out[3 * k], r->im[k] = out[3 * k + 1];
    if (std::isfinite(out[3 * k])) r->converged++, r->krein[k] = (PetscInt)out[3 * k + 2];
  }
  r->max_modulus = out[3 * nev];
  r->instability = (PetscInt)out[3 * nev + 1];
  r->leading_participation = out[3 * nev + 2], r->leading_edge = out[3 * nev + 3];
  r->products = n; // the 2N tangent columns of the monodromy
  r->verdict = r->max_modulus <= 1 + o.tol ? kStable : kUnstable;
  if (lead_re && lead_im) {
    PetscCall(ScatterFromRoot(lead.lead_re, lead_re));
    PetscCall(ScatterFromRoot(lead.lead_im, lead_im));
  }
  PetscCall(PetscLogEventEnd(Log().floquet, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

// x -> R x = (u, -v): negate the owned v half of a state vector.
static PetscErrorCode FlipMomentum(const Lattice &lat, Vec x)
{
  PetscScalar *a;
  const PetscInt m = lat.OwnedCount();
  PetscFunctionBeginUser;
  PetscCall(VecGetArray(x, &a));
  for (PetscInt k = m; k < 2 * m; k++) a[k] = -a[k];
  PetscCall(VecRestoreArray(x, &a));
  PetscFunctionReturn(0);
}

PetscErrorCode MonodromyShell::Create(PeriodicFlow &flow, Vec z0, PetscReal T, PetscReal beta, bool symmetrized)
{
  PetscInt n, nloc;
  PetscFunctionBeginUser;
  flow_ = &flow, z0_ = z0, T_ = T, beta_ = beta, symmetrized_ = symmetrized;
  PetscCall(VecGetSize(z0, &n));
  PetscCall(VecGetLocalSize(z0, &nloc));
  PetscCall(VecDuplicate(z0, zT_.out()));
  if (symmetrized) {
    for (OwnedVec *v : {&zr_, &xr_, &yr_}) PetscCall(VecDuplicate(z0, v->out()));
    PetscCall(VecCopy(z0, zr_));
    PetscCall(FlipMomentum(flow.Lat(), zr_));
  }
  PetscCall(MatCreateShell(PetscObjectComm((PetscObject)z0), nloc, nloc, n, n, this, M_.out()));
  PetscCall(MatShellSetOperation(M_, MATOP_MULT, (void (*)(void))ShellMult));
  PetscFunctionReturn(0);
}

PetscErrorCode MonodromyShell::Mult(Vec x, Vec y)
{
  PetscFunctionBeginUser;
  PetscCall(flow_->IntegrateWithTangent(z0_, T_, beta_, x, 0.0, 0.0, zT_, y));
  products_++;
  if (symmetrized_) { // y = (M x + R M(R z0) R x) / 2; beta = 0 keeps the flow reversible
    PetscCall(VecCopy(x, xr_));
    PetscCall(FlipMomentum(flow_->Lat(), xr_));
    PetscCall(flow_->IntegrateWithTangent(zr_, T_, 0.0, xr_, 0.0, 0.0, zT_, yr_));
    PetscCall(FlipMomentum(flow_->Lat(), yr_));
    PetscCall(VecAXPBY(y, 0.5, 0.5, yr_));
    products_++;
  }
  PetscFunctionReturn(0);
}

// One Krylov-Schur solve for nev_eps eigenvalues of the shell's operator, the
// trivial pair deflated when defl is given, started from init (may be empty).
static PetscErrorCode SolveOnce(MonodromyShell &shell, MPI_Comm comm, PetscInt nev_eps, const std::vector<Vec> &defl, const std::vector<Vec> &init,
                                OwnedEPS *eps)
{
  PetscFunctionBeginUser;
  PetscCall(EPSCreate(comm, eps->out()));
  PetscCall(EPSSetOptionsPrefix(*eps, "floquet_mf_"));
  PetscCall(EPSSetOperators(*eps, shell.Get(), NULL));
  PetscCall(EPSSetProblemType(*eps, EPS_NHEP));
  PetscCall(EPSSetType(*eps, EPSKRYLOVSCHUR));
  PetscCall(EPSSetWhichEigenpairs(*eps, EPS_LARGEST_MAGNITUDE));
  PetscCall(EPSSetDimensions(*eps, nev_eps, PETSC_DEFAULT, PETSC_DEFAULT));
  PetscCall(EPSSetTolerances(*eps, 1e-10, PETSC_DEFAULT));
  PetscCall(EPSSetFromOptions(*eps));
  PetscInt nev_set, ncv, mpd; // a user's -floquet_mf_eps_ncv stays unless too small for a repeat solve's nev
  PetscCall(EPSGetDimensions(*eps, &nev_set, &ncv, &mpd));
  if (nev_set < nev_eps || (ncv != PETSC_DEFAULT && ncv < 2 * nev_eps + 1))
    PetscCall(EPSSetDimensions(*eps, PetscMax(nev_set, nev_eps), ncv == PETSC_DEFAULT ? ncv : PetscMax(ncv, 2 * nev_eps + 1), mpd));
  if (!defl.empty()) PetscCall(EPSSetDeflationSpace(*eps, (PetscInt)defl.size(), const_cast<Vec *>(defl.data())));
  if (!init.empty()) PetscCall(EPSSetInitialSpace(*eps, (PetscInt)init.size(), const_cast<Vec *>(init.data())));
  PetscCall(EPSSolve(*eps));
  PetscFunctionReturn(0);
}

// The residual |Op x - lambda x| / |x| of eigenpair i of eps for the shell's
// operator Op (M, or B on the critical route): one more product (two for a
// complex pair), computed afresh rather than taken from Krylov-Schur's
// estimate.
static PetscErrorCode TrueResidual(MonodromyShell &shell, EPS eps, PetscInt i, Vec like, PetscReal *res)
{
  OwnedVec xr, xi, yr, yi;
  PetscScalar kr, ki;
  PetscReal a, b, c, d;
  PetscFunctionBeginUser;
  for (OwnedVec *v : {&xr, &xi, &yr, &yi}) PetscCall(VecDuplicate(like, v->out()));
  PetscCall(EPSGetEigenpair(eps, i, &kr, &ki, xr, xi));
  PetscCall(MatMult(shell.Get(), xr, yr)); // y = Op x - lambda x, real and imaginary parts
  PetscCall(VecAXPBYPCZ(yr, -kr, ki, 1.0, xr, xi));
  if (ki != 0) {
    PetscCall(MatMult(shell.Get(), xi, yi));
    PetscCall(VecAXPBYPCZ(yi, -ki, -kr, 1.0, xr, xi));
  } else {
    PetscCall(VecZeroEntries(xi));
    PetscCall(VecZeroEntries(yi));
  }
  PetscCall(VecNorm(yr, NORM_2, &a));
  PetscCall(VecNorm(yi, NORM_2, &b));
  PetscCall(VecNorm(xr, NORM_2, &c));
  PetscCall(VecNorm(xi, NORM_2, &d));
  *res = std::hypot(a, b) / std::hypot(c, d);
  PetscFunctionReturn(0);
}

// The initial Krylov space of an orbit from the previous orbit's
// eigenvectors warm (none: SLEPc's own start) into start. Krylov-Schur grows
// its space from the first initial vector only. The previous orbit's
// eigenvectors alone make it converge the same pair first and stop even when
// another pair has become the leading one (N = 10^4, E = 1.86: the edge pair
// 0.98746 was returned, not the interface pair near -0.9906), so they are
// mixed with an equal share of a random vector.
static PetscErrorCode WarmStart(Vec z0, const std::vector<OwnedVec> *warm, OwnedVec *start, std::vector<Vec> *init)
{
  PetscFunctionBeginUser;
  if (!warm || warm->empty()) PetscFunctionReturn(0);
  OwnedRandom rnd;
  PetscReal nrm;
  PetscCall(VecDuplicate(z0, start->out()));
  PetscCall(PetscRandomCreate(PetscObjectComm((PetscObject)z0), rnd.out()));
  PetscCall(PetscRandomSetSeed(rnd, 20261122));
  PetscCall(PetscRandomSeed(rnd));
  PetscCall(VecSetRandom(*start, rnd));
  PetscCall(VecShift(*start, -0.5));
  PetscCall(VecNormalize(*start, NULL));
  for (auto &w : *warm) {
    PetscCall(VecNorm(w, NORM_2, &nrm));
    if (nrm > 0) PetscCall(VecAXPY(*start, 1.0 / nrm, w));
  }
  init->push_back(start->get());
  PetscFunctionReturn(0);
}

// The eigensolve of an orbit: the first nev distinct eigenvalues of the
// shell's operator (seen, largest |b| first; first: the index of each one's
// first copy in eps; tol: the eigensolver's). Critical route: every
// eigenvalue b of B is double (mu and 1/mu, which is conj(mu) on the circle,
// give the same b), and a converged set may hold both copies of a pair. The
// multipliers are the first nev DISTINCT values, one per pair; when copies
// leave fewer than nev, a new solve asks for as many more eigenvalues, from
// the converged eigenvectors (at most twice).
static PetscErrorCode DistinctEigenvalues(MonodromyShell &shell, Vec z0, PetscInt nev, bool critical, const std::vector<Vec> &defl, std::vector<Vec> init,
                                          OwnedEPS *eps, std::vector<std::complex<PetscReal>> *seen, std::vector<PetscInt> *first, PetscReal *tol)
{
  const MPI_Comm comm = PetscObjectComm((PetscObject)z0);
  PetscInt nconv;
  std::vector<OwnedVec> previous; // the previous round's eigenvectors: the next one's start
  PetscFunctionBeginUser;
  for (PetscInt round = 0, nev_eps = nev;; round++) {
    PetscCall(SolveOnce(shell, comm, nev_eps, defl, init, eps));
    PetscCall(EPSGetConverged(*eps, &nconv));
    PetscCall(EPSGetTolerances(*eps, tol, NULL));
    seen->clear(), first->clear();
    for (PetscInt i = 0; i < nconv && (PetscInt)seen->size() < nev; i++) {
      PetscReal br, bi;
      PetscCall(EPSGetEigenvalue(*eps, i, &br, &bi));
      const std::complex<PetscReal> b(br, bi);
      bool copy = false;
      for (const auto &c : *seen) copy = copy || (critical && std::abs(b - c) <= 10 * *tol * std::max<PetscReal>(1, std::abs(c)));
      if (!copy) seen->push_back(b), first->push_back(i);
    }
    if ((PetscInt)seen->size() >= nev || nconv < nev_eps || round == 2) break;
    std::vector<OwnedVec> x(nconv);
    init.clear();
    for (PetscInt i = 0; i < nconv; i++) {
      PetscCall(VecDuplicate(z0, x[i].out()));
      PetscCall(EPSGetEigenvector(*eps, i, x[i], NULL));
      init.push_back(x[i]);
    }
    previous = std::move(x);
    nev_eps += nev - (PetscInt)seen->size();
  }
  PetscFunctionReturn(0);
}

// The multipliers of the eigenvalues seen (eigenpairs first of eps) into r,
// verified ones first: a converged Ritz pair is kept only if its true
// residual, computed afresh with one more product, confirms it: Krylov-Schur
// on the non-normal M (largest) declared values converged whose residual was
// 3e-4..2.5e-3 on the circle and 308 for a spurious |mu| = 306.9 (N = 102,
// E = 1.86, ncv 60, 30 restarts); on the critical route the residuals were
// 2e-11..3e-10. Accepted: |Op x - lambda x| <= 100 tol max(1, |lambda|) |x|,
// tol the eigensolver's. A rejected one is NaN, like an unconverged one
// (not converged within -floquet_mf_eps_max_it: a continuation goes on, the
// caller reports it; never a silent number). kept: the eigenpairs that passed.
static PetscErrorCode AcceptMultipliers(MonodromyShell &shell, EPS eps, Vec z0, const std::vector<std::complex<PetscReal>> &seen,
                                        const std::vector<PetscInt> &first, PetscReal tol, const FloquetMfOptions &o, LeadingMultipliers *r,
                                        std::vector<PetscInt> *kept)
{
  const PetscInt nev = o.nev;
  const bool critical = o.which == FloquetMfWhich::Critical;
  PetscFunctionBeginUser;
  r->converged = 0;
  r->re.assign(nev, NAN), r->im.assign(nev, NAN), r->resolution.assign(nev, NAN);
  r->max_modulus = 0;
  for (PetscInt k = 0; k < (PetscInt)seen.size(); k++) {
    PetscReal res = NAN;
    PetscCall(TrueResidual(shell, eps, first[k], z0, &res));
    if (!(res <= 100 * tol * std::max<PetscReal>(1, std::abs(seen[k])))) {
      r->spurious++;
      PetscCall(
          PetscInfo(NULL, "matrix-free Floquet: Ritz value %g%+gi rejected, true residual %g\n", (double)seen[k].real(), (double)seen[k].imag(), (double)res));
      continue;
    }
    kept->push_back(first[k]);
    const PetscInt slot = r->converged; // verified ones first, NaN after them
    const PetscReal br = seen[k].real(), bi = seen[k].imag();
    std::complex<PetscReal> mu(br, bi);
    if (critical) {
      if (std::abs(bi) <= o.circle_tol && std::abs(br) <= 1 + o.circle_tol) { // on the unit circle: mu = b + i sqrt(1 - b^2)
        const PetscReal c = std::max<PetscReal>(-1, std::min<PetscReal>(1, br));
        mu = std::complex<PetscReal>(c, std::sqrt(1 - c * c));
      } else { // mu = b + sqrt(b^2 - 1), the member with |mu| > 1
        const std::complex<PetscReal> b(br, bi), s = std::sqrt(b * b - 1.0);
        mu = std::abs(b + s) >= std::abs(b - s) ? b + s : b - s;
      }
    }
    r->re[slot] = mu.real(), r->im[slot] = mu.imag();
    // How far |mu| - 1 is resolved: an eigenvalue error ~ res; through
    // mu = b + sqrt(b^2 - 1) near b = +-1 it becomes sqrt(2 res).
    r->resolution[slot] = critical ? std::sqrt(2 * std::max(o.circle_tol, res)) : res;
    r->max_modulus = std::max(r->max_modulus, std::abs(mu));
    r->converged++;
  }
  // A partial answer bounds nothing: the missing multiplier may be the largest.
  if (r->converged < nev) r->max_modulus = NAN;
  PetscFunctionReturn(0);
}

// The eigenvector of M of the accepted multiplier of largest modulus (see
// FloquetLeading): x = xr + i xi from the eigensolver; on the critical route
// x lies in span{v_mu, v_1/mu} (B's eigenspace of b) and v = M x - x / mu
// keeps the v_mu part.
static PetscErrorCode LeadingVector(PeriodicFlow &flow, Vec z0, PetscReal T, PetscReal beta, EPS eps, const LeadingMultipliers &r,
                                    const std::vector<PetscInt> &kept, bool critical, Vec vr, Vec vi)
{
  PetscFunctionBeginUser;
  PetscCall(VecZeroEntries(vr));
  PetscCall(VecZeroEntries(vi));
  PetscInt best = -1;
  for (PetscInt k = 0; k < r.converged && k < (PetscInt)kept.size(); k++)
    if (best < 0 || std::hypot(r.re[k], r.im[k]) > std::hypot(r.re[best], r.im[best])) best = k;
  if (best < 0) PetscFunctionReturn(0);
  PetscCall(EPSGetEigenvector(eps, kept[best], vr, vi));
  if (!critical) PetscFunctionReturn(0);
  const std::complex<PetscReal> inv = 1.0 / std::complex<PetscReal>(r.re[best], r.im[best]);
  OwnedVec zT, mr, mi;
  PetscCall(VecDuplicate(z0, zT.out()));
  PetscCall(VecDuplicate(vr, mr.out()));
  PetscCall(VecDuplicate(vr, mi.out()));
  PetscCall(flow.IntegrateWithTangent(z0, T, beta, vr, 0, 0, zT, mr));
  PetscCall(flow.IntegrateWithTangent(z0, T, beta, vi, 0, 0, zT, mi));
  // (mr + i mi) - inv (vr + i vi)
  PetscCall(VecAXPBYPCZ(mr, -inv.real(), inv.imag(), 1.0, vr, vi));
  PetscCall(VecAXPBYPCZ(mi, -inv.imag(), -inv.real(), 1.0, vr, vi));
  PetscCall(VecCopy(mr, vr));
  PetscCall(VecCopy(mi, vi));
  PetscFunctionReturn(0);
}

PetscErrorCode FloquetLeading(PeriodicFlow &flow, Vec z0, PetscReal T, PetscReal beta, const FloquetMfOptions &o, LeadingMultipliers *r,
                              std::vector<OwnedVec> *warm, Vec dz0, Vec lead_re, Vec lead_im)
{
  MonodromyShell shell;
  OwnedEPS eps;
  const bool critical = o.which == FloquetMfWhich::Critical;
  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(Log().floquet, 0, 0, 0, 0));
  PetscCall(shell.Create(flow, z0, T, beta, critical));
  OwnedVec fz0, start;
  std::vector<Vec> defl, init;
  if (o.deflate && dz0) { // the trivial pair's invariant subspace span{f(z0), dz0} (header)
    PetscCall(VecDuplicate(z0, fz0.out()));
    PetscCall(flow.Field(z0, fz0));
    defl = {fz0.get(), dz0};
  }
  PetscCall(WarmStart(z0, warm, &start, &init));
  PetscReal tol;
  std::vector<std::complex<PetscReal>> seen;
  std::vector<PetscInt> first, kept; // kept: the eigenpairs that passed, the next orbit's start
  PetscCall(DistinctEigenvalues(shell, z0, o.nev, critical, defl, init, &eps, &seen, &first, &tol));
  PetscCall(AcceptMultipliers(shell, eps, z0, seen, first, tol, o, r, &kept));
  r->products = shell.Products();
  if (lead_re && lead_im) PetscCall(LeadingVector(flow, z0, T, beta, eps, *r, kept, critical, lead_re, lead_im));
  if (warm) { // this orbit's eigenvectors (real and imaginary parts, one copy per pair) start the next solve
    warm->clear();
    for (PetscInt i : kept) {
      OwnedVec xr, xi;
      PetscCall(VecDuplicate(z0, xr.out()));
      PetscCall(VecDuplicate(z0, xi.out()));
      PetscCall(EPSGetEigenvector(eps, i, xr, xi));
      warm->push_back(std::move(xr));
      PetscReal ni;
      PetscCall(VecNorm(xi, NORM_2, &ni));
      if (ni > 0) warm->push_back(std::move(xi));
    }
  }
  PetscCall(PetscLogEventEnd(Log().floquet, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

} // namespace nltopo
