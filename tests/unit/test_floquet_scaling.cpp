// Issue 35, scaling with N: the leading eigenvector's participation ratio and
// edge share (both dense Floquet routes) against known truth, and the envelope
// fit of -study floquet_scaling (stability/envelope_fit.hpp).
#include "bands/linear_modes.hpp"
#include "helpers.hpp"
#include "orbits/continuation.hpp"
#include "stability/envelope_fit.hpp"
#include "stability/floquet.hpp"
#include "stability/floquet_mf.hpp"
#include <cmath>
#include <complex>

using namespace nltopo;
using namespace nltopo::test;

TEST_CASE("dense leading pairs: the leading eigenvector's participation ratio and edge share of a constructed operator", "[floquet][mf]")
{
  // M = H D H with H the reflection taking e0 to x (H e0 = x, H^2 = I): the
  // eigenvector of D's 1.5 is x. Sites 0, 1, 2 (u rows 0-2, v rows 3-5); x's
  // displacement is 0.5 on every site: PR = 3 sites; with the interface cell at
  // site 1 and no extra edge sites, sites 1 and 2 are the edge region: 2/3.
  const int n = 6;
  const std::vector<PetscReal> x = {0.5, 0.5, 0.5, 0.5, 0, 0}, d = {1.5, 1 / 1.5, 1, 1, 0.9, 1 / 0.9};
  std::vector<PetscReal> w = x;
  w[0] -= 1;
  PetscReal ww = 0;
  for (PetscReal a : w) ww += a * a;
  std::vector<PetscReal> H(n * n), M(n * n, 0.0); // column-major
  for (int i = 0; i < n; i++)
    for (int j = 0; j < n; j++) H[j * n + i] = (i == j) - 2 * w[i] * w[j] / ww;
  for (int i = 0; i < n; i++)
    for (int j = 0; j < n; j++)
      for (int k = 0; k < n; k++) M[j * n + i] += H[k * n + i] * d[k] * H[j * n + k];
  const std::vector<PetscInt> u = {0, 1, 2}, v = {3, 4, 5};
  FloquetOptions o;
  o.edge_sites = 0;
  LeadingPairs lead;
  PCHK(DenseLeadingPairs(n, M.data(), 1, o, u, v, 1, &lead));
  REQUIRE(lead.mu.size() == 1);
  REQUIRE(std::abs(lead.mu[0] - 1.5) < 1e-12);
  REQUIRE(std::abs(lead.leading_participation - 3) < 1e-10);
  REQUIRE(std::abs(lead.leading_edge - 2.0 / 3) < 1e-10);
  REQUIRE(lead.instability == 2); // an edge share between 0.25 and 0.75: B-E
  // all on one site: PR 1
  std::vector<PetscReal> one(n * n, 0.0);
  for (int i = 0; i < n; i++) one[i * n + i] = d[i];
  PCHK(DenseLeadingPairs(n, one.data(), 1, o, u, v, 1, &lead));
  REQUIRE(std::abs(lead.leading_participation - 1) < 1e-12);
  REQUIRE(lead.leading_edge == 0); // site 0 lies outside sites 1..2
}

namespace {
// Both dense routes at every orbit of a branch: the full analysis and the leading pairs.
struct BothRoutes : public PointHook {
  PeriodicFlow &flow;
  FloquetOptions o;
  FloquetResult full;
  LeadingMultipliers lead;
  OwnedMat S;
  OwnedVec zT;
  BothRoutes(PeriodicFlow &f, const FloquetOptions &oo) : flow(f), o(oo) {}
  PetscErrorCode Point(Vec z0, PetscReal T, PetscReal beta, Vec) override
  {
    PetscFunctionBeginUser;
    if (!S) {
      PetscCall(flow.CreateSensitivityMatrix(S.out()));
      PetscCall(VecDuplicate(z0, zT.out()));
    }
    PetscCall(flow.IntegrateWithMonodromy(z0, T, beta, zT, S));
    PetscCall(FloquetAnalysis(flow.Lat(), S, o, &full));
    PetscCall(FloquetLeadingDense(flow.Lat(), S, 1, o, &lead));
    PetscFunctionReturn(0);
  }
};
} // namespace

