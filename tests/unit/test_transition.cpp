// The linear topological transition (bands/transition.hpp, -linear_gamma_list)
// against known truth: the Zak phases' jump at gamma = 0, and the finite
// spectrum against closed forms at gamma = -1, 0, 1 (model.md: K(i,i) = k_hat,
// K(i,i+1) = -k_b) and against the SLEPc modes of the linear study.
#include "bands/linear_modes.hpp"
#include "bands/transition.hpp"
#include "helpers.hpp"
#include <algorithm>
#include <cmath>

using namespace nltopo;
using namespace nltopo::test;

namespace {

// omega^2 = value, count times.
struct Level {
  PetscReal value;
  PetscInt count;
};

// The ascending omega^2 a list of levels gives.
std::vector<PetscReal> Levels(std::initializer_list<Level> levels)
{
  std::vector<PetscReal> v;
  for (const Level &l : levels) v.insert(v.end(), l.count, l.value);
  std::sort(v.begin(), v.end());
  return v;
}

void RequireSpectrum(const LatticeParams &p, const std::vector<PetscReal> &lambda)
{
  std::vector<PetscReal> w;
  PCHK(FiniteSpectrum(p, &w));
  REQUIRE(w.size() == lambda.size());
  for (size_t j = 0; j < w.size(); j++) {
    INFO("layout " << LayoutName(p.layout) << ", Nc " << p.cells << ", gamma " << p.gamma << ", mode " << j);
    REQUIRE(std::abs(w[j] * w[j] - lambda[j]) < 1e-13 * p.KHat());
  }
}

// The finite spectrum of p equals the linear study's SLEPc modes (1e-12); returns it.
std::vector<PetscReal> RequireSameAsModes(const LatticeParams &p)
{
  std::vector<PetscReal> w;
  PCHK(FiniteSpectrum(p, &w));
  Lattice lat;
  PCHK(lat.Setup(PETSC_COMM_WORLD, p));
  LinearModes modes;
  PCHK(modes.Compute(lat, LinearModesOptions()));
  REQUIRE(modes.Complete());
  REQUIRE(modes.Omega().size() == w.size());
  for (size_t j = 0; j < w.size(); j++) REQUIRE(std::abs(modes.Omega()[j] - w[j]) < 1e-12);
  return w;
}

} // namespace

TEST_CASE("transition: the gamma grid holds 0 and every +-gamma pair exactly", "[bands][transition][serial]")
{
  const std::vector<PetscReal> g = GammaGrid(-1, 1, 201);
  REQUIRE(g.size() == 201);
  REQUIRE(g.front() == -1.0);
  REQUIRE(g.back() == 1.0);
  REQUIRE(g[100] == 0.0);
  for (size_t i = 0; i < g.size(); i++) REQUIRE(g[i] == -g[200 - i]);
  REQUIRE(std::abs(g[140] - 0.4) == 0.0); // the paper's gamma is a grid point
  REQUIRE(GammaGrid(0, 1, 2) == std::vector<PetscReal>{0, 1});
}

TEST_CASE("transition: the Zak phase jumps between 0 and pi exactly at gamma = 0, the left and right cells in opposite senses", "[bands][transition][serial]")
{
  LatticeParams p; // k = 1, gamma0 = 1
  p.cells = 5;
  std::vector<PetscReal> gammas = GammaGrid(-1, 1, 201);
  // and ever closer to 0: the Wilson loop contains q = pi, where the gap is
  // smallest, so the phase stays quantised however small the gap
  for (PetscReal e : {1e-3, 1e-6, 1e-9, 1e-12}) gammas.insert(gammas.end(), {-e, e});
  for (PetscInt nq : {8, 201}) {
    TransitionResult t;
    PCHK(ComputeTransition(p, gammas, nq, &t));
    for (size_t i = 0; i < gammas.size(); i++)
      for (int band = 0; band < 2; band++) {
        const PetscReal g = gammas[i], zl = t.zak_left[2 * i + band], zr = t.zak_right[2 * i + band];
        INFO("gamma " << g << ", band " << band << ", nq " << nq << ": left " << zl << ", right " << zr);
        if (g > 0) { // left cell (intra k2 < inter k1): nontrivial; right cell trivial
          REQUIRE(std::abs(zl - PETSC_PI) < 1e-12);
          REQUIRE(std::abs(zr) < 1e-12);
        } else if (g < 0) { // the reverse
          REQUIRE(std::abs(zl) < 1e-12);
          REQUIRE(std::abs(zr - PETSC_PI) < 1e-12);
        } else { // k1 = k2: the gap is closed, the phase undefined
          REQUIRE(std::isnan(zl));
          REQUIRE(std::isnan(zr));
        }
      }
    // At gamma = +-1 a bond is zero: flat bands, nothing divides by zero.
    for (size_t i : {(size_t)0, (size_t)200}) {
      for (PetscInt j = 0; j < t.N; j++) REQUIRE(std::isfinite(t.omega[i * t.N + j]));
      REQUIRE(t.bands_inf[4 * i] == Approx(1.0).epsilon(1e-14)); // sqrt(k_hat - 2k): acoustic flat band
      REQUIRE(t.bands_inf[4 * i + 1] == Approx(1.0).epsilon(1e-14));
      REQUIRE(t.bands_inf[4 * i + 2] == Approx(std::sqrt(5.0)).epsilon(1e-14)); // sqrt(k_hat + 2k)
      REQUIRE(t.bands_inf[4 * i + 3] == Approx(std::sqrt(5.0)).epsilon(1e-14));
    }
  }
  REQUIRE(GapClosed(1.0, 1.0));
  REQUIRE_FALSE(GapClosed(1.0 + 1e-12, 1.0 - 1e-12));
}

