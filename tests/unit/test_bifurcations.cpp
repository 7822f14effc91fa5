// Bifurcations along NNM branches against known truth: the Krein rule on
// constructed symplectic matrices (a Hamiltonian-Hopf collision where linear
// algebra puts it), the pitchfork of two coupled dimers where averaging puts
// it, and the energy folds of a folded branch (extrema of E).
#include "core/errors.hpp"
#include "core/gather.hpp"
#include "dimers.hpp"
#include "branch_record.hpp"
#include "helpers.hpp"
#include "stability/bifurcation_locator.hpp"
#include "stability/bifurcations.hpp"
#include "stability/branch_switch.hpp"
#include <petscmat.h>
#include <slepceps.h>
#include <algorithm>
#include <cmath>
#include <complex>
#include <numeric>

using namespace nltopo;
using namespace nltopo::test;

namespace {

// exp(A) of a small dense matrix (row-major n x n) by scaling and squaring of its Taylor series.
std::vector<PetscReal> Expm(std::vector<PetscReal> A, int n)
{
  auto mul = [n](const std::vector<PetscReal> &x, const std::vector<PetscReal> &y) {
    std::vector<PetscReal> z(n * n, 0);
    for (int i = 0; i < n; i++)
      for (int k = 0; k < n; k++)
        for (int j = 0; j < n; j++) z[i * n + j] += x[i * n + k] * y[k * n + j];
    return z;
  };
  PetscReal norm = 0;
  for (PetscReal a : A) norm = std::max(norm, std::abs(a));
  int sq = 0;
  while (norm * n > 0.5) norm /= 2, sq++;
  for (PetscReal &a : A) a = std::ldexp(a, -sq);
  std::vector<PetscReal> E(n * n, 0), term(n * n, 0);
  for (int i = 0; i < n; i++) E[i * n + i] = term[i * n + i] = 1;
  for (int k = 1; k < 30; k++) {
    term = mul(term, A);
    for (int i = 0; i < n * n; i++) term[i] /= k, E[i] += term[i];
  }
  for (int s = 0; s < sq; s++) E = mul(E, E);
  return E;
}

// The monodromy over T = 1 of H = p^T D p / 2 + q^T K q / 2 in canonical
// z = (q1, q2, q3, p1, p2, p3): oscillators 1 and 2 (D = diag(1, sign),
// K = [[1, eps], [eps, sign (1 + s)]]) and a free particle 3, whose double
// multiplier at +1 plays the trivial pair of an NNM. sign = -1 gives oscillator
// 2 negative energy, hence the opposite Krein signature; its pairs then leave
// the circle where the eigenvalues (1 + b -+ sqrt((1 - b)^2 - 4 eps^2)) / 2 of
// D K turn complex, |s| < 2 eps. sign = +1: D K symmetric, never.
FloquetResult Constructed(PetscReal s, PetscReal sign, PetscReal eps)
{
  const int n = 6;
  std::vector<PetscReal> A(n * n, 0);
  const PetscReal D[3] = {1, sign, 1};
  const PetscReal K[3][3] = {{1, eps, 0}, {eps, sign * (1 + s), 0}, {0, 0, 0}};
  for (int i = 0; i < 3; i++) {
    A[i * n + 3 + i] = D[i];                                   // dq/dt = D p
    for (int j = 0; j < 3; j++) A[(3 + i) * n + j] = -K[i][j]; // dp/dt = -K q
  }
  const std::vector<PetscReal> M = Expm(A, n);
  Mat m;
  EPS e;
  MatCreateSeqDense(PETSC_COMM_SELF, n, n, NULL, &m);
  for (int i = 0; i < n; i++)
    for (int j = 0; j < n; j++) MatSetValue(m, i, j, M[i * n + j], INSERT_VALUES);
  MatAssemblyBegin(m, MAT_FINAL_ASSEMBLY);
  MatAssemblyEnd(m, MAT_FINAL_ASSEMBLY);
  EPSCreate(PETSC_COMM_SELF, &e);
  EPSSetOperators(e, m, NULL);
  EPSSetProblemType(e, EPS_NHEP);
  EPSSetType(e, EPSLAPACK);
  EPSSetDimensions(e, n, PETSC_DEFAULT, PETSC_DEFAULT);
  EPSSolve(e);
  Vec xr, xi;
  MatCreateVecs(m, &xr, &xi);
  FloquetResult r;
  for (int k = 0; k < n; k++) {
    PetscScalar kr, ki;
    const PetscScalar *a, *b;
    EPSGetEigenpair(e, k, &kr, &ki, xr, xi);
    if (ki == 0) VecZeroEntries(xi);
    VecGetArrayRead(xr, &a);
    VecGetArrayRead(xi, &b);
    PetscReal sums[2];
    KreinSums(a, b, 3, sums);
    const PetscReal kap = sums[1] > 0 ? sums[0] / sums[1] : 0;
    std::vector<std::complex<PetscReal>> v;
    if (ki > 0 && std::abs(std::hypot(kr, ki) - 1) < 1e-9) { // the circle members' eigenvectors (FloquetResult::vectors)
      PetscReal nrm = std::sqrt(sums[1]);
      for (int i = 0; i < n; i++) v.push_back(std::complex<PetscReal>(a[i], b[i]) / nrm);
    }
    r.vectors.push_back(v);
    VecRestoreArrayRead(xi, &b);
    VecRestoreArrayRead(xr, &a);
    r.re.push_back(kr);
    r.im.push_back(ki);
    r.kappa.push_back(kap);
    r.krein.push_back(std::abs(kap) < 1e-6 ? 0 : (kap > 0 ? 1 : -1));
    r.edge.push_back(1);
  }
  VecDestroy(&xr);
  VecDestroy(&xi);
  EPSDestroy(&e);
  MatDestroy(&m);
  return r;
}

// The coupled dimers, their upper (3) or lower (2) optical NNM continued up
// to Omega^2 = lambda_hi + 3 kappa, and the events located along it.
struct DimerEvents {
  CoupledDimers d;
  PetscReal lam_hi = 0, kappa = 0;
  BifurcationOptions bo;
  BifurcationLocator loc;
  PetscErrorCode Setup()
  {
    PetscFunctionBeginUser;
    PetscCall(d.Setup());
    const auto &w = d.modes.Omega();
    lam_hi = w[3] * w[3], kappa = (lam_hi - w[2] * w[2]) / 2;
    bo.tol = 1e-9;
    PetscCall(loc.Setup(d.shoot, FloquetOptions(), bo));
    PetscFunctionReturn(0);
  }
  PetscErrorCode Locate(PetscInt j, Branch *b, std::vector<BifurcationEvent> *ev)
  {
    Record rec(d.flow);
    PetscFunctionBeginUser;
    PetscCall(d.Continue(j, std::sqrt(lam_hi + 3 * kappa), &rec, b));
    PetscCall(loc.Locate(*b, rec.c.re, rec.c.im, rec.c.edge, "dimers", ev));
    PetscFunctionReturn(0);
  }
};

} // namespace

