#include "stability/floquet_mf.hpp"
#include "core/gather.hpp"
#include "core/log.hpp"
#include <algorithm>
#include <cmath>
#include <complex>
#include <numeric>
#include <petscblaslapack.h>
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

static const char *const kWhichNames[] = {"largest", "critical"};

PetscErrorCode FloquetMfOptionsFromOptions(MPI_Comm comm, FloquetMfOptions *o)
{
  PetscInt w = static_cast<PetscInt>(o->which);
  PetscFunctionBeginUser;
  PetscOptionsBegin(comm, "floquet_mf_", "Matrix-free Floquet multipliers (eigensolver options: -floquet_mf_eps_*)", NULL);
  PetscCall(PetscOptionsInt("-nev", "Leading multiplier pairs wanted per orbit (critical: one per distinct b)", NULL, o->nev, &o->nev, NULL));
  PetscCall(PetscOptionsEList("-which",
                              "largest: largest modulus (Krylov-Schur on M); critical: nearest the critical points +-1 or off the unit circle "
                              "(Krylov-Schur on (M + M^-1)/2)",
                              NULL, kWhichNames, 2, kWhichNames[w], &w, NULL));
  PetscCall(PetscOptionsReal("-circle_tol",
                             "critical: b = (mu + 1/mu)/2 within this of [-1, 1] is on the unit circle (|mu| - 1 is resolved down to sqrt(2 circle_tol))",
                             NULL, o->circle_tol, &o->circle_tol, NULL));
  PetscCall(PetscOptionsInt("-dense_max",
                            "Orbits with 2N at most this take the dense monodromy (all 2N multipliers: the only route that can call an orbit stable; "
                            "its cost grows as (2N)^3); 0: always matrix-free",
                            NULL, o->dense_max, &o->dense_max, NULL));
  PetscCall(PetscOptionsBool("-deflate", "Deflate the trivial pair mu = 1 (span of f(z0) and the family tangent) so that the nev multipliers are nontrivial",
                             NULL, o->deflate, &o->deflate, NULL));
  PetscOptionsEnd();
  PetscCheck(o->circle_tol > 0 && o->circle_tol < 1, comm, PETSC_ERR_USER, "-floquet_mf_circle_tol must lie in (0, 1), got %g", (double)o->circle_tol);
  PetscCheck(o->nev >= 1 && o->nev <= 1000, comm, PETSC_ERR_USER, "-floquet_mf_nev must lie in [1, 1000], got %" PetscInt_FMT, o->nev);
  PetscCheck(o->dense_max >= 0 && o->dense_max <= 20000, comm, PETSC_ERR_USER, "-floquet_mf_dense_max must lie in [0, 20000], got %" PetscInt_FMT, o->dense_max);
  o->which = static_cast<FloquetMfWhich>(w);
  PetscFunctionReturn(0);
}

PetscInt MatrixFreeVerdict(const LeadingMultipliers &r, PetscReal tol)
{
  for (size_t k = 0; k < r.re.size(); k++)
    if (std::hypot(r.re[k], r.im[k]) > 1 + tol) return kUnstable; // NaN compares false
  return kUndecided;
}

