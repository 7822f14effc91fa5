// The Krein resonance map (stability/krein_map.hpp, issue 35 item 4) against
// known truth: the paper lattice's analytic band edges (model.md: omega^2 =
// k_hat -+ |k_intra + k_inter e^{iq}|, so acoustic [1, sqrt(2.2)], optical
// [sqrt(3.8), sqrt(5)]), its localised modes (Sturm bisection against the
// dense eigenvalues of K), the pair classes open at a few Omega worked out by
// hand, and the energy criterion's flag on a constructed branch and on a
// continued branch with two known energy folds.
#include "bands/linear_modes.hpp"
#include "helpers.hpp"
#include "nnm_fixture.hpp"
#include "stability/krein_map.hpp"
#include <cmath>

using namespace nltopo;
using namespace nltopo::test;

TEST_CASE("Krein map: band edges, localised modes and the open pair classes of the paper lattice", "[krein_map]")
{
  LatticeParams p; // the paper's defaults, N = 102
  Lattice lat;
  PCHK(lat.Setup(PETSC_COMM_WORLD, p));
  KreinSpectrum s;
  PCHK(KreinSpectrumSetup(lat, &s));
  const BandEdges &b = s.bands;
  REQUIRE(std::abs(b.acoustic_bottom - 1) < 1e-14);
  REQUIRE(std::abs(b.acoustic_top - std::sqrt(2.2)) < 1e-14);
  REQUIRE(std::abs(b.optical_bottom - std::sqrt(3.8)) < 1e-14);
  REQUIRE(std::abs(b.optical_top - std::sqrt(5.0)) < 1e-14);

  // the localised modes: the interface's below and above the bands, the insulated and left-end pair at sqrt(3) (model.md)
  LinearModes modes;
  PCHK(modes.Compute(lat, LinearModesOptions()));
  std::vector<PetscReal> dense;
  for (PetscReal w : modes.Omega())
    if (w < b.acoustic_bottom || (w > b.acoustic_top && w < b.optical_bottom) || w > b.optical_top) dense.push_back(w);
  REQUIRE(s.localized.size() == 4);
  REQUIRE(dense.size() == 4);
  for (size_t i = 0; i < 4; i++) {
    INFO("localised mode " << i << ": Sturm " << s.localized[i] << ", dense " << dense[i]);
    REQUIRE(std::abs(s.localized[i] - dense[i]) < 1e-10);
  }
  REQUIRE(std::abs(s.localized[0] - 0.9197) < 1e-4);
  REQUIRE(std::abs(s.localized[1] - std::sqrt(3.0)) < 1e-9);
  REQUIRE(std::abs(s.localized[2] - std::sqrt(3.0)) < 1e-9);
  REQUIRE(std::abs(s.localized[3] - 2.2703) < 1e-4);

  // the insulated branch's E modes: one sqrt(3) is its own (the trivial pair)
  const std::vector<PetscReal> e = BranchEdgeModes(s, std::sqrt(3.0));
  REQUIRE(e.size() == 3);
  REQUIRE(BranchEdgeModes(s, 1.3).size() == 4); // a band mode's branch keeps all four

  // by hand, with e = {0.9197, 1.7321, 2.2703}: k Omega against AA [2, 2.966], AO [2.949, 3.719],
  // OO [3.899, 4.472], EA e + [1, 1.483], EO e + [1.949, 2.236], EE e + e'
  struct Case {
    PetscReal omega;
    PetscInt k, mask;
  };
  const Case cases[] = {
      {1.7, 1, 0},
      {1.7, 2, kPairAO | kPairEA},
      {1.7, 3, 0}, // 3.4: AO, EA(2.2703)
      {1.5, 1, 0},
      {1.5, 2, kPairAO | kPairEA | kPairEO},
      {1.5, 3, kPairEO}, // 3.0: EA(1.7321), EO(0.9197); 4.5: EO(2.2703)
      {1.1, 2, kPairAA | kPairEA},
      {1.1, 3, kPairAO | kPairEA},
      {1.1, 4, kPairOO | kPairEO}, // 2.2, 3.3, 4.4
  };
  for (const Case &c : cases) {
    INFO("Omega " << c.omega << ", k " << c.k);
    REQUIRE(OpenResonances(b, e, c.k * c.omega, c.k * c.omega) == c.mask);
  }
  // AO at k = 2 opens exactly on [(1 + sqrt(3.8))/2, (sqrt(2.2) + sqrt(5))/2]
  const PetscReal lo = (1 + std::sqrt(3.8)) / 2, hi = (std::sqrt(2.2) + std::sqrt(5.0)) / 2;
  for (PetscReal f : {1 - 1e-9, 1 + 1e-9}) {
    REQUIRE(bool(OpenResonances(b, e, 2 * lo * f, 2 * lo * f) & kPairAO) == (f > 1));
    REQUIRE(bool(OpenResonances(b, e, 2 * hi * f, 2 * hi * f) & kPairAO) == (f < 1));
  }
  // EE is a point: 2 sqrt(3) = 2 Omega crossed between two orbits, not at either alone
  REQUIRE(OpenResonances(b, e, 3.47, 3.46) & kPairEE);
  REQUIRE(!(OpenResonances(b, e, 3.47, 3.47) & kPairEE));
  REQUIRE(LargestSum(b, e) == 2 * e.back());

  // a branch: the map's table matches the pointwise masks, kmax from the lowest Omega
  const std::vector<PetscReal> E = {0.1, 0.2, 0.3}, period = {2 * PETSC_PI / 1.1, 2 * PETSC_PI / 1.5, 2 * PETSC_PI / 1.7};
  const KreinMap m = ComputeKreinMap(s, std::sqrt(3.0), E, period);
  REQUIRE(m.kmax == (PetscInt)std::floor(2 * e.back() / 1.1));
  REQUIRE(m.open[0 * m.kmax + 1] == (kPairAA | kPairEA));
  REQUIRE(m.open[2 * m.kmax + 1] == (kPairAO | kPairEA | kPairEE)); // e1 + e3 = 3.19 crossed from 2 x 1.5 to 2 x 1.7
}