TEST_CASE("the Krein rule on constructed symplectic matrices: opposite signatures leave the circle where theory says, equal ones pass", "[bifurcations]")
{
  const PetscReal eps = 0.05, tol = 1e-9;
  // equal signatures: every multiplier stays on the circle through the closest approach, no event
  PetscReal worst = 0;
  for (PetscReal s = -0.3; s <= 0.3; s += 0.01) {
    const FloquetResult r = Constructed(s, +1, eps);
    for (size_t k = 0; k < r.re.size(); k++) worst = std::max(worst, std::hypot(r.re[k], r.im[k]) - 1);
    REQUIRE(OutsideMultipliers(r, 1e-6).empty());
    PetscInt kr[2];
    CollidingSignatures(r, EventKind::HamiltonianHopf, 1.0, 1e-6, kr);
    REQUIRE(kr[0] == kr[1]);                                                   // both pairs near e^{i} carry the same signature ...
    REQUIRE(KreinCollisionOutcome(kr[0], kr[1]) == EventKind::KreinCollision); // ... so they pass
  }
  REQUIRE(worst < 1e-10);
  // opposite signatures: the pairs leave the circle at s = -2 eps (and return at +2 eps), located to tol
  const FloquetResult before = Constructed(-0.3, -1, eps);
  PetscInt kr[2];
  CollidingSignatures(before, EventKind::HamiltonianHopf, 1.0, 1e-6, kr);
  REQUIRE(kr[0] * kr[1] == -1);
  REQUIRE(KreinCollisionOutcome(kr[0], kr[1]) == EventKind::HamiltonianHopf);
  const PetscReal angle_tol = 0.15;
  auto probe = [&](PetscReal sigma, BifurcationSample *x) -> PetscErrorCode {
    const PetscReal s = -0.3 + 0.6 * sigma;
    x->sigma = sigma, x->omega = s, x->energy = 1; // "omega" carries s: the tolerance applies to it
    x->fr = Constructed(s, -1, eps);
    x->out = OutsideMultipliers(x->fr, 1e-9); // (LAPACK's rounding near the defective collision is ~1e-11)
    return 0;
  };
  BifurcationSample a, c;
  PCHK(probe(0, &a));
  PCHK(probe(0.5, &c));
  REQUIRE(a.out.empty());
  REQUIRE(c.out.size() == 1);
  REQUIRE(c.out[0].kind == EventKind::HamiltonianHopf);
  auto same = [&](const BifurcationSample &x, const BifurcationSample &y) { return SameOutside(x.out, y.out, angle_tol); };
  auto G = [&](const BifurcationSample &x, const BifurcationSample &y, const BifurcationSample &z) {
    const auto ch = OutsideChanges(x.out, y.out, angle_tol);
    return ch.empty() ? NAN : CollisionFunction(z.fr, ch[0].first.kind, ch[0].first.angle, 1e-9, angle_tol);
  };
  PetscInt probes;
  bool conv;
  PCHK(LocateChange(probe, same, G, tol, 60, &a, &c, &probes, &conv));
  INFO("located between s = " << a.omega << " and " << c.omega << " in " << probes << " probes");
  REQUIRE(conv);
  REQUIRE(a.omega <= -2 * eps + tol);
  REQUIRE(c.omega >= -2 * eps - tol);
  REQUIRE(c.omega - a.omega <= tol);
  REQUIRE(probes < 20); // bisection alone needs 29 from a bracket of 0.3 to 1e-9
  // and the return to the circle at +2 eps
  PCHK(probe(0.5, &a));
  PCHK(probe(1, &c));
  PCHK(LocateChange(probe, same, G, tol, 60, &a, &c, &probes, &conv));
  REQUIRE(conv);
  REQUIRE(std::abs(0.5 * (a.omega + c.omega) - 2 * eps) < tol);
}

