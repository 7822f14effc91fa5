// Floquet multipliers and Krein signatures against known truth: the linear
// limit (exp(+-i 2 pi omega_k / omega_j), signature +1 on exp(+i ...)), the
// symplectic structure (reciprocal and conjugate pairs, det M = 1) and the two
// trivial multipliers of an isolated NNM.
#include "bands/linear_modes.hpp"
#include "dimers.hpp"
#include "helpers.hpp"
#include "orbits/continuation.hpp"
#include "stability/floquet.hpp"
#include "stability/floquet_mf.hpp"
#include <algorithm>
#include <cmath>
#include <complex>

using namespace nltopo;
using namespace nltopo::test;
using cplx = std::complex<PetscReal>;

namespace {
// Every accepted orbit of a branch: its frequency and Floquet result, and the
// last orbit itself (z, T, beta) with the state part dz of the family tangent.
struct CaptureAll : public PointHook {
  PeriodicFlow &flow;
  std::vector<PetscReal> omega;
  std::vector<FloquetResult> res;
  OwnedMat S;
  OwnedVec zT, z, dz;
  PetscReal T = 0, beta = 0;
  explicit CaptureAll(PeriodicFlow &f) : flow(f) {}
  PetscErrorCode Point(Vec z0, PetscReal TT, PetscReal b, Vec dz0) override
  {
    PetscFunctionBeginUser;
    if (!z) PetscCall(VecDuplicate(z0, z.out()));
    if (!dz) PetscCall(VecDuplicate(z0, dz.out()));
    PetscCall(VecCopy(z0, z));
    PetscCall(VecCopy(dz0, dz));
    T = TT, beta = b;
    if (!S) {
      PetscCall(flow.CreateSensitivityMatrix(S.out()));
      PetscCall(VecDuplicate(z0, zT.out()));
    }
    PetscCall(flow.IntegrateWithMonodromy(z0, TT, b, zT, S));
    FloquetResult r;
    PetscCall(FloquetAnalysis(flow.Lat(), S, FloquetOptions(), &r));
    omega.push_back(2 * PETSC_PI / TT);
    res.push_back(r);
    PetscFunctionReturn(0);
  }
};
} // namespace

TEST_CASE("Floquet multipliers in the linear limit, symplectic pairs, det M = 1, Krein signs", "[floquet]")
{
  LatticeParams p;
  p.cells = 2; // N = 10
  Lattice lat;
  PCHK(lat.Setup(PETSC_COMM_WORLD, p));
  LinearModes modes;
  PCHK(modes.Compute(lat, LinearModesOptions()));
  PeriodicFlow flow;
  FlowOptions fo;
  fo.steps = 512; // det M = 1 to 1e-8 needs the RK error below it (2e-8 at 256 steps)
  auto fx_flow = Effects(lat);
  PCHK(flow.Setup(*fx_flow, fo));
  Shooting shoot;
  PCHK(shoot.Setup(flow, ShootingOptions()));
  ContinuationOptions co;
  co.verbose = PETSC_FALSE;
  co.max_points = 1; // the orbit at E = 1e-5
  const PetscInt N = lat.N();
  const auto &w = modes.Omega();
  for (PetscInt j : {0, 3, 7}) {
    CaptureAll cap(flow);
    Branch b;
    PCHK(ContinueBranch(shoot, modes.Mode(j), 2 * PETSC_PI / w[j], co, "floquet", &b, &cap));
    const FloquetResult &r = cap.res.back();
    REQUIRE((PetscInt)r.re.size() == 2 * N);
    std::vector<cplx> mu;
    for (PetscInt i = 0; i < 2 * N; i++) mu.emplace_back(r.re[i], r.im[i]);
    auto nearest = [&](cplx z) {
      size_t best = 0;
      for (size_t i = 1; i < mu.size(); i++)
        if (std::abs(mu[i] - z) < std::abs(mu[best] - z)) best = i;
      return best;
    };
    cplx prod = 1;
    for (auto &m : mu) {
      prod *= m;
      REQUIRE(std::abs(mu[nearest(1.0 / m)] - 1.0 / m) < 1e-6);           // reciprocal partner
      REQUIRE(std::abs(mu[nearest(std::conj(m))] - std::conj(m)) < 1e-6); // conjugate partner
      REQUIRE(std::abs(std::abs(m) - 1) < 1e-6);                          // the linear limit is stable
    }
    REQUIRE(std::abs(prod - 1.0) < 1e-8); // det M = exp(int trace A) = 1
    REQUIRE(r.stable);
    REQUIRE(r.trivial == 2); // time shift and the family direction
    // exp(+-i 2 pi omega_k / omega_j) for every linear mode k, and signature +1 on the + member
    for (PetscInt k = 0; k < N; k++) {
      const PetscReal th = 2 * PETSC_PI * w[k] / w[j];
      const cplx ep = std::polar<PetscReal>(1, th), em = std::conj(ep);
      const size_t ip = nearest(ep), im = nearest(em);
      INFO("branch " << j << ", mode " << k << ", theta " << th);
      REQUIRE(std::abs(mu[ip] - ep) < 1e-5);
      REQUIRE(std::abs(mu[im] - em) < 1e-5);
      if (k != j && std::abs(std::sin(th)) > 1e-3) {
        REQUIRE(r.krein[ip] == 1);
        REQUIRE(r.krein[im] == -1);
      }
    }
  }
}