PetscErrorCode FloquetLeadingDense(const Lattice &lat, Mat S, PetscInt nev, PetscReal tol, LeadingMultipliers *r)
{
  const PetscInt n = 2 * lat.N();
  const MPI_Comm comm = lat.Comm();
  PetscMPIInt rank;
  std::vector<PetscReal> a, wr, wi;
  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(Log().floquet, 0, 0, 0, 0));
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  if (rank == 0) a.resize((size_t)n * n);
  for (PetscInt c = 0; c < n; c++) { // column c of M, in PETSc's order on rows and columns alike (a similarity)
    Vec col;
    std::vector<PetscReal> x;
    PetscCall(MatDenseGetColumnVecRead(S, c, &col));
    PetscCall(GatherVec(col, false, &x));
    PetscCall(MatDenseRestoreColumnVecRead(S, c, &col));
    if (rank == 0) std::copy(x.begin(), x.begin() + n, a.begin() + (size_t)c * n);
  }
  std::vector<PetscReal> out(2 * nev + 1, NAN); // rank 0's answer: nev multipliers, then max |mu|
  if (rank == 0) {
    PetscBLASInt bn, one = 1, lwork = -1, info = 0;
    PetscReal wq;
    PetscCall(PetscBLASIntCast(n, &bn));
    wr.resize(n), wi.resize(n);
    PetscCallBLAS("LAPACKgeev", LAPACKgeev_("N", "N", &bn, a.data(), &bn, wr.data(), wi.data(), NULL, &one, NULL, &one, &wq, &lwork, &info));
    std::vector<PetscReal> work((size_t)wq + 1);
    PetscCall(PetscBLASIntCast((PetscInt)work.size(), &lwork));
    PetscCallBLAS("LAPACKgeev", LAPACKgeev_("N", "N", &bn, a.data(), &bn, wr.data(), wi.data(), NULL, &one, NULL, &one, work.data(), &lwork, &info));
    PetscCheck(info == 0, PETSC_COMM_SELF, PETSC_ERR_LIB, "Floquet (dense): LAPACK geev failed, info %d (2N = %" PetscInt_FMT ")", (int)info, n);
    std::vector<std::complex<PetscReal>> mu(n);
    for (PetscInt i = 0; i < n; i++) mu[i] = {wr[i], wi[i]};
    // the trivial pair: the two multipliers nearest 1
    std::sort(mu.begin(), mu.end(), [](auto x, auto y) { return std::abs(x - 1.0) < std::abs(y - 1.0); });
    mu.erase(mu.begin(), mu.begin() + std::min<PetscInt>(2, n));
    PetscReal big = 0;
    for (const auto &m : mu) big = std::max(big, std::abs(m));
    // one member of each pair: |mu| >= 1 off the circle, the upper half plane (or real) on it
    std::vector<std::complex<PetscReal>> lead;
    for (const auto &m : mu) {
      const bool off = std::abs(std::abs(m) - 1) > tol;
      if (off ? std::abs(m) > 1 && m.imag() >= 0 : m.imag() >= 0) lead.push_back(m);
    }
    std::sort(lead.begin(), lead.end(), [tol](auto x, auto y) {
      const bool ox = std::abs(x) > 1 + tol, oy = std::abs(y) > 1 + tol;
      if (ox != oy) return ox;
      return ox ? std::abs(x) > std::abs(y) : std::abs(x.real()) > std::abs(y.real());
    });
    // a real pair on the circle at +-1 is a double root: keep one
    for (PetscInt k = 0, j = 0; k < nev && j < (PetscInt)lead.size(); j++) {
      if (k > 0 && std::abs(lead[j] - std::complex<PetscReal>(out[2 * k - 2], out[2 * k - 1])) <= 1e-6) continue;
      out[2 * k] = lead[j].real(), out[2 * k + 1] = lead[j].imag(), k++;
    }
    out[2 * nev] = big;
  }
  PetscCallMPI(MPI_Bcast(out.data(), (PetscMPIInt)out.size(), MPIU_REAL, 0, comm));
  r->re.assign(nev, NAN), r->im.assign(nev, NAN);
  r->converged = 0;
  for (PetscInt k = 0; k < nev; k++) {
    r->re[k] = out[2 * k], r->im[k] = out[2 * k + 1];
    if (std::isfinite(out[2 * k])) r->converged++;
  }
  r->max_modulus = out[2 * nev];
  r->products = 0;
  r->verdict = r->max_modulus <= 1 + tol ? kStable : kUnstable;
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