TEST_CASE("Krein collisions of equal signature: two uncoupled oscillators pass where their frequencies meet, coupled ones avoid each other", "[bifurcations]")
{
  // Oscillator 1 at angle 1 and oscillator 2 at sqrt(1 + s) (T = 1): their
  // pairs meet at s = 0 with the same signature. Uncoupled (eps = 0) they pass
  // there; coupled by eps they avoid each other, the gap at s = 0 being
  // sqrt(1 + eps) - sqrt(1 - eps) (the eigenvalues of D K are 1 + s/2 -+
  // sqrt(s^2/4 + eps^2)).
  const PetscReal tol = 1e-9;
  for (PetscReal eps : {0.0, 0.05}) {
    auto probe = [&](PetscReal sigma, BifurcationSample *x) -> PetscErrorCode {
      const PetscReal s = -0.3 + 0.6 * sigma;
      x->sigma = sigma, x->omega = s, x->energy = 1; // "omega" carries s: the tolerance applies to it
      x->fr = Constructed(s, +1, eps);
      return 0;
    };
    BifurcationSample a0, c0, a, c;
    PCHK(probe(0, &a0));
    PCHK(probe(1, &c0));
    const auto cand = PassCandidates(a0.fr, c0.fr, 1e-9);
    REQUIRE(cand.size() == 1);
    const auto circle = UpperCircle(a0.fr, 1e-9);
    REQUIRE(circle.size() == 2);
    PetscInt probes;
    TrackedOutcome out;
    PCHK(LocatePass(probe, a0, c0, circle[0].first, circle[1].first, tol, 60, &a, &c, &probes, &out));
    INFO("eps " << eps << ": bracket [" << a.omega << ", " << c.omega << "], |difference| " << a.aux << " " << c.aux << ", " << probes << " probes");
    if (eps == 0) {
      REQUIRE(out == TrackedOutcome::Crossed);
      REQUIRE(a.omega <= tol);
      REQUIRE(c.omega >= -tol);
      REQUIRE(c.omega - a.omega <= tol);
      REQUIRE(probes < 16); // the difference of angles is smooth through the pass: secant steps (bisection needs 30)
      REQUIRE(a.fr.kappa[a.aux_index] * c.fr.kappa[c.aux_index] > 0);
    } else {
      REQUIRE(out == TrackedOutcome::Avoided);
      // where the eigenvectors' overlaps with those at s = -0.3 tie, the
      // difference jumps by twice the gap there, which is never below the
      // closest approach at s = 0
      const PetscReal sj = a.omega, h = std::sqrt(sj * sj / 4 + eps * eps);
      const PetscReal gap = std::sqrt(1 + sj / 2 + h) - std::sqrt(1 + sj / 2 - h), closest = std::sqrt(1 + eps) - std::sqrt(1 - eps);
      REQUIRE(std::abs(std::abs(a.aux) - gap) < 1e-6 * gap);
      REQUIRE(std::abs(std::abs(c.aux) - gap) < 1e-6 * gap);
      REQUIRE(gap >= closest);
    }
  }
}