TEST_CASE("transition: finite spectrum at gamma = +-1 (decoupled dimers, trimers, isolated sites) and 0 (uniform chain)", "[bands][transition][serial]")
{
  for (PetscInt Nc : {1, 3, 25}) {
    LatticeParams p;
    p.k = 1.3;      // not the defaults, so that k, gamma0 and k_hat enter separately
    p.gamma0 = 1.2; // > (2 sqrt(2) - 2) k: K stays positive definite at gamma = 1
    p.cells = Nc;
    const PetscReal kh = p.KHat(), k = p.k; // k_hat = k1 + k2 + gamma0 = 2k + gamma0 at every gamma
    REQUIRE(kh == Approx(3.8));
    // gamma = 1: k1 = 2k, k2 = 0. Interface layout: site 1 alone, Nc - 1 dimers (2,3)..(2Nc-2,2Nc-1),
    // the trimer (2Nc, m, m+1) around the interface site m = 2Nc+1 (a stiff bond on each side),
    // Nc dimers (m+2, m+3).. on the right. A dimer: k_hat -+ 2k; the trimer: k_hat, k_hat -+ 2 sqrt(2) k.
    p.gamma = 1;
    p.layout = Layout::Interface;
    RequireSpectrum(p,
                    Levels({{kh, 2}, {kh - 2 * k, 2 * Nc - 1}, {kh + 2 * k, 2 * Nc - 1}, {kh - 2 * std::sqrt(2.0) * k, 1}, {kh + 2 * std::sqrt(2.0) * k, 1}}));
    // gamma = -1: k1 = 0, k2 = 2k: Nc dimers, m alone, Nc dimers, the last site alone.
    p.gamma = -1;
    RequireSpectrum(p, Levels({{kh, 2}, {kh - 2 * k, 2 * Nc}, {kh + 2 * k, 2 * Nc}}));
    // The half lattices: each end that starts with a cut bond is an isolated site
    // (the edge mode at omega^2 = k_hat of a nontrivial half).
    p.layout = Layout::Left; // 1-2 is k2: nontrivial for gamma > 0
    p.gamma = 1;
    RequireSpectrum(p, Levels({{kh, 2}, {kh - 2 * k, Nc - 1}, {kh + 2 * k, Nc - 1}}));
    p.gamma = -1;
    RequireSpectrum(p, Levels({{kh - 2 * k, Nc}, {kh + 2 * k, Nc}}));
    p.layout = Layout::Right; // 1-2 is k1: nontrivial for gamma < 0
    p.gamma = 1;
    RequireSpectrum(p, Levels({{kh - 2 * k, Nc}, {kh + 2 * k, Nc}}));
    p.gamma = -1;
    RequireSpectrum(p, Levels({{kh, 2}, {kh - 2 * k, Nc - 1}, {kh + 2 * k, Nc - 1}}));
    // gamma = 0: every bond k and every diagonal k_hat, K = k_hat I - k (path adjacency):
    // omega_j^2 = k_hat - 2k cos(j pi / (N + 1)), j = 1..N; the gap is closed.
    p.gamma = 0;
    for (Layout l : {Layout::Interface, Layout::Left, Layout::Right}) {
      p.layout = l;
      std::vector<PetscReal> chain;
      for (PetscInt j = 1; j <= p.N(); j++) chain.push_back(kh - 2 * k * std::cos(j * PETSC_PI / (p.N() + 1)));
      std::sort(chain.begin(), chain.end());
      RequireSpectrum(p, chain);
    }
  }
}

TEST_CASE("transition: where K is not positive definite, lambda_min says so and omega is clamped to 0", "[bands][transition][serial]")
{
  LatticeParams p;
  p.k = 1.3;
  p.gamma0 = 0.7; // the trimer around the interface site at gamma = 1: k_hat - 2 sqrt(2) k < 0
  TransitionResult t;
  PCHK(ComputeTransition(p, {0.4, 1.0}, 8, &t));
  REQUIRE(t.lambda_min[0] > 0);
  REQUIRE(std::abs(t.lambda_min[1] - (p.KHat() - 2 * std::sqrt(2.0) * p.k)) < 1e-13);
  REQUIRE(t.omega[t.N] == 0.0); // row 1, mode 0
  REQUIRE(t.omega[t.N + 1] == Approx(std::sqrt(p.KHat() - 2 * p.k)).epsilon(1e-13));
}

TEST_CASE("transition: the finite spectrum equals the linear study's SLEPc modes, the same on every rank", "[bands][transition]")
{
  for (Layout l : {Layout::Interface, Layout::Left, Layout::Right})
    for (PetscReal gamma : {-0.7, 0.4}) {
      LatticeParams p;
      p.layout = l;
      p.gamma = gamma;
      const std::vector<PetscReal> w = RequireSameAsModes(p);
      // every rank computes the whole spectrum itself: bit for bit rank 0's
      std::vector<PetscReal> w0 = w;
      MPI_Bcast(w0.data(), (int)w0.size(), MPIU_REAL, 0, PETSC_COMM_WORLD);
      REQUIRE(w0 == w);
    }
  // A perturbed lattice: the same K as the Lattice assembles (LatticeSprings).
  LatticeParams p;
  p.perturbation = Perturbation::Achiral;
  p.delta = 0.1;
  p.seed = 7;
  RequireSameAsModes(p);
}