// A known unstable orbit from theory. Layout `right` with Nc = 2 and gamma =
// 0.9 is two stiff dimers (k1 = 1.9, cubic) joined by a weak soft bond (k2 =
// 0.1): two weakly coupled identical hardening oscillators, mirror-symmetric.
// Their optical NNMs are the mirror-odd and mirror-even combinations, linear
// eigenvalues lambda_hi - lambda_lo = 2 kappa apart (kappa = k2/2 = 0.05). First-order
// averaging of the pair x'' + w^2 x + a x^3 + kappa (x - y) = 0 (the Mathieu
// equation of the symmetry-breaking perturbation, first tongue) says: the
// lower NNM is stable at all amplitudes; the upper one is stable until its
// frequency shift Omega^2 - lambda_hi reaches kappa, then a real pair of multipliers
// leaves +1 (pitchfork to localised NNMs) with
// mu = exp(pi sqrt(s^2 - (s - 2 kappa)^2) / Omega^2), s = Omega^2 - lambda_hi.
TEST_CASE("Floquet flags the symmetry-breaking instability of two coupled dimers, as averaging predicts", "[floquet][once]")
{
  // [once]: at 2 ranks the same continuation with Floquet multipliers of the dimers runs in
  // test_bifurcations.cpp ("branch switching at the dimer pitchfork ...").
  CoupledDimers d;
  PCHK(d.Setup());
  PeriodicFlow &flow = d.flow;
  const auto &w = d.modes.Omega();
  const PetscReal lam_lo = w[2] * w[2], lam_hi = w[3] * w[3], kappa = (lam_hi - lam_lo) / 2;
  REQUIRE(std::abs(kappa - 0.05) < 1e-12);
  for (PetscInt j : {2, 3}) {
    CaptureAll cap(flow);
    PCHK(d.Continue(j, std::sqrt(lam_hi + 5 * kappa), &cap));
    REQUIRE(cap.omega.size() > 10);
    REQUIRE(cap.omega.back() > std::sqrt(lam_hi + 4 * kappa));
    PetscReal onset = -1;
    for (size_t i = 0; i < cap.omega.size(); i++) {
      const PetscReal s = cap.omega[i] * cap.omega[i] - lam_hi;
      const FloquetResult &r = cap.res[i];
      INFO("mode " << j << ", omega " << cap.omega[i] << ", s/kappa " << s / kappa << ", max |mu| " << r.max_modulus);
      if (j == 2 || s < 0.8 * kappa) {
        REQUIRE(r.stable);
        continue;
      }
      if (onset < 0 && !r.stable) onset = s / kappa;
      if (s > 1.5 * kappa) {
        REQUIRE(!r.stable);
        // The leading multiplier is real and positive (a pitchfork, not a period doubling) ...
        size_t lead = 0;
        for (size_t k = 1; k < r.re.size(); k++)
          if (std::hypot(r.re[k], r.im[k]) > std::hypot(r.re[lead], r.im[lead])) lead = k;
        REQUIRE(std::abs(r.im[lead]) < 1e-8);
        REQUIRE(r.re[lead] > 1);
        // ... and its size follows the Mathieu growth rate to first order in kappa / Omega^2.
        const PetscReal W2 = cap.omega[i] * cap.omega[i];
        const PetscReal mu = std::exp(PETSC_PI * std::sqrt(s * s - (s - 2 * kappa) * (s - 2 * kappa)) / W2);
        REQUIRE(std::abs(std::log(r.re[lead]) / std::log(mu) - 1) < 0.15);
      }
    }
    if (j == 3) {
      INFO("onset at s/kappa = " << onset);
      REQUIRE(onset > 0.8);
      REQUIRE(onset < 1.5);
    }
  }
}