TEST_CASE("internal resonances: a pair crosses exp(2 pi i/3) where its angle is 2 pi/3, and the orbit's harmonics drive odd orders with nu^q = -1 only",
          "[bifurcations]")
{
  // oscillator 2 at angle sqrt(1 + s): the root e^{2 pi i/3} at s* = (2 pi/3)^2 - 1
  const PetscReal tol = 1e-10, sstar = std::pow(2 * PETSC_PI / 3, 2) - 1;
  auto probe = [&](PetscReal sigma, BifurcationSample *x) -> PetscErrorCode {
    const PetscReal s = 3 + sigma;
    x->sigma = sigma, x->omega = s, x->energy = 1;
    x->fr = Constructed(s, +1, 0);
    return 0;
  };
  const auto roots = ResonanceRoots(5);
  REQUIRE(roots == std::vector<std::pair<PetscInt, PetscInt>>{{1, 5}, {1, 4}, {1, 3}, {2, 5}});
  BifurcationSample a0, c0, a, c;
  PCHK(probe(0, &a0));
  PCHK(probe(1, &c0));
  const PetscReal th = 2 * PETSC_PI / 3;
  REQUIRE(CountBelow(a0.fr, th, 1e-9) == 2);
  REQUIRE(CountBelow(c0.fr, th, 1e-9) == 1);
  PetscInt moving = -1;
  for (const auto &[k, angle] : UpperCircle(a0.fr, 1e-9))
    if (angle > 1.5) moving = k;
  PetscInt probes;
  TrackedOutcome out;
  PCHK(LocateRootCrossing(probe, a0, c0, moving, th, tol, 60, &a, &c, &probes, &out));
  INFO("bracket [" << a.omega << ", " << c.omega << "] against s* = " << sstar << ", " << probes << " probes");
  REQUIRE(out == TrackedOutcome::Crossed);
  REQUIRE(a.omega <= sstar + tol);
  REQUIRE(c.omega >= sstar - tol);
  REQUIRE(probes < 16); // bisection needs 34
  // the other member (angle 1) does not cross it
  for (const auto &[k, angle] : UpperCircle(a0.fr, 1e-9))
    if (k != moving) {
      PCHK(LocateRootCrossing(probe, a0, c0, k, th, tol, 60, &a, &c, &probes, &out));
      REQUIRE(out == TrackedOutcome::NoCrossing);
    }
  // The selection rule on nu = e^{i pi n/q}: driven iff q is odd and n is odd.
  for (PetscInt q : {3, 4, 5, 7})
    for (PetscInt n = 1; n < 2 * q; n++) {
      if (std::gcd(n, q) != 1) continue;
      const PetscReal phi = PETSC_PI * n / q;
      INFO("q " << q << " n " << n);
      REQUIRE(ResonanceDriven(q, std::cos(phi), std::sin(phi)) == (q % 2 == 1 && n % 2 == 1));
    }
}

TEST_CASE("an NNM of the lattice has the half-period symmetry, so its monodromy is the square of the half-period one", "[bifurcations]")
{
  // The selection rule of internal resonances rests on this: z(T/2) = -z(0)
  // and the tangent is T/2-periodic (the force is odd in u), so M = M_{T/2}^2.
  NnmFixture f;
  LatticeParams p;
  p.cells = 1; // interface layout, N = 6
  PCHK(f.Setup(p));
  ContinuationOptions co;
  co.verbose = PETSC_FALSE;
  co.energy_max = 5;
  Branch b;
  PCHK(f.Continue(3, co, &b));
  const PetscInt N = f.lat.N(), np = (PetscInt)b.energy.size();
  REQUIRE(np > 3);
  const std::vector<PetscReal> rows = AllRows(b);
  OwnedVec z0, zh, zT;
  OwnedMat Sh, S;
  PCHK(f.lat.CreateStateVector(z0.out()));
  PCHK(VecDuplicate(z0, zh.out()));
  PCHK(VecDuplicate(z0, zT.out()));
  PCHK(f.flow.CreateSensitivityMatrix(Sh.out()));
  PCHK(f.flow.CreateSensitivityMatrix(S.out()));
  const PetscInt k = np - 1; // the most nonlinear orbit
  PCHK(StateFromRow(f.lat, rows.data() + (size_t)k * 2 * N, z0));
  const PetscReal T = b.period[k], beta = f.flow.FloquetBeta(b.beta[k]);
  {
    PeriodMultipleScope half(f.flow, 1, 2); // half the steps: the orbit's own step size
    PCHK(f.flow.IntegrateWithMonodromy(z0, 0.5 * T, beta, zh, Sh));
  }
  PCHK(f.flow.IntegrateWithMonodromy(z0, T, beta, zT, S));
  PetscReal n0, d;
  PCHK(VecNorm(z0, NORM_2, &n0));
  PCHK(VecAXPY(zh, 1.0, z0));
  PCHK(VecNorm(zh, NORM_2, &d));
  INFO("E " << b.energy[k] << ": |z(T/2) + z0| / |z0| = " << d / n0);
  REQUIRE(d < 1e-9 * n0); // to the Newton tolerance: the discrete step commutes with z -> -z
  // M - Mh^2 on the state block (the sensitivity matrices' first 2N columns)
  std::vector<PetscReal> M, H;
  for (auto [mat, out] : {std::pair<Mat, std::vector<PetscReal> *>{S, &M}, {Sh, &H}}) {
    for (PetscInt col = 0; col < 2 * N; col++) {
      Vec c;
      std::vector<PetscReal> x;
      PCHK(MatDenseGetColumnVecRead(mat, col, &c));
      PCHK(GatherVec(c, true, &x));
      PCHK(MatDenseRestoreColumnVecRead(mat, col, &c));
      out->insert(out->end(), x.begin(), x.begin() + 2 * N);
    }
  }
  PetscReal err = 0, norm = 0;
  const PetscInt n = 2 * N; // column-major: X[r + c n]
  for (PetscInt r = 0; r < n; r++)
    for (PetscInt c = 0; c < n; c++) {
      PetscReal h2 = 0;
      for (PetscInt j = 0; j < n; j++) h2 += H[r + j * n] * H[j + c * n];
      err = std::max(err, std::abs(M[r + c * n] - h2));
      norm = std::max(norm, std::abs(M[r + c * n]));
    }
  INFO("max |M - Mh^2| = " << err << " against max |M| = " << norm);
  REQUIRE(err < 1e-10 * norm);
}

