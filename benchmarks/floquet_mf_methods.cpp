// Matrix-free Floquet verdicts inside the band (issue 20, measurement phase):
// candidate methods for the leading nontrivial multiplier of the orbits of the
// insulated branch, against the dense route on the same orbits.
//
// The driver continues the branch exactly as `-study continuation` does (same
// options: lattice, -nnm_*, -cont_*; e.g. -options_file options/fep_long.opts
// -lattice_cells 25 -cont_energy_max 20) and keeps every orbit with its family
// tangent. Then, for the selected points (-bench_points, default all):
//  dense   the 2N x 2N monodromy and all 2N multipliers (FloquetAnalysis): the
//          reference; only with -bench_dense (a list of point indices, or -1 for all)
//          or -bench_dense_energies (the points nearest these energies)
//  ks      Krylov-Schur on B = (M + M^-1)/2 (FloquetLeading) for each of the
//          -bench_ks ncv:max_it:warm configurations (warm = 1: the previous
//          selected point's eigenvectors start the solve, as in a continuation)
//  window  the localisation of E = M - M_lin (M_lin: the monodromy of the
//          linear lattice, the same scheme and period, i.e. the tangent at z = 0):
//          |E e_j| for the unit vectors of the sites within -bench_window_sites
//          of the interface (two products each); with the dense reference also
//          the leading modulus of M_lin + E P_W P_W^T for the window W of the
//          sites where |E e_j| > -bench_window_tol |M|, i.e. what a method that
//          uses only the window's columns of M and exact linear algebra on
//          M_lin would return
//  cheb    -bench_cheb m,k,max_products: Chebyshev-filtered subspace iteration on B
//  sinv    -bench_sinv s1,s2,...: shift-and-invert on B at these real shifts
//          (inner GMRES; an inner solve that does not converge stops the run
//          with SLEPc's error)
// One line per point and method (bench: ...), to be read by a script.
// Serial (1 rank): the window part reads the state layout [u | v].
#include "bench_clock.hpp"
#include "core/handle.hpp"
#include "stability/floquet.hpp"
#include "stability/floquet_mf.hpp"
#include "studies/nnm_setup.hpp"
#include "timeint/ts_rkn.hpp"
#include "timeint/ts_symsplit.hpp"
#include "core/log.hpp"
#include <petscblaslapack.h>
#include <slepcsys.h>
#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdio>
#include <string>
#include <vector>

using namespace nltopo;

