// Spring perturbations (paper, "Robustness to perturbations"): chiral ones keep
// diag(K) = k_hat and therefore the insulated mode at exactly sqrt(k_hat);
// achiral ones move it; a seed is one realisation whatever the number of ranks.
#include "bands/linear_modes.hpp"
#include "helpers.hpp"
#include <algorithm>
#include <cmath>

using namespace nltopo;
using namespace nltopo::test;

static PetscReal NearestOmegaTo(const LinearModes &m, PetscReal w)
{
  PetscReal best = PETSC_MAX_REAL;
  for (PetscReal x : m.Omega()) best = std::min(best, std::abs(x - w));
  return best;
}

// The two eigenvalues omega^2 nearest k_hat: the insulated mode and the left-end
// edge mode, split by their exponentially small overlap ((3/7)^Nc ~ 1e-10).
static void NearestPair(const LinearModes &m, PetscReal kh, PetscReal *l1, PetscReal *l2)
{
  std::vector<PetscReal> lam;
  for (PetscReal x : m.Omega()) lam.push_back(x * x);
  std::sort(lam.begin(), lam.end(), [&](PetscReal a, PetscReal b) { return std::abs(a - kh) < std::abs(b - kh); });
  *l1 = lam[0];
  *l2 = lam[1];
}

TEST_CASE("chiral perturbations keep the insulated frequency at sqrt(3); achiral ones move it", "[lattice][perturbation]")
{
  for (PetscInt seed : {1, 2, 3})
    for (PetscReal delta : {0.01, 0.05, 0.25}) {
      LatticeParams p;
      p.perturbation = Perturbation::Chiral;
      p.delta = delta;
      p.seed = seed;
      Lattice lat;
      PCHK(lat.Setup(PETSC_COMM_WORLD, p));
      LinearModes modes;
      PCHK(modes.Compute(lat, LinearModesOptions()));
      // K - k_hat I stays off-diagonal (bipartite), so its spectrum is symmetric
      // about 0: the pair nearest k_hat is centred on it exactly, and its
      // splitting stays exponentially small.
      PetscReal l1, l2;
      NearestPair(modes, 3.0, &l1, &l2);
      INFO("chiral, seed " << seed << ", delta " << delta << ": pair " << l1 - 3 << ", " << l2 - 3);
      REQUIRE(std::abs(0.5 * (l1 + l2) - 3.0) < 1e-12);
      REQUIRE(std::abs(l1 - l2) < 1e-7);
      REQUIRE(std::abs(modes.Named().insulated_omega - std::sqrt(3.0)) < 1e-12); // the even-site projection
      REQUIRE(modes.Named().insulated_residual < 1e-7);
      p.perturbation = Perturbation::Achiral;
      Lattice lat2;
      PCHK(lat2.Setup(PETSC_COMM_WORLD, p));
      LinearModes modes2;
      PCHK(modes2.Compute(lat2, LinearModesOptions()));
      INFO("achiral: nearest eigenfrequency to sqrt(3) off by " << NearestOmegaTo(modes2, std::sqrt(3.0)));
      REQUIRE(NearestOmegaTo(modes2, std::sqrt(3.0)) > 1e-5);
    }
}

TEST_CASE("a perturbation seed is one realisation on any number of ranks; mean |delta| is delta", "[lattice][perturbation]")
{
  LatticeParams p;
  p.perturbation = Perturbation::Achiral;
  p.delta = 0.05;
  p.seed = 7;
  std::vector<PetscReal> bonds, diag, b0, d0;
  LatticeSprings(p, &bonds, &diag); // built on this rank alone
  Lattice lat;
  PCHK(lat.Setup(PETSC_COMM_WORLD, p)); // distributed over the ranks
  PetscInt lo, hi;
  PCHK(MatGetOwnershipRange(lat.K(), &lo, &hi));
  const PetscInt N = lat.N();
  for (PetscInt r = lo; r < hi; r++)
    for (PetscInt c = std::max<PetscInt>(r - 1, 0); c <= std::min(r + 1, N - 1); c++) {
      PetscScalar v;
      PCHK(MatGetValues(lat.K(), 1, &r, 1, &c, &v));
      const PetscReal expect = r == c ? diag[r] : -bonds[std::min(r, c)];
      REQUIRE(v == expect); // the same numbers, bit for bit
    }
  // The unperturbed lattice is the delta = 0 case; a different seed is a different draw.
  LatticeParams q = p;
  q.delta = 0;
  LatticeSprings(q, &b0, &d0);
  for (PetscInt b = 0; b < N - 1; b++) REQUIRE(b0[b] == q.Bond(b));
  for (PetscReal d : d0) REQUIRE(d == q.KHat());
  q = p;
  q.seed = 8;
  std::vector<PetscReal> b8, d8;
  LatticeSprings(q, &b8, &d8);
  REQUIRE(b8 != bonds);
  // delta_b uniform in (-2 delta, 2 delta): the mean |delta_b| over many bonds is delta
  q.cells = 25000;
  LatticeSprings(q, &b8, &d8);
  PetscReal mean = 0;
  for (size_t b = 0; b < b8.size(); b++) mean += std::abs(b8[b] - q.Bond((PetscInt)b)) / q.k;
  mean /= b8.size();
  REQUIRE(std::abs(mean / q.delta - 1) < 0.02);
}