TEST_CASE("the pitchfork of two coupled dimers is located where averaging puts it, and breaks their mirror symmetry", "[bifurcations][once]")
{
  // [once]: at 2 ranks the same location runs in "branch switching at the dimer pitchfork ..." below,
  // which switches at the located point.
  DimerEvents de;
  PCHK(de.Setup());
  const CoupledDimers &d = de.d;
  const PetscReal lam_hi = de.lam_hi, kappa = de.kappa;
  for (PetscInt j : {2, 3}) {
    Branch b;
    std::vector<BifurcationEvent> ev;
    PCHK(de.Locate(j, &b, &ev));
    INFO("mode " << j << ": " << ev.size() << " events");
    if (j == 2) { // the lower NNM: stable at every amplitude, and its trivial pair never triggers an event
      REQUIRE(ev.empty());
      continue;
    }
    REQUIRE(ev.size() == 1);
    const BifurcationEvent &e = ev[0];
    REQUIRE(e.kind == EventKind::BranchPoint);
    REQUIRE(e.direction == 1);
    REQUIRE(e.omega_bracket <= de.bo.tol);
    // First-order averaging: the real pair leaves +1 at Omega^2 - lambda_hi = kappa; its error is O(kappa / Omega^2) ~ 1e-2.
    const PetscReal onset = (e.omega * e.omega - lam_hi) / kappa;
    INFO("located onset s/kappa = " << onset);
    REQUIRE(std::abs(onset - 1) < 0.05);
    REQUIRE(std::abs(e.mu_re - 1) < 1e-3);
    REQUIRE(e.mu_im == 0);
    REQUIRE(e.krein[0] * e.krein[1] == -1); // the pair at +1: conjugate members
    // The critical eigenvector has the other mirror parity than the orbit (u_i <-> u_{N-1-i}):
    // the family it starts breaks the symmetry.
    const PetscInt N = d.lat.N();
    const std::vector<PetscReal> z0 = AllRows(b);
    const PetscReal *u = z0.data() + (size_t)e.point * 2 * N;
    PetscReal even = 0, odd = 0, veven = 0, vodd = 0;
    for (PetscInt i = 0; i < N; i++) {
      even += std::pow(u[i] + u[N - 1 - i], 2), odd += std::pow(u[i] - u[N - 1 - i], 2);
      const PetscReal *x = e.vector.data();
      veven += std::pow(x[i] + x[N - 1 - i], 2) + std::pow(x[N + i] + x[2 * N - 1 - i], 2);
      vodd += std::pow(x[i] - x[N - 1 - i], 2) + std::pow(x[N + i] - x[2 * N - 1 - i], 2);
    }
    const bool orbit_even = even > odd;
    INFO("orbit even/odd " << even << " " << odd << ", vector even/odd " << veven << " " << vodd);
    REQUIRE(std::min(even, odd) < 1e-20 * std::max(even, odd) + 1e-24);
    REQUIRE((orbit_even ? veven : vodd) < 1e-12 * (veven + vodd));
  }
}