namespace {

struct Orbit {
  OwnedVec z0, dz0;
  PetscReal T = 0, beta = 0;
};

class KeepOrbits : public PointHook {
public:
  PetscErrorCode Point(Vec z0, PetscReal T, PetscReal beta, Vec dz0) override
  {
    Orbit o;
    PetscFunctionBeginUser;
    PetscCall(VecDuplicate(z0, o.z0.out()));
    PetscCall(VecCopy(z0, o.z0));
    PetscCall(VecDuplicate(z0, o.dz0.out()));
    PetscCall(VecCopy(dz0, o.dz0));
    o.T = T, o.beta = beta;
    orbits.push_back(std::move(o));
    PetscFunctionReturn(0);
  }
  std::vector<Orbit> orbits;
};

// The leading multiplier of a multiplier list: the largest modulus, the trivial
// pair (the two nearest 1) left out; kind: +1 real positive, -1 real negative, 2 complex.
void Leading(const std::vector<std::complex<double>> &mu, double *mod, std::complex<double> *lead, int *kind)
{
  std::vector<size_t> idx(mu.size());
  for (size_t i = 0; i < idx.size(); i++) idx[i] = i;
  std::sort(idx.begin(), idx.end(), [&](size_t a, size_t b) { return std::abs(mu[a] - 1.0) < std::abs(mu[b] - 1.0); });
  *mod = 0, *lead = 0, *kind = 0;
  for (size_t q = 2; q < idx.size(); q++) {
    const std::complex<double> m = mu[idx[q]];
    if (std::abs(m) > *mod) *mod = std::abs(m), *lead = m;
  }
  *kind = std::abs(lead->imag()) <= 1e-7 * std::abs(*lead) ? (lead->real() > 0 ? 1 : -1) : 2;
}

// Eigenvalues of a dense n x n column-major real matrix (destroyed).
PetscErrorCode DenseEigenvalues(PetscInt n, std::vector<PetscScalar> &a, std::vector<std::complex<double>> *mu)
{
  PetscBLASInt bn, lwork, info, one = 1;
  PetscFunctionBeginUser;
  PetscCall(PetscBLASIntCast(n, &bn));
  PetscCall(PetscBLASIntCast(8 * n, &lwork));
  std::vector<PetscReal> wr(n), wi(n), work(8 * n);
  PetscScalar dummy;
  PetscCallBLAS("LAPACKgeev", LAPACKgeev_("N", "N", &bn, a.data(), &bn, wr.data(), wi.data(), &dummy, &one, &dummy, &one, work.data(), &lwork, &info));
  PetscCheck(info == 0, PETSC_COMM_SELF, PETSC_ERR_LIB, "geev failed: %d", (int)info);
  mu->resize(n);
  for (PetscInt i = 0; i < n; i++) (*mu)[i] = {wr[i], wi[i]};
  PetscFunctionReturn(0);
}

// Leading of the eigenvalues of a dense n x n matrix (M copied: the eigensolver overwrites it).
PetscErrorCode DenseLeading(PetscInt n, std::vector<PetscScalar> M, double *mod, std::complex<double> *lead, int *kind)
{
  std::vector<std::complex<double>> mu;
  PetscFunctionBeginUser;
  PetscCall(DenseEigenvalues(n, M, &mu));
  Leading(mu, mod, lead, kind);
  PetscFunctionReturn(0);
}

// Dense monodromy (columns 0..2N-1 of the sensitivity matrix) as a column-major array.
PetscErrorCode DenseMonodromy(PeriodicFlow &flow, Vec z0, PetscReal T, PetscReal beta, std::vector<PetscScalar> *a)
{
  OwnedMat S;
  OwnedVec zT;
  PetscInt n;
  const PetscScalar *s;
  PetscFunctionBeginUser;
  PetscCall(VecGetSize(z0, &n));
  PetscCall(VecDuplicate(z0, zT.out()));
  PetscCall(flow.CreateSensitivityMatrix(S.out()));
  PetscCall(flow.IntegrateWithMonodromy(z0, T, beta, zT, S));
  PetscInt lda;
  PetscCall(MatDenseGetLDA(S, &lda));
  PetscCall(MatDenseGetArrayRead(S, &s));
  a->resize((size_t)n * n);
  for (PetscInt j = 0; j < n; j++)
    for (PetscInt i = 0; i < n; i++) (*a)[(size_t)j * n + i] = s[(size_t)j * lda + i];
  PetscCall(MatDenseRestoreArrayRead(S, &s));
  PetscFunctionReturn(0);
}


// mu = b + sqrt(b^2 - 1), the member of the pair with |mu| >= 1.
std::complex<double> MuOfB(std::complex<double> b)
{
  const std::complex<double> r = std::sqrt(b * b - 1.0);
  return std::abs(b + r) >= std::abs(b - r) ? b + r : b - r;
}

// x -= Q Q^T x for an orthonormal set Q.
PetscErrorCode Project(const std::vector<Vec> &Q, Vec x)
{
  PetscFunctionBeginUser;
  for (int pass = 0; pass < 2; pass++)
    for (Vec q : Q) {
      PetscScalar d;
      PetscCall(VecDot(x, q, &d));
      PetscCall(VecAXPY(x, -d, q));
    }
  PetscFunctionReturn(0);
}

// Orthonormalise X in place against Q and itself (modified Gram-Schmidt, twice).
PetscErrorCode Orthonormalise(const std::vector<Vec> &Q, std::vector<OwnedVec> &X)
{
  std::vector<Vec> done = Q;
  PetscFunctionBeginUser;
  for (auto &x : X) {
    PetscCall(Project(done, x));
    PetscCall(VecNormalize(x, NULL));
    done.push_back(x);
  }
  PetscFunctionReturn(0);
}

// The trivial pair's subspace span{f(z0), dz0}, orthonormal.
PetscErrorCode TrivialSpace(PeriodicFlow &flow, Vec z0, Vec dz0, std::vector<OwnedVec> *Q)
{
  PetscFunctionBeginUser;
  Q->resize(2);
  for (auto &q : *Q) PetscCall(VecDuplicate(z0, q.out()));
  PetscCall(flow.Field(z0, (*Q)[0]));
  PetscCall(VecCopy(dz0, (*Q)[1]));
  PetscCall(Orthonormalise({}, *Q));
  PetscFunctionReturn(0);
}

// Chebyshev-filtered subspace iteration on B (block m, degree k per sweep),
// the trivial pair projected out: T_k(B) = (M^k + M^-k)/2 grows like |mu|^k
// for every multiplier off the unit circle (real pairs and quadruplets alike)
// and stays within [-1, 1] on it. After each sweep, Rayleigh-Ritz with B; a
// line per sweep with the products so far (monodromy actions) and the largest
// Ritz |mu|, until max_products.
PetscErrorCode ChebyshevSweeps(PeriodicFlow &flow, Orbit &o, PetscReal beta, PetscInt m, PetscInt k, PetscInt max_products, PetscInt point)
{
  MonodromyShell sh;
  std::vector<OwnedVec> Qd, X(m), Y0(m), Y1(m);
  OwnedVec t;
  PetscRandom rnd;
  PetscFunctionBeginUser;
  PetscCall(sh.Create(flow, o.z0, o.T, beta, true));
  PetscCall(TrivialSpace(flow, o.z0, o.dz0, &Qd));
  const std::vector<Vec> Q = {Qd[0], Qd[1]};
  PetscCall(PetscRandomCreate(PETSC_COMM_WORLD, &rnd));
  PetscCall(PetscRandomSetSeed(rnd, 20261126));
  PetscCall(PetscRandomSeed(rnd));
  for (PetscInt i = 0; i < m; i++) {
    PetscCall(VecDuplicate(o.z0, X[i].out()));
    PetscCall(VecDuplicate(o.z0, Y0[i].out()));
    PetscCall(VecDuplicate(o.z0, Y1[i].out()));
    PetscCall(VecSetRandom(X[i], rnd));
    PetscCall(VecShift(X[i], -0.5));
  }
  PetscCall(PetscRandomDestroy(&rnd));
  PetscCall(VecDuplicate(o.z0, t.out()));
  PetscCall(Orthonormalise(Q, X));
  const double t0 = Now();
  while (sh.Products() < max_products) {
    for (PetscInt i = 0; i < m; i++) { // X[i] <- T_k(B) X[i] by the three-term recurrence
      PetscCall(VecCopy(X[i], Y0[i]));
      PetscCall(MatMult(sh.Get(), Y0[i], Y1[i]));
      for (PetscInt j = 2; j <= k; j++) {
        PetscCall(MatMult(sh.Get(), Y1[i], t));
        PetscCall(VecAXPBY(t, -1.0, 2.0, Y0[i])); // t = 2 B y1 - y0
        PetscCall(Project(Q, t));
        PetscCall(VecSwap(Y0[i], Y1[i]));
        PetscCall(VecSwap(Y1[i], t));
      }
      PetscCall(VecCopy(Y1[i], X[i]));
    }
    PetscCall(Orthonormalise(Q, X));
    std::vector<PetscScalar> H((size_t)m * m);
    for (PetscInt j = 0; j < m; j++) {
      PetscCall(MatMult(sh.Get(), X[j], t));
      for (PetscInt i = 0; i < m; i++) PetscCall(VecDot(t, X[i], &H[(size_t)j * m + i]));
    }
    std::vector<std::complex<double>> b;
    PetscCall(DenseEigenvalues(m, H, &b));
    std::complex<double> lead = 0;
    for (auto bi : b)
      if (std::abs(MuOfB(bi)) > std::abs(lead)) lead = MuOfB(bi);
    const int kind = std::abs(lead.imag()) <= 1e-7 * std::abs(lead) ? (lead.real() > 0 ? 1 : -1) : 2;
    PetscCall(PetscPrintf(PETSC_COMM_WORLD, "bench: point %d method cheb:%d:%d modulus %.12f re %.12f im %.12f kind %d products %d seconds %.3f\n", (int)point,
                          (int)m, (int)k, std::abs(lead), lead.real(), lead.imag(), kind, (int)sh.Products(), Now() - t0));
  }
  PetscFunctionReturn(0);
}

// Shift-and-invert on B at a real shift sigma: Krylov-Schur on (B - sigma)^-1,
// inner GMRES (restart 200, no preconditioner) with the shell; the eigenvalue
// of B nearest sigma, the trivial pair deflated.
PetscErrorCode ShiftInvert(PeriodicFlow &flow, Orbit &o, PetscReal beta, PetscReal sigma, PetscReal ksp_rtol, PetscInt point)
{
  MonodromyShell sh;
  std::vector<OwnedVec> Qd;
  OwnedEPS eps;
  ST st;
  KSP ksp;
  PC pc;
  PetscInt nconv, its = 0;
  PetscFunctionBeginUser;
  PetscCall(sh.Create(flow, o.z0, o.T, beta, true));
  PetscCall(TrivialSpace(flow, o.z0, o.dz0, &Qd));
  std::vector<Vec> defl = {Qd[0], Qd[1]};
  const double t0 = Now();
  PetscCall(EPSCreate(PETSC_COMM_WORLD, eps.out()));
  PetscCall(EPSSetOperators(eps, sh.Get(), NULL));
  PetscCall(EPSSetProblemType(eps, EPS_NHEP));
  PetscCall(EPSSetType(eps, EPSKRYLOVSCHUR));
  PetscCall(EPSSetTarget(eps, sigma));
  PetscCall(EPSSetWhichEigenpairs(eps, EPS_TARGET_MAGNITUDE));
  PetscCall(EPSSetDimensions(eps, 4, 12, PETSC_DEFAULT));
  PetscCall(EPSSetTolerances(eps, 1e-10, 20));
  PetscCall(EPSSetDeflationSpace(eps, 2, defl.data()));
  PetscCall(EPSGetST(eps, &st));
  PetscCall(STSetType(st, STSINVERT));
  PetscCall(STSetMatMode(st, ST_MATMODE_SHELL));
  PetscCall(STGetKSP(st, &ksp));
  PetscCall(KSPSetType(ksp, KSPGMRES));
  PetscCall(KSPGMRESSetRestart(ksp, 200));
  PetscCall(KSPGetPC(ksp, &pc));
  PetscCall(PCSetType(pc, PCNONE));
  PetscCall(KSPSetTolerances(ksp, ksp_rtol, PETSC_DEFAULT, PETSC_DEFAULT, 20000));
  PetscCall(EPSSolve(eps));
  PetscCall(EPSGetConverged(eps, &nconv));
  PetscCall(EPSGetIterationNumber(eps, &its));
  std::complex<double> lead = NAN;
  for (PetscInt i = 0; i < nconv; i++) {
    PetscScalar br, bi;
    PetscCall(EPSGetEigenvalue(eps, i, &br, &bi));
    const std::complex<double> mu = MuOfB({br, bi});
    if (i == 0 || std::abs(mu) > std::abs(lead)) lead = mu;
  }
  const int kind = !(std::abs(lead) == std::abs(lead)) ? 0 : std::abs(lead.imag()) <= 1e-7 * std::abs(lead) ? (lead.real() > 0 ? 1 : -1) : 2;
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "bench: point %d method sinv:%g modulus %.12f re %.12f im %.12f kind %d products %d seconds %.3f converged %d outer %d\n",
                        (int)point, (double)sigma, std::abs(lead), lead.real(), lead.imag(), kind, (int)sh.Products(), Now() - t0, (int)nconv, (int)its));
  PetscFunctionReturn(0);
}
} // namespace