PetscErrorCode FloquetLeading(PeriodicFlow &flow, Vec z0, PetscReal T, PetscReal beta, const FloquetMfOptions &o, LeadingMultipliers *r,
                              std::vector<OwnedVec> *warm, Vec dz0)
{
  MonodromyShell shell;
  OwnedEPS eps;
  PetscInt nconv;
  const PetscInt nev = o.nev;
  const bool critical = o.which == FloquetMfWhich::Critical;
  const MPI_Comm comm = PetscObjectComm((PetscObject)z0);
  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(Log().floquet, 0, 0, 0, 0));
  PetscCall(shell.Create(flow, z0, T, beta, critical));
  OwnedVec fz0;
  std::vector<Vec> defl, init;
  if (o.deflate && dz0) { // the trivial pair's invariant subspace span{f(z0), dz0} (header)
    PetscCall(VecDuplicate(z0, fz0.out()));
    PetscCall(flow.Field(z0, fz0));
    defl = {fz0.get(), dz0};
  }
  // Krylov-Schur grows its space from the first initial vector only. The
  // previous orbit's eigenvectors alone make it converge the same pair first
  // and stop even when another pair has become the leading one (N = 10^4,
  // E = 1.86: the edge pair 0.98746 was returned, not the interface pair near
  // -0.9906), so they are mixed with an equal share of a random vector.
  OwnedVec start;
  if (warm && !warm->empty()) {
    PetscRandom rnd;
    PetscReal nrm;
    PetscCall(VecDuplicate(z0, start.out()));
    PetscCall(PetscRandomCreate(comm, &rnd));
    PetscCall(PetscRandomSetSeed(rnd, 20261122));
    PetscCall(PetscRandomSeed(rnd));
    PetscCall(VecSetRandom(start, rnd));
    PetscCall(PetscRandomDestroy(&rnd));
    PetscCall(VecShift(start, -0.5));
    PetscCall(VecNormalize(start, NULL));
    for (auto &w : *warm) {
      PetscCall(VecNorm(w, NORM_2, &nrm));
      if (nrm > 0) PetscCall(VecAXPY(start, 1.0 / nrm, w));
    }
    init.push_back(start.get());
  }
  // Critical route: every eigenvalue b of B is double (mu and 1/mu, which is
  // conj(mu) on the circle, give the same b), and a converged set may hold both
  // copies of a pair. The multipliers are the first nev DISTINCT values, one
  // per pair; when copies leave fewer than nev, a new solve asks for as many
  // more eigenvalues, from the converged eigenvectors (at most twice).
  PetscReal tol;
  std::vector<std::complex<PetscReal>> seen; // distinct values, largest |b| first
  std::vector<PetscInt> first;                // the index of each one's first copy
  std::vector<OwnedVec> previous;             // the previous round's eigenvectors: the next one's start
  for (PetscInt round = 0, nev_eps = nev;; round++) {
    PetscCall(SolveOnce(shell, comm, nev_eps, defl, init, &eps));
    PetscCall(EPSGetConverged(eps, &nconv));
    PetscCall(EPSGetTolerances(eps, &tol, NULL));
    seen.clear(), first.clear();
    for (PetscInt i = 0; i < nconv && (PetscInt)seen.size() < nev; i++) {
      PetscReal br, bi;
      PetscCall(EPSGetEigenvalue(eps, i, &br, &bi));
      const std::complex<PetscReal> b(br, bi);
      bool copy = false;
      for (const auto &c : seen) copy = copy || (critical && std::abs(b - c) <= 10 * tol * std::max<PetscReal>(1, std::abs(c)));
      if (!copy) seen.push_back(b), first.push_back(i);
    }
    if ((PetscInt)seen.size() >= nev || nconv < nev_eps || round == 2) break;
    std::vector<OwnedVec> x(nconv);
    init.clear();
    for (PetscInt i = 0; i < nconv; i++) {
      PetscCall(VecDuplicate(z0, x[i].out()));
      PetscCall(EPSGetEigenvector(eps, i, x[i], NULL));
      init.push_back(x[i]);
    }
    previous = std::move(x);
    nev_eps += nev - (PetscInt)seen.size();
  }
  // Not converged within -floquet_mf_eps_max_it: NaN for the missing ones (a
  // continuation goes on; the caller reports it), never a silent number.
  r->converged = (PetscInt)seen.size();
  r->re.assign(nev, NAN), r->im.assign(nev, NAN);
  r->max_modulus = 0;
  for (PetscInt k = 0; k < r->converged; k++) {
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
    r->re[k] = mu.real(), r->im[k] = mu.imag();
    r->max_modulus = std::max(r->max_modulus, std::abs(mu));
  }
  // A partial answer bounds nothing: the missing multiplier may be the largest.
  if (r->converged < nev) r->max_modulus = NAN;
  r->products = shell.Products();
  if (warm) { // this orbit's eigenvectors (real and imaginary parts, one copy per pair) start the next solve
    warm->clear();
    for (PetscInt i : first) {
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