TEST_CASE("energy folds of a folded branch are located at the extrema of E, and the pair crossing +1 there is not a branch point", "[bifurcations]")
{
  // Mode 0 of the N = 6 interface lattice: E rises to ~66, falls to ~8, rises again (test_continuation.cpp;
  // to 1e3 it folds twice more).
  LatticeParams p;
  p.cells = 1;
  NnmFixture nf;
  PCHK(nf.Setup(p));
  const PetscInt N = nf.lat.N();
  ContinuationOptions co;
  co.verbose = PETSC_FALSE;
  co.energy_max = 300;
  Record rec(nf.flow);
  Branch b;
  PCHK(nf.Continue(0, co, &b, &rec));
  BifurcationLocator loc;
  std::vector<BifurcationEvent> ev;
  PCHK(LocateRecorded(loc, nf.shoot, b, rec, "folds", &ev));
  std::vector<const BifurcationEvent *> folds;
  for (const BifurcationEvent &e : ev)
    if (e.kind == EventKind::Fold) folds.push_back(&e);
  REQUIRE(folds.size() == 2);
  for (const BifurcationEvent &e : ev) // the change of stability at a fold is the fold's: no other event at it
    for (const BifurcationEvent *f : folds) {
      INFO("event kind " << (int)e.kind << " at omega " << e.omega << ", fold at " << f->omega);
      if (&e != f) REQUIRE(std::abs(e.s - f->s) > 1e-6 * f->s);
    }
  REQUIRE(folds[0]->direction == 1);  // maximum of E first
  REQUIRE(folds[1]->direction == -1); // then the minimum
  for (const BifurcationEvent *f : folds) {
    REQUIRE(f->omega_bracket <= 1e-9); // LocateRecorded's tolerance
    // an extremum of E along the branch: beyond every stored neighbour
    for (PetscInt k = std::max<PetscInt>(0, f->point - 2); k <= std::min<PetscInt>(f->point + 3, (PetscInt)b.energy.size() - 1); k++) {
      INFO("fold at E " << f->energy << ", point " << k << " E " << b.energy[k]);
      REQUIRE(f->direction * (f->energy - b.energy[k]) >= -1e-9 * f->energy);
    }
    REQUIRE(f->vector.size() == (size_t)(2 * N)); // the family tangent there
  }
}

TEST_CASE(
    "branch switching at the dimer pitchfork: the new family breaks the mirror symmetry, its asymmetry grows like the root of the distance, and it meets the parent at the located point",
    "[bifurcations][switch]")
{
  DimerEvents de;
  PCHK(de.Setup());
  CoupledDimers &d = de.d;
  BifurcationLocator &loc = de.loc;
  Branch parent;
  std::vector<BifurcationEvent> ev;
  PCHK(de.Locate(3, &parent, &ev));
  REQUIRE(ev.size() == 1);
  const PetscInt N = d.lat.N();
  OwnedVec Xs;
  bool found;
  PCHK(d.shoot.CreateUnknowns(Xs.out()));
  PCHK(loc.OrbitAt(ev[0].point, ev[0].sigma, Xs, &found));
  REQUIRE(found);
  for (PetscInt sign : {1, -1}) {
    Branch start, b;
    bool pinned;
    PetscReal away;
    PCHK(StartSwitchedBranch(d.shoot, Xs, ev[0], 0.02, sign, &start, &pinned, &away));
    REQUIRE(pinned);
    INFO("sign " << sign << ": first step " << away << " along the critical eigenvector");
    REQUIRE(away > 0.9);
    ContinuationOptions co;
    co.verbose = PETSC_FALSE;
    co.max_change = 0.05;
    co.max_points = 25;
    PCHK(ContinueBranch(d.shoot, nullptr, 0, co, "switched", &b, nullptr, &start));
    REQUIRE(b.energy.size() == 25);
    // every orbit: the parity the parent has not (asymmetry), relative to |u0|
    const std::vector<PetscReal> z0 = AllRows(b);
    std::vector<PetscReal> asym;
    for (size_t k = 0; k < b.energy.size(); k++) {
      const PetscReal *u = z0.data() + k * 2 * N;
      PetscReal even = 0, all = 0;
      for (PetscInt i = 0; i < N; i++) even += std::pow(0.5 * (u[i] + u[N - 1 - i]), 2), all += u[i] * u[i];
      asym.push_back(std::sqrt(even / all)); // the parent (mode 3) is mirror-odd: this is 0 on it
    }
    INFO("asymmetry at the branch point " << asym[0] << ", then " << asym[1] << " " << asym[5] << " " << asym.back());
    // point 0 is the parent's orbit at the located point, symmetric up to Newton's
    // tolerance amplified by the Jacobian singular in the null direction there
    REQUIRE(asym[0] < 1e-6);
    for (size_t k = 1; k < asym.size(); k++) REQUIRE(asym[k] > 1e-3); // off the parent family
    // a pitchfork: asym^2 is linear in the frequency shift omega - omega*, so that its
    // fit over the first points returns to zero at the located point
    PetscReal sx = 0, sy = 0, sxx = 0, sxy = 0;
    const int m = 5;
    for (int k = 1; k <= m; k++) {
      const PetscReal x = b.omega[k] - ev[0].omega, y = asym[k] * asym[k];
      sx += x, sy += y, sxx += x * x, sxy += x * y;
    }
    const PetscReal slope = (m * sxy - sx * sy) / (m * sxx - sx * sx), icpt = (sy - slope * sx) / m;
    const PetscReal x0 = -icpt / slope; // where the fitted asym^2 vanishes, relative to omega*
    INFO("asym^2 = " << slope << " (omega - omega*) + " << icpt << ": zero at omega* + " << x0 << ", first shift " << b.omega[1] - ev[0].omega);
    REQUIRE(std::abs(x0) < 0.05 * std::abs(b.omega[m] - ev[0].omega));
    // the orbits close: each is a fixed point of the period map to the Newton tolerance
    OwnedVec z, zT;
    PCHK(d.lat.CreateStateVector(z.out()));
    PCHK(VecDuplicate(z, zT.out()));
    PetscReal worst = 0;
    for (size_t k = 1; k < b.energy.size(); k += 6) {
      PCHK(StateFromRow(d.lat, z0.data() + k * 2 * N, z));
      PCHK(d.flow.Integrate(z, b.period[k], b.beta[k], zT));
      PetscReal nz0, dz;
      PCHK(VecNorm(z, NORM_2, &nz0));
      PCHK(VecAXPY(zT, -1.0, z));
      PCHK(VecNorm(zT, NORM_2, &dz));
      worst = std::max(worst, dz / nz0);
    }
    INFO("worst closure " << worst);
    REQUIRE(worst < 1e-9);
  }
}

