// Linear modes and Bloch bands against closed forms (model.md "Standard values").
#include "bands/linear_modes.hpp"
#include "core/gather.hpp"
#include "effects/forcing.hpp"
#include "helpers.hpp"
#include <cmath>

using namespace nltopo;
using namespace nltopo::test;

TEST_CASE("insulated mode: omega = sqrt(3), even-site support, -k2/k1 decay", "[bands]")
{
  LatticeParams p; // paper defaults, Nc = 25
  Lattice lat;
  PCHK(lat.Setup(PETSC_COMM_WORLD, p));
  LinearModes modes;
  PCHK(modes.Compute(lat, LinearModesOptions()));
  REQUIRE(modes.Complete());
  const NamedModes &nm = modes.Named();
  REQUIRE(std::abs(nm.insulated_omega - std::sqrt(3.0)) < 1e-10);
  REQUIRE(nm.insulated_cluster == 2);    // the insulated mode and the left-end edge mode (model.md "Trap")
  REQUIRE(nm.insulated_residual < 1e-8); // the projection is an eigenvector (its Rayleigh quotient is k_hat by construction)
  // It is an eigenvector of K to the accuracy of the finite lattice: ||K x - 3 x|| tiny.
  OwnedVec r;
  PCHK(VecDuplicate(modes.Insulated(), r.out()));
  PCHK(MatMult(lat.K(), modes.Insulated(), r));
  PCHK(VecAXPY(r, -3.0, modes.Insulated()));
  PetscReal res;
  PCHK(VecNorm(r, NORM_2, &res));
  REQUIRE(res < 1e-8);
  const auto x = Gather(modes.Insulated());
  const PetscInt m1 = p.InterfaceSite(); // 0-based index of model.md's site m (51)
  // 1-based site s is x[s-1]; m = 51: u_{m+1} = x[m1+1], u_{m-1} = x[m1-1].
  for (PetscInt s = 1; s <= p.N(); s += 2) REQUIRE(x[s - 1] == 0.0); // odd sites at rest
  REQUIRE(x[m1 + 1] > 0);
  REQUIRE(x[m1 - 1] == Approx(-x[m1 + 1]).epsilon(1e-10));
  const PetscReal ratio = -p.K2() / p.K1(); // -3/7
  REQUIRE(x[m1 + 3] / x[m1 + 1] == Approx(ratio).epsilon(1e-9));
  REQUIRE(x[m1 - 3] / x[m1 - 1] == Approx(ratio).epsilon(1e-9));
  REQUIRE(x[m1 + 5] / x[m1 + 3] == Approx(ratio).epsilon(1e-9));
}

TEST_CASE("small lattices still have an insulated mode (the pair splits by ~0.03 (3/7)^(Nc-4))", "[bands]")
{
  for (PetscInt Nc : {3, 6, 10, 14}) {
    LatticeParams p;
    p.cells = Nc;
    Lattice lat;
    PCHK(lat.Setup(PETSC_COMM_WORLD, p));
    LinearModes modes;
    PCHK(modes.Compute(lat, LinearModesOptions()));
    const NamedModes &nm = modes.Named();
    INFO("Nc = " << Nc << ", residual " << nm.insulated_residual);
    REQUIRE(nm.insulated_cluster == 2);
    REQUIRE(modes.Insulated() != nullptr);
    // The even-site projection is exact up to the left-end coupling (3/7)^(Nc-1).
    REQUIRE(nm.insulated_residual < 2 * std::pow(3.0 / 7.0, Nc - 1));
  }
}

TEST_CASE("band edges: closed form and the finite lattice", "[bands]")
{
  LatticeParams p;
  const BandEdges b = InfiniteBandEdges(p);
  REQUIRE(b.acoustic_bottom == Approx(1.0).epsilon(1e-14));
  REQUIRE(b.acoustic_top == Approx(std::sqrt(2.2)).epsilon(1e-14));
  REQUIRE(b.optical_bottom == Approx(std::sqrt(3.8)).epsilon(1e-14));
  REQUIRE(b.optical_top == Approx(std::sqrt(5.0)).epsilon(1e-14));
  REQUIRE(b.optical_bottom == Approx(1.9494).epsilon(1e-4));
  REQUIRE(b.optical_top == Approx(2.2361).epsilon(1e-4));
  // The closed form is the extremum of the dispersion over the Brillouin zone.
  const BlochResult bl = ComputeBloch(p, 2001);
  const auto mm_a = std::minmax_element(bl.omega_acoustic.begin(), bl.omega_acoustic.end());
  const auto mm_o = std::minmax_element(bl.omega_optical.begin(), bl.omega_optical.end());
  REQUIRE(*mm_a.second == Approx(b.acoustic_top).epsilon(1e-12));
  REQUIRE(*mm_o.first == Approx(b.optical_bottom).epsilon(1e-12));
  REQUIRE(*mm_o.second == Approx(b.optical_top).epsilon(1e-12));

  Lattice lat;
  PCHK(lat.Setup(PETSC_COMM_WORLD, p));
  LinearModes modes;
  PCHK(modes.Compute(lat, LinearModesOptions()));
  const NamedModes &nm = modes.Named();
  const auto &w = modes.Omega();
  // Finite-lattice edges lie inside the infinite bands and within 0.5 % of them for Nc = 25.
  REQUIRE(w[nm.acoustic_top] <= b.acoustic_top);
  REQUIRE(w[nm.acoustic_top] == Approx(b.acoustic_top).epsilon(5e-3));
  REQUIRE(w[nm.optical_bottom] >= b.optical_bottom);
  REQUIRE(w[nm.optical_bottom] == Approx(b.optical_bottom).epsilon(5e-3));
  REQUIRE(w[nm.optical_top] <= b.optical_top);
  REQUIRE(w[nm.optical_top] == Approx(b.optical_top).epsilon(5e-3));
  // Interface mode above the optical band (~2.27), localised at the interface cell.
  REQUIRE(nm.interface == (PetscInt)w.size() - 1);
  REQUIRE(w[nm.interface] == Approx(2.27).epsilon(5e-3));
  // Every eigenvalue is an eigenvalue of K: residual check for all pairs.
  OwnedVec r;
  PCHK(VecDuplicate(modes.Mode(0), r.out()));
  for (size_t j = 0; j < w.size(); j++) {
    PetscReal res;
    PCHK(MatMult(lat.K(), modes.Mode(j), r));
    PCHK(VecAXPY(r, -w[j] * w[j], modes.Mode(j)));
    PCHK(VecNorm(r, NORM_2, &res));
    REQUIRE(res < 1e-10);
  }
}

