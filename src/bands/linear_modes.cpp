#include "bands/linear_modes.hpp"
#include "core/memory_guard.hpp"
#include "core/log.hpp"
#include "core/option_table.hpp"
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numeric>

namespace nltopo {

static const auto &kLinearModesTable = DeclareOptionTable<
    LinearModesOptions>("linear_", "Linear modes (SLEPc EPS on K; solver options -linear_eps_*)", [](OptionTable<LinearModesOptions> &t) {
  t.Int("dense_max", &LinearModesOptions::dense_max, Closed(0, 10000), "Largest N solved for all eigenpairs; above it, shift-invert around the band edges")
      .Why("the dense path holds N x N: 10^4 sites is 800 MB")
      .Int("nev", &LinearModesOptions::nev, Closed(1, 1000), "Shift-invert path: eigenpairs computed per target")
      .Real("target_offset", &LinearModesOptions::offset, Open(0, 0.1),
            "Shift-invert path: relative distance of each target outside its band edge (small: fast convergence; not 0: an exact eigenvalue is a zero pivot)");
});

PetscErrorCode LinearModesOptionsFromOptions(MPI_Comm comm, LinearModesOptions *o) { return kLinearModesTable.Read(comm, o); }

// An EPS on K with the -linear_eps_* prefix (Hermitian problem).
static PetscErrorCode CreateEps(const Lattice &lat, EPSType type, EPS *eps)
{
  PetscFunctionBeginUser;
  PetscCall(EPSCreate(lat.Comm(), eps));
  PetscCall(EPSSetOptionsPrefix(*eps, "linear_"));
  PetscCall(EPSSetOperators(*eps, lat.K(), NULL));
  PetscCall(EPSSetProblemType(*eps, EPS_HEP));
  PetscCall(EPSSetType(*eps, type));
  PetscFunctionReturn(0);
}

PetscErrorCode LinearModes::AppendPairs(const Lattice &lat, EPS eps, PetscInt nmax)
{
  PetscInt nconv;
  PetscFunctionBeginUser;
  PetscCall(EPSGetConverged(eps, &nconv));
  nconv = std::min(nconv, nmax); // the nmax nearest (EPS sorts them): the same set on any number of ranks
  for (PetscInt i = 0; i < nconv; i++) {
    PetscScalar lam;
    OwnedVec x;
    PetscCall(DMCreateGlobalVector(lat.SiteDM(), x.out()));
    PetscCall(EPSGetEigenpair(eps, i, &lam, NULL, x, NULL));
    // Drop duplicates found from two targets: same value and same vector.
    bool dup = false;
    for (size_t j = 0; j < omega_.size() && !dup; j++) {
      if (std::abs(omega_[j] * omega_[j] - lam) > 1e-8 * std::abs(lam)) continue;
      PetscScalar d;
      PetscCall(VecDot(x, modes_[j], &d));
      dup = std::abs(d) > 0.5;
    }
    if (dup) continue;
    omega_.push_back(std::sqrt(std::max<PetscReal>(lam, 0)));
    modes_.push_back(std::move(x));
  }
  PetscFunctionReturn(0);
}

PetscErrorCode LinearModes::SolveAll(const Lattice &lat)
{
  OwnedEPS eps;
  const PetscInt N = lat.N();
  PetscFunctionBeginUser;
  PetscCall(CreateEps(lat, EPSLAPACK, eps.out()));
  PetscCall(EPSSetWhichEigenpairs(eps, EPS_SMALLEST_REAL));
  PetscCall(EPSSetDimensions(eps, N, PETSC_DEFAULT, PETSC_DEFAULT));
  PetscCall(EPSSetFromOptions(eps));
  PetscCall(EPSSolve(eps));
  PetscCall(AppendPairs(lat, eps, N));
  complete_ = (PetscInt)omega_.size() == N;
  PetscCheck(complete_, lat.Comm(), PETSC_ERR_NOT_CONVERGED, "linear modes: only %zu of %" PetscInt_FMT " eigenpairs converged", omega_.size(), N);
  PetscFunctionReturn(0);
}

PetscErrorCode LinearModes::SolveNear(const Lattice &lat, const LinearModesOptions &o)
{
  const LatticeParams &p = lat.Params();
  const PetscReal kh = p.KHat(), s = p.K1() + p.K2(), d = std::abs(p.K1() - p.K2());
  // Targets (omega^2) just outside each closed-form band edge and next to k_hat:
  // close enough that the nearest eigenvalues separate well after the
  // spectral transformation (band edges are dense for large N), never on an
  // exact eigenvalue (zero pivot).
  const PetscReal off = o.offset * kh;
  PetscMPIInt size;
  // At k_hat the gap holds the insulated pair (model.md "Trap"): ask for 2 there;
  // more would be band-edge eigenvalues, far away and clustered (no convergence).
  const PetscReal targets[] = {kh - d + off, kh + off, kh + d - off, kh + s + off};
  const PetscInt nevs[] = {o.nev, 2, o.nev, o.nev};
  PetscFunctionBeginUser;
  for (int k = 0; k < 4; k++) {
    const PetscReal sigma = targets[k];
    OwnedEPS eps;
    ST st;
    KSP ksp;
    PC pc;
    PetscCall(CreateEps(lat, EPSKRYLOVSCHUR, eps.out()));
    PetscCall(EPSSetTarget(eps, sigma));
    PetscCall(EPSSetWhichEigenpairs(eps, EPS_TARGET_MAGNITUDE));
    PetscCall(EPSSetDimensions(eps, nevs[k], PETSC_DEFAULT, PETSC_DEFAULT));
    PetscCall(EPSGetST(eps, &st));
    PetscCall(STSetType(st, STSINVERT));
    PetscCall(STGetKSP(st, &ksp));
    PetscCall(KSPSetType(ksp, KSPPREONLY));
    PetscCall(KSPGetPC(ksp, &pc));
    PetscCallMPI(MPI_Comm_size(lat.Comm(), &size));
    if (size > 1) {
      // K - sigma I is tridiagonal and indefinite: a redundant LU (each rank
      // factors the whole chain, O(N) per rank, natural order, no fill) beats
      // MUMPS's parallel solves by ~100x here (134 ms per solve at N = 1e5).
      KSP inner;
      PC ipc;
      PetscCall(PCSetType(pc, PCREDUNDANT));
      PetscCall(PCRedundantGetKSP(pc, &inner));
      PetscCall(KSPGetPC(inner, &ipc));
      PetscCall(PCSetType(ipc, PCLU));
      PetscCall(PCFactorSetMatOrderingType(ipc, MATORDERINGNATURAL));
    } else {
      PetscCall(PCSetType(pc, PCLU));                                // K - sigma I is indefinite: LU
      PetscCall(PCFactorSetMatOrderingType(pc, MATORDERINGNATURAL)); // tridiagonal: no fill
    }
    PetscCall(EPSSetFromOptions(eps));
    PetscCall(EPSSolve(eps));
    PetscCall(AppendPairs(lat, eps, nevs[k]));
  }
  // The extreme ends (localised modes outside the bands) with plain Krylov-Schur.
  for (EPSWhich which : {EPS_LARGEST_REAL, EPS_SMALLEST_REAL}) {
    OwnedEPS eps;
    PetscCall(CreateEps(lat, EPSKRYLOVSCHUR, eps.out()));
    PetscCall(EPSSetWhichEigenpairs(eps, which));
    PetscCall(EPSSetDimensions(eps, 1, PETSC_DEFAULT, PETSC_DEFAULT));
    PetscCall(EPSSetFromOptions(eps));
    PetscCall(EPSSolve(eps));
    PetscCall(AppendPairs(lat, eps, 1));
  }
  complete_ = false;
  PetscFunctionReturn(0);
}

PetscErrorCode LinearModes::SortAndNormalise()
{
  PetscFunctionBeginUser;
  std::vector<size_t> order(omega_.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) { return omega_[a] < omega_[b]; });
  std::vector<PetscReal> w;
  std::vector<OwnedVec> m;
  for (size_t k : order) {
    w.push_back(omega_[k]);
    m.push_back(std::move(modes_[k]));
  }
  omega_ = std::move(w);
  modes_ = std::move(m);
  for (auto &x : modes_) { // deterministic sign: the entry of largest magnitude is positive
    PetscReal mx, mn, nrm;
    PetscCall(VecNormalize(x, &nrm));
    PetscCall(VecMax(x, NULL, &mx));
    PetscCall(VecMin(x, NULL, &mn));
    if (-mn > mx) PetscCall(VecScale(x, -1.0));
  }
  PetscFunctionReturn(0);
}