namespace {

// The message of fn's error ("" when it succeeds).
template <typename Fn> std::string ErrorOf(Fn &&fn)
{
  PetscErrorCode code;
  char msg[512];
  PCHK(CaptureError(fn, &code, msg, sizeof msg));
  return code ? msg : "";
}

} // namespace

TEST_CASE("-cont_switch items: parsed by index or by kind and omega, an event selected by kind and nearest omega, refused with one line when none or two fit",
          "[bifurcations][switch][switch_spec]")
{
  const MPI_Comm self = PETSC_COMM_SELF;
  std::vector<SwitchSpec> sp;
  PCHK(ParseSwitchSpecs(self, {"insulated:12", "insulated:bp@2.418", "mode3_bp4_plus:period_doubling@1.5e0", "3:pd@2"}, &sp));
  REQUIRE(sp.size() == 4);
  REQUIRE((sp[0].branch == "insulated" && sp[0].ByIndex() && sp[0].index == 12));
  REQUIRE((sp[1].branch == "insulated" && !sp[1].ByIndex() && sp[1].kind == EventKind::BranchPoint && sp[1].omega == 2.418));
  REQUIRE((sp[2].branch == "mode3_bp4_plus" && sp[2].kind == EventKind::PeriodDoubling && sp[2].omega == 1.5));
  REQUIRE(sp[3].text == "3:pd@2");
  for (const char *bad : {"insulated", "insulated:x", "insulated:-1", ":3", "insulated:bp", "insulated:bp@", "insulated:fold@2", "insulated:bp@-1",
                          "insulated:bp@2x", "insulated:pd@nan"})
    REQUIRE(ErrorOf([&]() {
              return ParseSwitchSpecs(self, {bad}, &sp);
            }).rfind(std::string("-cont_switch ") + bad + ": expected <branch>:<event index> or", 0) == 0);
  REQUIRE(ErrorOf([&]() {
            return ParseSwitchSpecs(self, {"insulated:bp@2.4", "insulated:branch_point@2.4"}, &sp);
          }) == "-cont_switch insulated:branch_point@2.4: given twice");
  REQUIRE(ErrorOf([&]() { return ParseSwitchSpecs(self, {"3:5", "mode3:5"}, &sp); }) == "-cont_switch mode3:5: given twice");
  PCHK(ParseSwitchSpecs(self, {"insulated:bp@2.4", "insulated:bp@2.5", "insulated:5"}, &sp)); // different omegas: two items

  // the families' names come from the typed plan
  SwitchPlan plan{"insulated", 21, EventKind::BranchPoint, 1};
  REQUIRE(
      (plan.Label(1) == "insulated_bp21_plus" && plan.Label(-1) == "insulated_bp21_minus" && plan.ParentAttribute() == "insulated:21" && !plan.OneFamily()));
  plan = {"insulated_bp21_minus", 15, EventKind::PeriodDoubling, 2};
  REQUIRE((plan.Label(1) == "insulated_bp21_minus_pd15" && plan.Label(-1) == plan.Label(1) && plan.OneFamily()));

  // an event table: kind, omega
  std::vector<BifurcationEvent> ev(7);
  const std::pair<EventKind, PetscReal> table[] = {
      {EventKind::HamiltonianHopf, 1.80},    {EventKind::BranchPoint, 2.418248}, {EventKind::Resonance, 2.0275}, {EventKind::PeriodDoubling, 2.704867},
      {EventKind::PeriodDoubling, 2.705080}, {EventKind::BranchPoint, 3.1},      {EventKind::Fold, 2.418}};
  for (size_t i = 0; i < ev.size(); i++) ev[i].kind = table[i].first, ev[i].omega = table[i].second;
  const auto select = [&](const std::string &item, PetscInt *k) {
    return ErrorOf([&]() -> PetscErrorCode {
      PetscFunctionBeginUser;
      PetscCall(ParseSwitchSpecs(self, {item}, &sp));
      PetscCall(SelectSwitchEvent(self, sp[0], ev, "insulated", k));
      PetscFunctionReturn(0);
    });
  };
  PetscInt k = -1;
  REQUIRE(select("insulated:bp@2.418", &k) == ""); // the fold nearer 2.418 is another kind
  REQUIRE(k == 1);
  REQUIRE(select("insulated:branch_point@3", &k) == "");
  REQUIRE(k == 5);
  REQUIRE(select("insulated:bp@3.5", &k) == "");
  REQUIRE(k == 5);
  REQUIRE(select("insulated:bp@9", &k).find("ambiguous: the branch points of branch insulated at omega 3.1 (event 5) and 2.418248 (event 1)") !=
          std::string::npos);
  REQUIRE(select("insulated:pd@2.70487", &k) == "");
  REQUIRE(k == 3);
  REQUIRE(select("insulated:pd@2.70508", &k) == "");
  REQUIRE(k == 4);
  REQUIRE(select("insulated:4", &k) == "");
  REQUIRE(k == 4);
  REQUIRE(
      select("insulated:pd@2.705", &k) ==
      "-cont_switch insulated:pd@2.705: ambiguous: the period doublings of branch insulated at omega 2.70508 (event 4) and 2.704867 (event 3) are about as near "
      "(the nearest must be less than half as far as the next); give omega nearer one of them, or the index");
  REQUIRE(select("insulated:7", &k) == "-cont_switch insulated:7: branch insulated has 7 located events (0 .. 6)");
  ev.erase(ev.begin() + 3, ev.begin() + 5);
  REQUIRE(select("insulated:pd@2.7", &k) == "-cont_switch insulated:pd@2.7: branch insulated has no period doublings among its 5 located events");
  ev.clear();
  REQUIRE(select("insulated:0", &k) == "-cont_switch insulated:0: branch insulated has 0 located events");
}