// Matrix-free monodromy (long-lattice route): its action equals the dense
// monodromy times a vector, and Krylov-Schur on it finds the dense leading
// multiplier of a known unstable orbit (the coupled dimers past their pitchfork).
TEST_CASE("matrix-free monodromy action and leading multiplier equal the dense ones", "[floquet][mf]")
{
  CoupledDimers d;
  PCHK(d.Setup());
  Lattice &lat = d.lat;
  PeriodicFlow &flow = d.flow;
  const auto &w = d.modes.Omega();
  CaptureAll last(flow);                                         // also the dense monodromy S and multipliers of the last orbit
  PCHK(d.Continue(3, std::sqrt(w[3] * w[3] + 3 * 0.05), &last)); // s = 3 kappa: unstable, mu ~ 1.09
  const FloquetResult &dense = last.res.back();
  Mat S = last.S;
  OwnedVec x, y, yd;
  // Action on a pseudo-random vector against S x (the first 2N columns of S).
  PCHK(VecDuplicate(last.z, x.out()));
  PCHK(VecDuplicate(last.z, y.out()));
  PCHK(VecDuplicate(last.z, yd.out()));
  Scatter(Pseudo(2 * lat.N(), 3), x); // global state order
  {
    OwnedVec xe, ye;
    PCHK(MatCreateVecs(S, xe.out(), ye.out())); // S = [M | dz(T)/dbeta]: x extended by a zero beta entry
    std::vector<PetscReal> full = Gather(x);
    full.push_back(0.0);
    Scatter(full, xe);
    PCHK(MatMult(S, xe, yd));
    MonodromyShell shell;
    PCHK(shell.Create(flow, last.z, last.T, last.beta));
    PCHK(MatMult(shell.Get(), x, y));
    PetscReal nrm, err;
    PCHK(VecNorm(yd, NORM_INFINITY, &nrm));
    PCHK(VecAXPY(y, -1.0, yd));
    PCHK(VecNorm(y, NORM_INFINITY, &err));
    INFO("matrix-free M x vs dense S x: " << err / nrm);
    REQUIRE(err < 1e-8 * nrm);
  }
  // Leading multiplier: real, > 1, equal to the dense one.
  LeadingMultipliers lead;
  FloquetMfOptions mo;
  mo.nev = 1;
  mo.which = FloquetMfWhich::Largest;
  PCHK(FloquetLeading(flow, last.z, last.T, last.beta, mo, &lead));
  REQUIRE(dense.max_modulus > 1.05);
  INFO("matrix-free " << lead.re[0] << " + " << lead.im[0] << " i, dense max modulus " << dense.max_modulus << ", " << lead.products << " products");
  REQUIRE(std::abs(lead.im[0]) < 1e-8);
  REQUIRE(std::abs(lead.re[0] - dense.max_modulus) < 1e-8);

  // The "critical" route ((M + M^-1)/2, M^-1 by reversibility) finds the same multiplier.
  LeadingMultipliers crit;
  mo.which = FloquetMfWhich::Critical;
  PCHK(FloquetLeading(flow, last.z, last.T, last.beta, mo, &crit));
  INFO("critical route: " << crit.re[0] << " + " << crit.im[0] << " i, " << crit.products << " products");
  REQUIRE(std::abs(crit.max_modulus - dense.max_modulus) < 1e-7);
  // A converged multiplier off the circle proves the orbit unstable, on either route.
  REQUIRE(MatrixFreeVerdict(lead, 1e-6) == kUnstable);
  REQUIRE(MatrixFreeVerdict(crit, 1e-6) == kUnstable);
  // The dense leading pair (-floquet_mf_dense_max): the same real multiplier, from the same S.
  LeadingMultipliers dl;
  PCHK(FloquetLeadingDense(lat, S, 1, FloquetOptions(), &dl));
  INFO("dense leading " << dl.re[0] << " + " << dl.im[0] << " i");
  REQUIRE(dl.verdict == kUnstable);
  REQUIRE(dl.im[0] == 0);
  REQUIRE(std::abs(dl.re[0] - dense.max_modulus) < 1e-12 * dense.max_modulus);
  REQUIRE(std::abs(dl.max_modulus - dense.max_modulus) < 1e-12 * dense.max_modulus);
  // its kind: a real pair (Krein form 0) and the dense route's class of the same eigenvector
  REQUIRE(dl.krein[0] == 0);
  REQUIRE(dense.instability > 0);
  REQUIRE(dl.instability == dense.instability);
}