int main(int argc, char **argv)
{
  PetscCall(SlepcInitialize(&argc, &argv, NULL, "floquet_mf_methods: matrix-free Floquet candidates against the dense route\n"));
  {
    MPI_Comm comm = PETSC_COMM_WORLD;
    PetscMPIInt size;
    PetscCallMPI(MPI_Comm_size(comm, &size));
    PetscCheck(size == 1, comm, PETSC_ERR_SUP, "floquet_mf_methods runs on 1 rank");
    PetscCall(LogRegister());
    PetscCall(TSSymSplitRegister());
    PetscCall(TSRknRegister());
    NnmSetup nnm;
    PetscCall(nnm.ReadOptions(comm));
    FloquetOptions fo;
    PetscCall(FloquetOptionsFromOptions(comm, &fo));
    FloquetMfOptions mo;
    PetscCall(FloquetMfOptionsFromOptions(comm, &mo));
    PetscInt points[1000], npoints = 1000, dense[1000], ndense = 1000, wsites = 12;
    PetscReal wtol = 1e-10;
    char ks[1000][64];
    char *ksp[1000];
    PetscInt nks = 1000;
    PetscBool has_points, has_dense;
    PetscCall(PetscOptionsGetIntArray(NULL, NULL, "-bench_points", points, &npoints, &has_points));
    PetscCall(PetscOptionsGetIntArray(NULL, NULL, "-bench_dense", dense, &ndense, &has_dense));
    PetscReal dense_e[100];
    PetscInt ndense_e = 100;
    PetscCall(PetscOptionsGetRealArray(NULL, NULL, "-bench_dense_energies", dense_e, &ndense_e, NULL));
    PetscCall(PetscOptionsGetInt(NULL, NULL, "-bench_window_sites", &wsites, NULL));
    PetscInt cheb[3] = {8, 50, 20000}, ncheb = 3;
    PetscBool has_cheb;
    PetscCall(PetscOptionsGetIntArray(NULL, NULL, "-bench_cheb", cheb, &ncheb, &has_cheb));
    PetscReal sinv[10];
    PetscInt nsinv = 10;
    PetscCall(PetscOptionsGetRealArray(NULL, NULL, "-bench_sinv", sinv, &nsinv, NULL));
    PetscReal sinv_rtol = 1e-10;
    PetscCall(PetscOptionsGetReal(NULL, NULL, "-bench_sinv_rtol", &sinv_rtol, NULL));
    PetscCall(PetscOptionsGetReal(NULL, NULL, "-bench_window_tol", &wtol, NULL));
    for (PetscInt i = 0; i < 1000; i++) ksp[i] = ks[i];
    PetscCall(PetscOptionsGetStringArray(NULL, NULL, "-bench_ks", ksp, &nks, NULL));
    struct Ks {
      PetscInt ncv, max_it, warm, largest;
      std::vector<OwnedVec> w;
    };
    std::vector<Ks> kss;
    for (PetscInt i = 0; i < nks; i++) {
      int a, b, c, d = 0;
      PetscCheck(std::sscanf(ksp[i], "%d:%d:%d:%d", &a, &b, &c, &d) >= 3, comm, PETSC_ERR_USER, "-bench_ks: ncv:max_it:warm[:largest], got %s", ksp[i]);
      kss.push_back({a, b, c, d, {}});
      PetscCall(PetscFree(ksp[i]));
    }

    PetscCall(nnm.Build(comm, "-study continuation"));
    PeriodicFlow &flow = nnm.flow;
    const PetscInt N = nnm.lat.N(), n2 = 2 * N;
    OwnedVec u;
    PetscCall(VecDuplicate(nnm.modes.Insulated(), u.out()));
    PetscCall(VecCopy(nnm.modes.Insulated(), u));
    KeepOrbits keep;
    Branch b;
    double t0 = Now();
    PetscCall(ContinueBranch(nnm.shoot, u, 2 * PETSC_PI / nnm.modes.Named().insulated_omega, nnm.co, "insulated", &b, &keep));
    PetscCall(PetscPrintf(comm, "bench: branch N %d points %d seconds %.2f\n", (int)N, (int)b.energy.size(), Now() - t0));
    const PetscInt np = (PetscInt)keep.orbits.size();
    if (!has_points) {
      npoints = np;
      for (PetscInt p = 0; p < np; p++) points[p] = p;
    }
    for (PetscInt i = 0; i < ndense_e; i++) { // -bench_dense_energies: the points nearest these energies
      PetscInt best = 0;
      for (PetscInt p = 1; p < np; p++)
        if (std::abs(std::log(b.energy[p] / dense_e[i])) < std::abs(std::log(b.energy[best] / dense_e[i]))) best = p;
      if (!has_dense) ndense = 0, has_dense = PETSC_TRUE;
      dense[ndense++] = best;
    }
    auto want_dense = [&](PetscInt p) {
      if (!has_dense) return false;
      for (PetscInt i = 0; i < ndense; i++)
        if (dense[i] == p || dense[i] < 0) return true;
      return false;
    };

    OwnedVec zero, zT, x, y, ylin;
    PetscCall(VecDuplicate(keep.orbits[0].z0, zero.out()));
    PetscCall(VecSet(zero, 0));
    for (OwnedVec *v : {&zT, &x, &y, &ylin}) PetscCall(VecDuplicate(zero, v->out()));

    for (PetscInt q = 0; q < npoints; q++) {
      const PetscInt p = points[q];
      PetscCheck(p >= 0 && p < np, comm, PETSC_ERR_USER, "-bench_points: no point %d (branch has %d)", (int)p, (int)np);
      Orbit &o = keep.orbits[p];
      const PetscReal beta = flow.FloquetBeta(o.beta), E = b.energy[p], w = 2 * PETSC_PI / o.T;
      PetscCall(PetscPrintf(comm, "bench: point %d E %.6g omega %.9f\n", (int)p, (double)E, (double)w));
      // dense reference
      std::vector<PetscScalar> Md;
      if (want_dense(p)) {
        t0 = Now();
        PetscCall(DenseMonodromy(flow, o.z0, o.T, beta, &Md));
        double mod;
        std::complex<double> lead;
        int kind;
        PetscCall(DenseLeading(n2, Md, &mod, &lead, &kind));
        PetscCall(PetscPrintf(comm, "bench: point %d method dense modulus %.12f re %.12f im %.12f kind %d products %d seconds %.3f\n", (int)p, mod, lead.real(),
                              lead.imag(), kind, (int)n2, Now() - t0));
      }
      // Krylov-Schur on B
      for (Ks &k : kss) {
        char s[32];
        std::snprintf(s, sizeof s, "%d", (int)k.ncv);
        PetscCall(PetscOptionsSetValue(NULL, "-floquet_mf_eps_ncv", s));
        std::snprintf(s, sizeof s, "%d", (int)k.max_it);
        PetscCall(PetscOptionsSetValue(NULL, "-floquet_mf_eps_max_it", s));
        LeadingMultipliers r;
        FloquetMfOptions mk = mo;
        if (k.largest) mk.which = FloquetMfWhich::Largest;
        t0 = Now();
        PetscCall(FloquetLeading(flow, o.z0, o.T, beta, mk, &r, k.warm ? &k.w : nullptr, o.dz0));
        PetscCall(PetscPrintf(comm, "bench: point %d method %s:%d:%d:%d modulus %.12f re %.12f im %.12f kind %d products %d seconds %.3f\n", (int)p, k.largest ? "ksM" : "ks", (int)k.ncv,
                              (int)k.max_it, (int)k.warm, (double)r.max_modulus, (double)r.re[0], (double)r.im[0],
                              std::isnan(r.max_modulus) ? 0 : std::abs(r.im[0]) <= 1e-7 ? (r.re[0] > 0 ? 1 : -1) : 2, (int)r.products, Now() - t0));
      }
      if (has_cheb) PetscCall(ChebyshevSweeps(flow, o, beta, cheb[0], cheb[1], cheb[2], p));
      for (PetscInt i = 0; i < nsinv; i++) PetscCall(ShiftInvert(flow, o, beta, sinv[i], sinv_rtol, p));
      // localisation of E = M - M_lin: columns at the sites around the interface (argmax |u0|)
      if (wsites > 0) {
        const PetscScalar *z;
        PetscInt ic = 0;
        PetscCall(VecGetArrayRead(o.z0, &z));
        for (PetscInt i = 1; i < N; i++)
          if (std::abs(z[i]) > std::abs(z[ic])) ic = i;
        PetscCall(VecRestoreArrayRead(o.z0, &z));
        t0 = Now();
        std::vector<PetscInt> cols;
        std::vector<std::vector<PetscScalar>> Ecols;
        std::vector<double> colnorm;
        double mnorm = 0;
        for (PetscInt s = std::max<PetscInt>(0, ic - wsites); s <= std::min<PetscInt>(N - 1, ic + wsites); s++)
          for (PetscInt part : {0, 1}) {
            const PetscInt j = s + part * N;
            PetscCall(VecSet(x, 0));
            PetscCall(VecSetValue(x, j, 1.0, INSERT_VALUES));
            PetscCall(VecAssemblyBegin(x));
            PetscCall(VecAssemblyEnd(x));
            PetscCall(flow.IntegrateWithTangent(o.z0, o.T, beta, x, 0, 0, zT, y));
            PetscCall(flow.IntegrateWithTangent(zero, o.T, 0, x, 0, 0, zT, ylin));
            PetscReal ny, ne;
            PetscCall(VecNorm(y, NORM_2, &ny));
            PetscCall(VecAXPY(y, -1.0, ylin));
            PetscCall(VecNorm(y, NORM_2, &ne));
            mnorm = std::max(mnorm, (double)ny);
            const PetscScalar *ya;
            PetscCall(VecGetArrayRead(y, &ya));
            cols.push_back(j), Ecols.emplace_back(ya, ya + n2), colnorm.push_back(ne);
            PetscCall(VecRestoreArrayRead(y, &ya));
          }
        const double tw = Now() - t0;
        // the window: sites whose u or v column has |E e_j| > wtol |M|
        std::vector<PetscInt> win; // its state indices, in the order of the columns of a
        PetscInt dmax = -1;
        for (size_t c = 0; c < cols.size(); c++)
          if (colnorm[c] > wtol * mnorm) dmax = std::max(dmax, std::abs(cols[c] % N - ic));
        std::string prof;
        for (PetscInt d = 0; d <= wsites; d++) {
          double m = 0;
          for (size_t c = 0; c < cols.size(); c++)
            if (std::abs(cols[c] % N - ic) == d) m = std::max(m, colnorm[c] / mnorm);
          char s[32];
          std::snprintf(s, sizeof s, "%s%.1e", d ? "," : "", m);
          prof += s;
        }
        // numerical rank of the window's columns of E (singular values above wtol |M|)
        std::vector<PetscScalar> a;
        PetscInt nc = 0;
        for (size_t c = 0; c < cols.size(); c++)
          if (std::abs(cols[c] % N - ic) <= dmax) a.insert(a.end(), Ecols[c].begin(), Ecols[c].end()), win.push_back(cols[c]), nc++;
        PetscInt rank = 0;
        if (nc > 0) {
          PetscBLASInt m_, n_, lwork, info, one = 1;
          PetscCall(PetscBLASIntCast(n2, &m_));
          PetscCall(PetscBLASIntCast(nc, &n_));
          PetscCall(PetscBLASIntCast(10 * (n2 + nc), &lwork));
          std::vector<PetscReal> sv(nc), work(10 * (n2 + nc));
          std::vector<PetscScalar> acopy = a;
          PetscScalar dummy;
          PetscCallBLAS("LAPACKgesvd", LAPACKgesvd_("N", "N", &m_, &n_, acopy.data(), &m_, sv.data(), &dummy, &one, &dummy, &one, work.data(), &lwork, &info));
          PetscCheck(info == 0, comm, PETSC_ERR_LIB, "gesvd failed: %d", (int)info);
          for (PetscReal s : sv) rank += s > wtol * mnorm;
        }
        PetscCall(PetscPrintf(comm, "bench: point %d window half_width %d columns %d rank %d products %d seconds %.3f profile %s\n", (int)p, (int)dmax, (int)nc,
                              (int)rank, (int)(2 * cols.size()), tw, prof.c_str()));
        // what the window model returns: eig(M_lin + E P_W P_W^T) against the dense M
        if (!Md.empty() && nc > 0) {
          std::vector<PetscScalar> Ml;
          t0 = Now();
          PetscCall(DenseMonodromy(flow, zero, o.T, 0, &Ml));
          double maxout = 0, maxin = 0; // |M - model| outside and inside the window's columns, relative to |M|
          for (PetscInt j = 0; j < n2; j++) {
            const bool in = std::abs(j % N - ic) <= dmax;
            if (in) {
              const PetscInt k = (PetscInt)(std::find(win.begin(), win.end(), j) - win.begin());
              for (PetscInt i = 0; i < n2; i++) {
                Ml[(size_t)j * n2 + i] += a[(size_t)k * n2 + i];
                maxin = std::max(maxin, std::abs(Md[(size_t)j * n2 + i] - Ml[(size_t)j * n2 + i]));
              }
            } else
              for (PetscInt i = 0; i < n2; i++) maxout = std::max(maxout, std::abs(Md[(size_t)j * n2 + i] - Ml[(size_t)j * n2 + i]));
          }
          double mod;
          std::complex<double> lead;
          int kind;
          PetscCall(DenseLeading(n2, Ml, &mod, &lead, &kind));
          PetscCall(PetscPrintf(comm, "bench: point %d method window modulus %.12f re %.12f im %.12f kind %d products %d seconds %.3f outside %.2e inside %.2e\n", (int)p, mod,
                                lead.real(), lead.imag(), kind, (int)nc, Now() - t0, maxout / mnorm, maxin / mnorm));
        }
      }
    }
  }
  PetscCall(SlepcFinalize());
  return 0;
}
