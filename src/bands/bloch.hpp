#pragma once
// Infinite-lattice Bloch bands and the Zak phase (paper eq. ZakPhaseNumeric).
// A two-site unit cell with intra-cell bond k_a and inter-cell bond k_b has the
// Bloch matrix D(q) = [[k_hat, h], [conj(h), k_hat]], h = -(k_a + k_b e^{-iq}),
// so omega^2 = k_hat -+ |k_a + k_b e^{iq}| (acoustic -, optical +).
#include "lattice/params.hpp"
#include <complex>
#include <vector>

namespace nltopo {

using Complex = std::complex<PetscReal>;

struct BandEdges {
  PetscReal acoustic_bottom, acoustic_top, optical_bottom, optical_top; // omega (rad/s)
};
BandEdges InfiniteBandEdges(const LatticeParams &p);

// Bloch eigenvector of band (0 acoustic, 1 optical) at wavenumber q.
void BlochVector(PetscReal k_intra, PetscReal k_inter, int band, PetscReal q, Complex v[2]);

// Zak phase by the discrete Wilson-loop formula over 2 nq points of the BZ,
// theta = -Im sum_n ln(u(q_n)^H u(q_{n+1})), the loop closed with u(q_0) so the
// result is gauge-invariant; gauge_seed != 0 multiplies every u(q_n) by a
// random phase (to demonstrate that invariance). Wrapped to [-pi/2, 3 pi/2).
PetscReal ZakPhase(PetscReal k_intra, PetscReal k_inter, int band, PetscInt nq, unsigned gauge_seed = 0);

// Wraps an angle into [-pi/2, 3 pi/2) (model.md, Diagnostics).
PetscReal WrapPhase(PetscReal a);

struct BlochResult {
  std::vector<PetscReal> q, omega_acoustic, omega_optical;
  PetscReal zak_left[2], zak_right[2]; // [band]; left cell: intra k2, inter k1; right cell: intra k1, inter k2
};
BlochResult ComputeBloch(const LatticeParams &p, PetscInt nq);

} // namespace nltopo