TEST_CASE("shift-invert path finds the same named modes as the dense path", "[bands]")
{
  LatticeParams p;
  Lattice lat;
  PCHK(lat.Setup(PETSC_COMM_WORLD, p));
  LinearModes dense, near;
  PCHK(dense.Compute(lat, LinearModesOptions()));
  LinearModesOptions o;
  o.dense_max = 10; // force shift-invert for N = 102
  PCHK(near.Compute(lat, o));
  REQUIRE(!near.Complete());
  const NamedModes &a = dense.Named(), &b = near.Named();
  REQUIRE(b.insulated_omega == Approx(a.insulated_omega).epsilon(1e-12));
  REQUIRE(near.Omega()[b.interface] == Approx(dense.Omega()[a.interface]).epsilon(1e-10));
  REQUIRE(near.Omega()[b.acoustic_top] == Approx(dense.Omega()[a.acoustic_top]).epsilon(1e-10));
  REQUIRE(near.Omega()[b.optical_bottom] == Approx(dense.Omega()[a.optical_bottom]).epsilon(1e-10));
  REQUIRE(near.Omega()[b.optical_top] == Approx(dense.Omega()[a.optical_top]).epsilon(1e-10));
}

TEST_CASE("Zak phase: pi for the left cell, 0 for the right, gauge invariant", "[bands][serial]")
{
  LatticeParams p;
  const PetscReal k1 = p.K1(), k2 = p.K2();
  for (int band = 0; band < 2; band++) {
    REQUIRE(ZakPhase(k2, k1, band, 50) == Approx(PETSC_PI).epsilon(1e-10)); // left: intra soft, inter stiff
    REQUIRE(ZakPhase(k1, k2, band, 50) == Approx(0.0).margin(1e-10));       // right: intra stiff
    for (unsigned seed : {1u, 2u, 3u}) {                                    // random phase per k-point: same loop product
      REQUIRE(ZakPhase(k2, k1, band, 50, seed) == Approx(PETSC_PI).epsilon(1e-10));
      REQUIRE(ZakPhase(k1, k2, band, 50, seed) == Approx(0.0).margin(1e-10));
    }
  }
  // Band inversion: gamma < 0 swaps the roles of the cells.
  LatticeParams q;
  q.gamma = -0.4;
  REQUIRE(ZakPhase(q.K2(), q.K1(), 1, 50) == Approx(0.0).margin(1e-10));
  // The wrap interval [-pi/2, 3 pi/2) keeps values near 0 and pi apart.
  REQUIRE(WrapPhase(-1e-3) == Approx(-1e-3));
  REQUIRE(WrapPhase(2 * PETSC_PI - 1e-3) == Approx(-1e-3));
  REQUIRE(WrapPhase(-PETSC_PI) == Approx(PETSC_PI));
}

TEST_CASE("exponential forcing profile: the fit of the insulated mode's envelope decays by k2/k1 per cell", "[bands][effects]")
{
  LatticeParams p;
  Lattice lat;
  PCHK(lat.Setup(PETSC_COMM_WORLD, p));
  LinearModes modes;
  PCHK(modes.Compute(lat, LinearModesOptions()));
  PetscReal a, b;
  PCHK(FitExponentialProfile(lat, modes.Insulated(), &a, &b));
  // |u_{m+3} / u_{m+1}| = k2/k1 = 3/7 over two sites (model.md), so b = ln(3/7) / 2 per site.
  REQUIRE(std::abs(b - 0.5 * std::log(3.0 / 7.0)) < 1e-8);
  // and a is the mode's amplitude one site from m: |u_{m+1}| = a e^{b}
  ToneBurstOptions o;
  o.profile = ForceProfile::Exponential;
  o.omega = 2.0;
  ToneBurst burst;
  PCHK(burst.Setup(lat, o, &modes));
  REQUIRE(burst.ExponentialB() == b);
  std::vector<PetscReal> phi;
  PCHK(GatherVec(modes.Insulated(), true, &phi));
  const PetscInt m = p.InterfaceSite();
  REQUIRE(std::abs(a * std::exp(b) - std::abs(phi[m + 1])) < 1e-8);
  // The whole profile on every rank (/sweep/force_eta): zero on the odd sites
  // (1-based), the insulated mode itself on the even ones.
  std::vector<PetscReal> eta;
  PCHK(burst.Profile(lat, &eta));
  REQUIRE((PetscInt)eta.size() == lat.N());
  for (PetscInt i = 0; i < lat.N(); i++) {
    if (i % 2 == 0) REQUIRE(eta[i] == 0.0);
    else REQUIRE(std::abs(eta[i] - phi[i]) < 1e-6);
  }
}