// In the linear limit the multipliers are exp(+-i 2 pi omega_k / omega_j) with
// the linear modes as eigenvectors: the leading one (nearest +-1, the trivial
// pair of mode j left out) is mode k's, whose participation ratio is
// 1 / sum phi_k^4 and edge share the sum of phi_k^2 over the edge region.
TEST_CASE("the leading eigenvector's participation ratio and edge share in the linear limit equal its linear mode's, on both dense routes", "[floquet]")
{
  LatticeParams p;
  p.cells = 6; // N = 26, interface site 12
  Lattice lat;
  PCHK(lat.Setup(PETSC_COMM_WORLD, p));
  LinearModes modes;
  PCHK(modes.Compute(lat, LinearModesOptions()));
  PeriodicFlow flow;
  FlowOptions fo;
  fo.steps = 256;
  auto fx = Effects(lat);
  PCHK(flow.Setup(*fx, fo));
  Shooting shoot;
  PCHK(shoot.Setup(flow, ShootingOptions()));
  ContinuationOptions co;
  co.verbose = PETSC_FALSE;
  co.max_points = 1; // the orbit at E = 1e-5
  FloquetOptions o;
  o.edge_sites = 3;
  const auto &w = modes.Omega();
  const PetscInt N = lat.N(), iface = p.InterfaceSite();
  PetscInt checked = 0;
  for (PetscInt j = 0; j < N; j += 3) { // every third mode: several known truths, cheap at 2 ranks
    // the expected leading mode: largest |cos(2 pi w_k / w_j)|, k != j, unique by a margin
    PetscInt best = -1;
    PetscReal c1 = -1, c2 = -1;
    for (PetscInt k = 0; k < N; k++) {
      if (k == j) continue;
      const PetscReal c = std::abs(std::cos(2 * PETSC_PI * w[k] / w[j]));
      if (c > c1) c2 = c1, c1 = c, best = k;
      else if (c > c2) c2 = c;
    }
    INFO("branch " << j << ": leading mode " << best << ", |cos| " << c1 << " against " << c2);
    if (c1 - c2 < 1e-3 || c1 > 1 - 1e-3) continue; // ambiguous, or too near the trivial pair: not a known truth
    const std::vector<PetscReal> phi = Gather(modes.Mode(best)); // a 1-D DMDA: natural order
    PetscReal s2 = 0, s4 = 0, edge = 0;
    for (PetscInt s = 0; s < N; s++) {
      s2 += phi[s] * phi[s], s4 += std::pow(phi[s], 4);
      if (InEdgeRegion(s, iface, o.edge_sites)) edge += phi[s] * phi[s];
    }
    const PetscReal pr = s2 * s2 / s4;
    edge /= s2;
    BothRoutes both(flow, o);
    Branch b;
    PCHK(ContinueBranch(shoot, modes.Mode(j), 2 * PETSC_PI / w[j], co, "pr", &b, &both));
    INFO("expected PR " << pr << ", edge share " << edge << "; full route " << both.full.leading_participation << ", " << both.full.leading_edge
                        << "; leading pairs " << both.lead.leading_participation << ", " << both.lead.leading_edge);
    // against the linear mode: to the orbit's nonlinearity at E = 1e-5 and the integration error
    REQUIRE(std::abs(both.full.leading_participation - pr) < 2e-5 * pr);
    REQUIRE(std::abs(both.full.leading_edge - edge) < 2e-5);
    // the two routes, one monodromy: to rounding
    REQUIRE(std::abs(both.lead.leading_participation - both.full.leading_participation) < 1e-9 * pr);
    REQUIRE(std::abs(both.lead.leading_edge - both.full.leading_edge) < 1e-9);
    checked++;
  }
  REQUIRE(checked >= 3);
}