// On a stable orbit every multiplier lies on the unit circle, where "largest
// modulus" cannot choose; the critical route must return multipliers of the
// dense spectrum, on the circle, nearest +-1.
TEST_CASE("matrix-free critical multipliers of a stable orbit equal dense ones", "[floquet][mf]")
{
  CoupledDimers d;
  PCHK(d.Setup());
  const auto &w = d.modes.Omega();
  CaptureAll cap(d.flow);
  PCHK(d.Continue(2, std::sqrt(w[2] * w[2] + 0.5 * 0.05), &cap)); // the lower optical NNM: stable at every amplitude
  const FloquetResult &dense = cap.res.back();
  REQUIRE(dense.stable);
  FloquetMfOptions mo;
  mo.nev = 4;
  LeadingMultipliers lead;
  PCHK(FloquetLeading(d.flow, cap.z, cap.T, cap.beta, mo, &lead));
  REQUIRE(std::abs(lead.max_modulus - 1) < 1e-8);
  // Compared through b = (mu + 1/mu)/2, which is well conditioned: mu itself is
  // not near the Jordan block at 1 (a b error of 1e-10 moves mu by 1e-5 there,
  // in the dense route as much as in this one).
  auto bval = [](cplx mu) { return 0.5 * (mu + 1.0 / mu); };
  for (size_t i = 0; i < lead.re.size(); i++) {
    PetscReal best = 1e300;
    for (size_t j = 0; j < dense.re.size(); j++) best = std::min(best, std::abs(bval(cplx(lead.re[i], lead.im[i])) - bval(cplx(dense.re[j], dense.im[j]))));
    INFO("mf multiplier " << lead.re[i] << " + " << lead.im[i] << " i: nearest dense (mu + 1/mu)/2 at " << best);
    REQUIRE(best < 1e-8);
  }
}