// Weight of x on the sites in [a, b] (0-based, inclusive).
static PetscErrorCode SiteWeight(Vec x, PetscInt a, PetscInt b, PetscReal *w)
{
  PetscInt lo, hi;
  const PetscScalar *v;
  PetscReal loc = 0;
  PetscFunctionBeginUser;
  PetscCall(VecGetOwnershipRange(x, &lo, &hi));
  PetscCall(VecGetArrayRead(x, &v));
  for (PetscInt i = std::max(lo, a); i < std::min(hi, b + 1); i++) loc += v[i - lo] * v[i - lo];
  PetscCall(VecRestoreArrayRead(x, &v));
  PetscCall(MPIU_Allreduce(&loc, w, 1, MPIU_REAL, MPIU_SUM, PetscObjectComm((PetscObject)x)));
  PetscFunctionReturn(0);
}

// Zeroes the odd 0-based entries (model.md's odd sites), keeping the even sublattice of model.md.
static PetscErrorCode ProjectEvenSites(Vec x)
{
  PetscInt lo, hi;
  PetscScalar *v;
  PetscFunctionBeginUser;
  PetscCall(VecGetOwnershipRange(x, &lo, &hi));
  PetscCall(VecGetArray(x, &v));
  for (PetscInt i = lo; i < hi; i++)
    if (i % 2 == 0) v[i - lo] = 0; // 0-based even = 1-based odd
  PetscCall(VecRestoreArray(x, &v));
  PetscFunctionReturn(0);
}