TEST_CASE("envelope fit: a power law's exponent and prefactor, the verdict rule, windows", "[floquet][scaling]")
{
  const std::vector<PetscReal> N = {102, 202, 402, 1002};
  auto law = [&](PetscReal C, PetscReal p) {
    std::vector<PetscReal> e;
    for (PetscReal n : N) e.push_back(C * std::pow(n, -p));
    return e;
  };
  SECTION("exact power laws: p and C to rounding, R^2 1, the verdict by -scaling_persist_exponent")
  {
    for (PetscReal p : {0.0, 0.2, 0.6, 1.0, 1.7}) {
      const EnvelopeFit f = FitEnvelope(N, law(0.3, p), 1e-6, 0.5);
      INFO("p " << p << ": fitted " << f.p << ", C " << f.C << ", R^2 " << f.r2);
      REQUIRE(std::abs(f.p - p) < 1e-12);
      REQUIRE(std::abs(f.C - 0.3) < 1e-12);
      REQUIRE(f.residual < 1e-12);
      REQUIRE(f.npoints == 4);
      if (p != 0) REQUIRE(std::abs(f.r2 - 1) < 1e-12);
      REQUIRE(f.verdict == (p < 0.5 ? kScalingPersists : kScalingFiniteSize));
    }
  }
  SECTION("a noisy law: p within its standard error; the threshold inside it: undetermined")
  {
    std::vector<PetscReal> e = law(0.01, 0.45);
    e[1] *= 1.3, e[2] /= 1.3;
    const EnvelopeFit f = FitEnvelope(N, e, 1e-6, 0.5);
    INFO("fitted " << f.p << " +- " << f.p_stderr << ", R^2 " << f.r2 << ", residual " << f.residual);
    REQUIRE(f.p_stderr > 0.05);
    REQUIRE(std::abs(f.p - 0.45) < 2 * f.p_stderr);
    REQUIRE(f.r2 < 1);
    REQUIRE(f.residual > 0.05);
    REQUIRE(f.verdict == kScalingUndetermined);
  }
  SECTION("stable sizes are left out; a window stable everywhere is stable; one without orbits, or one point, undetermined")
  {
    std::vector<PetscReal> e = law(0.01, 1.0);
    e[3] = 1e-12; // stable at the largest N
    const EnvelopeFit f = FitEnvelope(N, e, 1e-6, 0.5);
    REQUIRE(f.npoints == 3);
    REQUIRE(std::abs(f.p - 1) < 1e-12);
    REQUIRE(FitEnvelope(N, {1e-14, 1e-13, 1e-12, 1e-14}, 1e-6, 0.5).verdict == kScalingStable);
    REQUIRE(FitEnvelope(N, {NAN, NAN, NAN, NAN}, 1e-6, 0.5).verdict == kScalingUndetermined);
    const EnvelopeFit one = FitEnvelope(N, {1e-3, 1e-12, NAN, 1e-12}, 1e-6, 0.5);
    REQUIRE(one.npoints == 1);
    REQUIRE(one.verdict == kScalingUndetermined);
    REQUIRE(std::isnan(one.p));
  }
  SECTION("a window's maximum: [lo, hi), NaN moduli skipped, none: -1 and NaN")
  {
    const std::vector<PetscReal> E = {0.5, 1.0, 1.5, 2.0}, m = {1.01, 1.002, NAN, 1.5};
    PetscReal env;
    REQUIRE(WindowMaximum(E, m, 0, 2, &env) == 0);
    REQUIRE(std::abs(env - 0.01) < 1e-14);
    REQUIRE(WindowMaximum(E, m, 1, 2, &env) == 1);
    REQUIRE(WindowMaximum(E, m, 1.2, 1.9, &env) == -1);
    REQUIRE(std::isnan(env));
  }
}