// The trivial pair mu = 1 of every NNM is a double eigenvalue b = 1 of
// (M + M^-1)/2; without deflation it takes one of the nev places (and, nearly
// defective in the discrete flow, converges slowly). Deflated through f(z0)
// and the family tangent, the route must return the leading NONTRIVIAL dense
// multiplier pairs: the distinct dense b values by decreasing |b| once the two
// nearest 1 are dropped (every b of B is double: mu and conj(mu) give the same b).
TEST_CASE("deflating the trivial pair, the critical route returns the leading nontrivial dense multipliers", "[floquet][mf]")
{
  CoupledDimers d;
  PCHK(d.Setup());
  const auto &w = d.modes.Omega();
  CaptureAll cap(d.flow);
  PCHK(d.Continue(2, std::sqrt(w[2] * w[2] + 0.5 * 0.05), &cap)); // stable lower optical NNM
  const FloquetResult &dense = cap.res.back();
  auto bval = [](cplx mu) { return 0.5 * (mu + 1.0 / mu); };
  std::vector<cplx> bd;
  for (size_t j = 0; j < dense.re.size(); j++) bd.push_back(bval(cplx(dense.re[j], dense.im[j])));
  for (int k = 0; k < 2; k++) { // drop the trivial pair (the two b nearest 1)
    auto it = std::min_element(bd.begin(), bd.end(), [](cplx a, cplx b) { return std::abs(a - 1.0) < std::abs(b - 1.0); });
    bd.erase(it);
  }
  std::sort(bd.begin(), bd.end(), [](cplx a, cplx b) { return std::abs(a) > std::abs(b); });
  std::vector<cplx> distinct; // one b per pair
  for (cplx b : bd)
    if (distinct.empty() || std::abs(b - distinct.back()) > 1e-6) distinct.push_back(b);
  REQUIRE(distinct.size() == 3);               // 4 sites: the trivial pair and three nontrivial pairs
  REQUIRE(std::abs(distinct[0] - 1.0) > 1e-3); // well away from the trivial pair here
  FloquetMfOptions mo;
  mo.nev = 2;
  for (PetscBool deflate : {PETSC_TRUE, PETSC_FALSE}) {
    mo.deflate = deflate;
    LeadingMultipliers lead;
    PCHK(FloquetLeading(d.flow, cap.z, cap.T, cap.beta, mo, &lead, nullptr, cap.dz));
    REQUIRE(lead.converged == 2);
    const cplx b0 = bval(cplx(lead.re[0], lead.im[0])), b1 = bval(cplx(lead.re[1], lead.im[1]));
    INFO("deflate " << deflate << ": mf b = " << b0 << ", " << b1 << "; dense nontrivial " << distinct[0] << ", " << distinct[1] << "; " << lead.products
                    << " products");
    if (deflate) {
      REQUIRE(std::abs(b0 - distinct[0]) < 1e-8);
      REQUIRE(std::abs(b1 - distinct[1]) < 1e-8);
      // all on the circle: matrix-free, that is no verdict (a quadruplet inside the spectrum cannot be excluded)
      REQUIRE(MatrixFreeVerdict(lead, 1e-6) == kUndecided);
    } else { // the control: undeflated, the trivial pair takes the first place
      REQUIRE(std::abs(b0 - 1.0) < 1e-6);
      REQUIRE(std::abs(b1 - distinct[0]) < 1e-8);
    }
  }
  // The dense leading pairs: the trivial pair left out, the same two pairs in
  // the same order (nearest +-1 on the circle), and the verdict "stable".
  LeadingMultipliers dl;
  PCHK(FloquetLeadingDense(d.lat, cap.S, 2, FloquetOptions(), &dl));
  REQUIRE(dl.converged == 2);
  REQUIRE(dl.verdict == kStable);
  REQUIRE(std::abs(dl.max_modulus - 1) < 1e-8); // the dense floor (rounding of 2N eigenvalues on the circle)
  for (int k = 0; k < 2; k++) {
    INFO("dense leading pair " << k << ": b = " << bval(cplx(dl.re[k], dl.im[k])) << ", expected " << distinct[k]);
    REQUIRE(dl.im[k] >= 0);
    REQUIRE(std::abs(bval(cplx(dl.re[k], dl.im[k])) - distinct[k]) < 1e-10);
    // the Krein signature of the same multiplier in the full dense analysis
    size_t j = 0;
    for (size_t i = 1; i < dense.re.size(); i++)
      if (std::abs(cplx(dense.re[i], dense.im[i]) - cplx(dl.re[k], dl.im[k])) < std::abs(cplx(dense.re[j], dense.im[j]) - cplx(dl.re[k], dl.im[k]))) j = i;
    REQUIRE(dense.krein[j] != 0);
    REQUIRE(dl.krein[k] == dense.krein[j]);
  }
  REQUIRE(dl.instability == 0);
}