PetscErrorCode LinearModes::Identify(const Lattice &lat)
{
  const LatticeParams &p = lat.Params();
  const BandEdges b = InfiniteBandEdges(p);
  const PetscReal tol = 1e-9;
  const PetscInt n = omega_.size();
  PetscFunctionBeginUser;
  named_ = NamedModes();
  for (PetscInt j = 0; j < n; j++) {
    const PetscReal w = omega_[j];
    if (w <= b.acoustic_top * (1 + tol)) named_.acoustic_top = j;
    if (w >= b.optical_bottom * (1 - tol) && named_.optical_bottom < 0) named_.optical_bottom = j;
    if (w >= b.optical_bottom * (1 - tol) && w <= b.optical_top * (1 + tol)) named_.optical_top = j;
  }
  if (named_.acoustic_top >= 0 && omega_[named_.acoustic_top] < b.acoustic_bottom * (1 - tol)) named_.acoustic_top = -1;
  if (named_.optical_bottom >= 0 && omega_[named_.optical_bottom] > b.optical_top * (1 + tol)) named_.optical_bottom = -1;
  if (p.layout != Layout::Interface) PetscFunctionReturn(0);

  const PetscInt m = p.InterfaceSite();
  // Interface mode: above the optical band, largest weight on the interface cell (m, m+1).
  PetscReal best = -1;
  for (PetscInt j = 0; j < n; j++) {
    if (omega_[j] <= b.optical_top * (1 + tol)) continue;
    PetscReal w;
    PetscCall(SiteWeight(modes_[j], m, m + 1, &w));
    if (w > best) {
      best = w;
      named_.interface = j;
    }
  }
  // Insulated mode: the even-sublattice projection of the eigenspace at
  // omega^2 = k_hat; the dominant direction of the 2x2 (or kxk) Gram matrix of
  // the projected eigenvectors, normalised and positive at site m+1.
  const PetscReal kh = p.KHat();
  std::vector<PetscInt> cl;
  // The pair is split by ~0.03 (3/7)^(Nc-4) through the finite lattice: the
  // cluster is every eigenpair within 5 % of k_hat (inside the gap for any
  // gamma used here), which holds both for small Nc too.
  for (PetscInt j = 0; j < n; j++)
    if (std::abs(omega_[j] * omega_[j] - kh) < 5e-2 * kh && omega_[j] > b.acoustic_top && omega_[j] < b.optical_bottom) cl.push_back(j);
  named_.insulated_cluster = cl.size();
  if (cl.empty()) PetscFunctionReturn(0);
  std::vector<OwnedVec> proj(cl.size());
  for (size_t a = 0; a < cl.size(); a++) {
    PetscCall(VecDuplicate(modes_[cl[a]], proj[a].out()));
    PetscCall(VecCopy(modes_[cl[a]], proj[a]));
    PetscCall(ProjectEvenSites(proj[a]));
  }
  // Power iteration on the small Gram matrix G_ab = proj_a . proj_b.
  const size_t c = cl.size();
  std::vector<PetscReal> G(c * c), coef(c, 1.0);
  for (size_t a = 0; a < c; a++)
    for (size_t bb = 0; bb < c; bb++) PetscCall(VecDot(proj[a], proj[bb], &G[a * c + bb]));
  for (int it = 0; it < 200; it++) {
    std::vector<PetscReal> y(c, 0.0);
    PetscReal nr = 0;
    for (size_t a = 0; a < c; a++) {
      for (size_t bb = 0; bb < c; bb++) y[a] += G[a * c + bb] * coef[bb];
      nr += y[a] * y[a];
    }
    nr = std::sqrt(nr);
    for (size_t a = 0; a < c; a++) coef[a] = y[a] / nr;
  }
  PetscCall(VecDuplicate(modes_[cl[0]], insulated_.out()));
  PetscCall(VecZeroEntries(insulated_));
  for (size_t a = 0; a < c; a++) PetscCall(VecAXPY(insulated_, coef[a], proj[a]));
  PetscReal nrm;
  PetscCall(VecNormalize(insulated_, &nrm));
  // Sign: positive at site m+1 (0-based m+1), read on its owner and broadcast.
  PetscInt lo, hi;
  PetscReal sgn = 0, g;
  PetscCall(VecGetOwnershipRange(insulated_, &lo, &hi));
  if (m + 1 >= lo && m + 1 < hi) {
    const PetscScalar *v;
    PetscCall(VecGetArrayRead(insulated_, &v));
    sgn = v[m + 1 - lo] >= 0 ? 1 : -1;
    PetscCall(VecRestoreArrayRead(insulated_, &v));
  }
  PetscCall(MPIU_Allreduce(&sgn, &g, 1, MPIU_REAL, MPIU_SUM, lat.Comm()));
  if (g < 0) PetscCall(VecScale(insulated_, -1.0));
  OwnedVec Kx;
  PetscScalar rq;
  PetscCall(VecDuplicate(insulated_, Kx.out()));
  PetscCall(MatMult(lat.K(), insulated_, Kx));
  PetscCall(VecDot(insulated_, Kx, &rq));
  named_.insulated_omega = std::sqrt(rq); // = sqrt(k_hat) for any even-site vector: K - k_hat I couples the sublattices
  PetscCall(VecAXPY(Kx, -rq, insulated_));
  PetscCall(VecNorm(Kx, NORM_2, &named_.insulated_residual)); // how far the projection is from an eigenvector
  PetscFunctionReturn(0);
}