TEST_CASE("Krein map: the energy criterion's flag on a constructed branch", "[krein_map]")
{
  // E(s) = 1 - (s - 1/2)^2 against Omega(s) = 1.7 + 0.1 s: one maximum of E at s = 1/2 (point 5 of 11), dE/dOmega = -20 (s - 1/2)
  std::vector<PetscReal> E, W, W2;
  for (int i = 0; i <= 10; i++) {
    const PetscReal s = 0.1 * i;
    E.push_back(1 - (s - 0.5) * (s - 0.5)), W.push_back(1.7 + 0.1 * s), W2.push_back(1.7 + 0.1 * (s - 0.3) * (s - 0.3));
  }
  const std::vector<PetscInt> f = EnergyCriterionFlags(E, W);
  const std::vector<PetscReal> d = EnergySlope(E, W);
  for (int i = 0; i <= 10; i++) {
    INFO("point " << i);
    REQUIRE(f[i] == (i == 5 ? 1 : 0));
    if (i > 0 && i < 10) REQUIRE(std::abs(d[i] + 20 * (0.1 * i - 0.5)) < 1e-9); // the central difference is exact for these quadratics
  }
  // Omega turning at s = 0.3 (point 3): dE/dOmega through infinity, flag 2
  const std::vector<PetscInt> g = EnergyCriterionFlags(E, W2);
  for (int i = 0; i <= 10; i++) REQUIRE(g[i] == (i == 5 ? 1 : 0) + (i == 3 ? 2 : 0));
}

// [serial]: the flag is arithmetic on the branch's arrays (the same on every rank; the gathered K is the first case's, at 2 ranks too), and
// a 6-site branch at 2 ranks is only slower
TEST_CASE("Krein map: the energy criterion flags the two energy folds of a folded branch", "[krein_map][serial]")
{
  // Mode 0 of the N = 6 interface lattice: E rises to ~66, falls to ~8, rises again (test_bifurcations.cpp)
  LatticeParams p;
  p.cells = 1;
  NnmFixture nf;
  PCHK(nf.Setup(p));
  ContinuationOptions co;
  co.verbose = PETSC_FALSE;
  co.energy_max = 300;
  Branch b;
  PCHK(nf.Continue(0, co, &b));
  std::vector<PetscReal> W;
  for (PetscReal T : b.period) W.push_back(2 * PETSC_PI / T);
  const std::vector<PetscInt> f = EnergyCriterionFlags(b.energy, W);
  std::vector<size_t> at;
  for (size_t i = 0; i < f.size(); i++)
    if (f[i] & 1) at.push_back(i);
  REQUIRE(at.size() == 2);
  INFO("E extrema at E = " << b.energy[at[0]] << ", " << b.energy[at[1]]);
  REQUIRE(b.energy[at[0]] > 50); // the maximum (~66) first
  REQUIRE(b.energy[at[1]] < 15); // then the minimum (~8)
  const std::vector<PetscReal> d = EnergySlope(b.energy, W);
  REQUIRE(d[at[0] - 1] * d[at[0] + 1] < 0); // dE/dOmega changes sign across each
  REQUIRE(d[at[1] - 1] * d[at[1] + 1] < 0);
}