// A constructed symplectic operator with known spectrum for the dense leading
// pairs' kernel: two oscillators of opposite energy, H = (p1^2 + w1^2 q1^2)/2
// - (p2^2 + w2^2 q2^2)/2 + eps q1 q2, and a free particle q3 (the trivial pair
// mu = 1, a Jordan block as on every NNM); M = exp(A T) by scaling and squaring.
// Apart (eps = 0, w1 != w2): exp(+-i w T) on the circle, the exp(+i w1 T) member
// of signature +1 and the exp(+i w2 T) member -1 (negative energy). Colliding
// (w1 = w2 = w, eps > 0): with z = q1 + i q2, z'' = (-w^2 + i eps) z, a Krein
// quadruplet with |mu| = exp(a T), a = Re sqrt(-w^2 + i eps).
namespace {
std::vector<PetscReal> KreinOperator(PetscReal w1, PetscReal w2, PetscReal eps, PetscReal T)
{
  const int n = 6; // (q1, q2, q3, p1, p2, p3), column-major
  std::vector<PetscReal> A(n * n, 0.0);
  auto at = [&](std::vector<PetscReal> &m, int i, int j) -> PetscReal & { return m[j * n + i]; };
  at(A, 0, 3) = 1, at(A, 3, 0) = -w1 * w1, at(A, 3, 1) = -eps; // q1' = p1, p1' = -w1^2 q1 - eps q2
  at(A, 1, 4) = -1, at(A, 4, 1) = w2 * w2, at(A, 4, 0) = -eps; // q2' = -p2, p2' = w2^2 q2 - eps q1
  at(A, 2, 5) = 1;                                             // q3' = p3
  int squarings = 10;
  const PetscReal h = T / std::pow(2.0, squarings);
  std::vector<PetscReal> M(n * n, 0.0), term(n * n, 0.0), next(n * n);
  for (int i = 0; i < n; i++) at(M, i, i) = at(term, i, i) = 1;
  for (int k = 1; k <= 20; k++) { // Taylor series of exp(A h)
    for (int i = 0; i < n; i++)
      for (int j = 0; j < n; j++) {
        PetscReal s = 0;
        for (int l = 0; l < n; l++) s += at(A, i, l) * at(term, l, j);
        at(next, i, j) = s * h / k;
      }
    term = next;
    for (int i = 0; i < n * n; i++) M[i] += term[i];
  }
  while (squarings--) {
    for (int i = 0; i < n; i++)
      for (int j = 0; j < n; j++) {
        PetscReal s = 0;
        for (int l = 0; l < n; l++) s += at(M, i, l) * at(M, l, j);
        at(next, i, j) = s;
      }
    M = next;
  }
  return M;
}
} // namespace