PetscErrorCode CheckLinearModesMemory(MPI_Comm comm, PetscInt N, const LinearModesOptions &o)
{
  PetscFunctionBeginUser;
  // LAPACK on the dense N x N matrix: the matrix, its eigenvectors and workspace on every rank.
  if (N <= o.dense_max) PetscCall(CheckMemory(comm, 4.0 * 8.0 * (double)N * (double)N, "all linear eigenpairs (N <= -linear_dense_max)"));
  PetscFunctionReturn(0);
}

PetscErrorCode LinearModes::Compute(const Lattice &lat, const LinearModesOptions &o)
{
  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(Log().eigen, 0, 0, 0, 0));
  omega_.clear();
  modes_.clear();
  PetscCall(CheckLinearModesMemory(lat.Comm(), lat.N(), o));
  if (lat.N() <= o.dense_max) {
    PetscCall(SolveAll(lat));
  } else PetscCall(SolveNear(lat, o));
  PetscCall(SortAndNormalise());
  PetscCall(Identify(lat));
  PetscCall(PetscLogEventEnd(Log().eigen, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

PetscErrorCode LinearModes::CopyMode(PetscInt j, Vec x) const
{
  PetscFunctionBeginUser;
  PetscCheck(j >= 0 && j < (PetscInt)modes_.size(), PetscObjectComm((PetscObject)x), PETSC_ERR_USER, "linear mode index %" PetscInt_FMT " out of range 0..%zu",
             j, modes_.size() - 1);
  PetscCall(VecCopy(modes_[j], x));
  PetscFunctionReturn(0);
}

PetscErrorCode LinearModes::Projections(Vec eta, std::vector<PetscReal> *proj2) const
{
  PetscFunctionBeginUser;
  proj2->resize(modes_.size());
  for (size_t j = 0; j < modes_.size(); j++) {
    PetscScalar d;
    PetscCall(VecDot(modes_[j], eta, &d));
    (*proj2)[j] = d * d;
  }
  PetscFunctionReturn(0);
}

std::string NoInsulatedModeReason(const LatticeParams &p)
{
  char why[400];
  const PetscReal g = std::abs(p.gamma);
  // The mode decays by (1 - |gamma|)/(1 + |gamma|) per cell away from the
  // interface: over xi cells. Measured (k = 1, gamma0 = 1): it exists from
  // about 0.8 xi cells (at least 3; 2 at gamma -0.4).
  const PetscReal xi = g > 0 && g < 1 ? 1 / std::log((1 + g) / (1 - g)) : INFINITY;
  if (p.layout != Layout::Interface)
    std::snprintf(why, sizeof why, "-lattice_layout %s has no interface, where the insulated mode lives (-lattice_layout interface)", LayoutName(p.layout));
  else if (p.gamma == 0)
    std::snprintf(why, sizeof why, "-lattice_gamma 0 closes the gap (k1 = k2): without a gap there is no insulated mode");
  else if ((PetscReal)p.cells < std::max<PetscReal>(4, 3 * xi))
    std::snprintf(why, sizeof why,
                  "-lattice_cells %d is too few cells for the insulated mode to form at -lattice_gamma %g: it decays over about %.3g cells "
                  "(1/ln((1+|gamma|)/(1-|gamma|))) and needs about that many or more on each side (at least 3)",
                  (int)p.cells, (double)p.gamma, (double)xi);
  else if (p.perturbation != Perturbation::None && p.delta > 0)
    std::snprintf(why, sizeof why, "-lattice_perturbation %s -lattice_delta %g moved the insulated mode away from omega^2 = k_hat", PerturbationName(p.perturbation),
                  (double)p.delta);
  else std::snprintf(why, sizeof why, "no eigenpair within 5 %% of omega^2 = k_hat inside the gap (docs/studies/linear.md, Mode identification)");
  return why;
}

} // namespace nltopo