TEST_CASE("-cont_switch items on switched families: each on a branch of -cont_branch or on a family another item starts", "[bifurcations][switch][switch_spec]")
{
  const MPI_Comm self = PETSC_COMM_SELF;
  const auto among = [](const std::string &b) { return SwitchNames(b, "insulated") || SwitchNames(b, "3"); }; // -cont_branch insulated,3
  const auto check = [&](std::vector<std::string> items) {
    return ErrorOf([&]() -> PetscErrorCode {
      std::vector<SwitchSpec> sp;
      PetscFunctionBeginUser;
      PetscCall(ParseSwitchSpecs(self, items, &sp));
      PetscCall(CheckSwitchParents(self, sp, among));
      PetscFunctionReturn(0);
    });
  };
  REQUIRE(check({"insulated:34", "insulated_bp34_plus:7", "insulated_bp34_plus_pd7:2", "insulated_pd34:1"}) == "");
  REQUIRE(check({"mode3:bp@2", "mode3_bp5_minus:pd@2.5", "3:4", "mode3_pd4:0"}) == ""); // by kind: any index of that kind
  REQUIRE(check({"insulated:bp@2.4", "insulated_pd3:0"}) ==
          "-cont_switch insulated_pd3:0: no branch insulated_pd3 among -cont_branch or the families of the other -cont_switch events");
  REQUIRE(check({"insulated:3", "insulated_pd3_minus:1"}) ==
          "-cont_switch insulated_pd3_minus:1: no branch insulated_pd3_minus among -cont_branch or the families of the other -cont_switch events");
  REQUIRE(check({"insulated:3", "insulated_bp4_plus:1"}) != "");
  REQUIRE(check({"insulated:bp@2", "insulated_bpx_plus:1"}) != "");
  REQUIRE(check({"optical_top:0"}) == "-cont_switch optical_top:0: no branch optical_top among -cont_branch or the families of the other -cont_switch events");
}