TEST_CASE("dense leading pairs of a constructed symplectic operator: Krein signatures apart, a quadruplet in collision", "[floquet][mf]")
{
  const std::vector<PetscInt> u = {0, 1, 2}, v = {3, 4, 5};
  const PetscReal T = 2;
  FloquetOptions o;
  SECTION("apart: on the circle, signatures +1 and -1, ordered nearest +-1")
  {
    std::vector<PetscReal> M = KreinOperator(1.0, 1.3, 0.0, T);
    LeadingPairs lead;
    PCHK(DenseLeadingPairs(6, M.data(), 2, o, u, v, -1, &lead));
    REQUIRE(lead.mu.size() == 2);
    // |cos 2.6| = 0.857 > |cos 2| = 0.416: the negative-energy oscillator's pair first
    INFO("leading " << lead.mu[0] << " (" << lead.krein[0] << "), " << lead.mu[1] << " (" << lead.krein[1] << ")");
    REQUIRE(std::abs(lead.mu[0] - std::polar(1.0, 1.3 * T)) < 1e-12);
    REQUIRE(lead.krein[0] == -1);
    REQUIRE(std::abs(lead.mu[1] - std::polar(1.0, 1.0 * T)) < 1e-12);
    REQUIRE(lead.krein[1] == 1);
    REQUIRE(std::abs(lead.max_modulus - 1) < 1e-12);
    REQUIRE(lead.instability == 0);
  }
  SECTION("colliding: the quadruplet's |mu| = exp(a T), complex, Krein form 0")
  {
    const PetscReal eps = 0.01, a = std::sqrt((std::hypot(1.0, eps) - 1.0) / 2);
    std::vector<PetscReal> M = KreinOperator(1.0, 1.0, eps, T);
    LeadingPairs lead;
    PCHK(DenseLeadingPairs(6, M.data(), 2, o, u, v, -1, &lead));
    REQUIRE(lead.mu.size() == 1); // one member of the quadruplet has |mu| > 1 and Im mu > 0; nothing else is nontrivial
    INFO("leading " << lead.mu[0] << ", expected modulus " << std::exp(a * T));
    REQUIRE(std::abs(std::abs(lead.mu[0]) - std::exp(a * T)) < 1e-12);
    REQUIRE(lead.mu[0].imag() > 0.5); // complex, near exp(i w T)
    REQUIRE(std::abs(lead.max_modulus - std::exp(a * T)) < 1e-12);
    REQUIRE(lead.krein[0] == 0);
    REQUIRE(lead.instability == 1); // no edge region given: bulk
  }
  SECTION("degenerate: two distinct pairs with one multiplier are both kept; more pairs asked than exist")
  {
    std::vector<PetscReal> M = KreinOperator(1.0, 1.0, 0.0, T);
    LeadingPairs lead;
    PCHK(DenseLeadingPairs(6, M.data(), 4, o, u, v, -1, &lead));
    REQUIRE(lead.mu.size() == 2); // 3 pairs, the trivial one left out
    for (const auto &m : lead.mu) REQUIRE(std::abs(m - std::polar(1.0, T)) < 1e-7);
  }
  SECTION("a quadruplet within -floquet_tol of the circle: one pair, the outer member, stable")
  {
    const PetscReal eps = 1e-7, a = std::sqrt((std::hypot(1.0, eps) - 1.0) / 2); // |mu| - 1 = 1e-7 < tol = 1e-6
    std::vector<PetscReal> M = KreinOperator(1.0, 1.0, eps, T);
    LeadingPairs lead;
    PCHK(DenseLeadingPairs(6, M.data(), 2, o, u, v, -1, &lead));
    INFO("leading " << (lead.mu.empty() ? cplx(NAN) : lead.mu[0]) << ", " << lead.mu.size() << " pairs");
    REQUIRE(lead.mu.size() == 1);
    REQUIRE(std::abs(std::abs(lead.mu[0]) - std::exp(a * T)) < 1e-8); // near a collision the eigenvalues carry ~sqrt(eps)
    REQUIRE(std::abs(lead.mu[0]) > 1);
    REQUIRE(lead.max_modulus <= 1 + o.tol);
  }
}
