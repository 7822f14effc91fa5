#pragma once
// The exterior route (-floquet_loc_exterior, docs/long-lattices.md "The
// exterior route"): every multiplier of the whole finite lattice beyond
// 1 + floor, for an orbit localized at the interface, at the cost of a window.
//
// The orbit's tangent stiffness K_T(u(t)) differs from the linear lattice's K
// only where the orbit is, so the monodromy differs from the linear lattice's
// M_lin (the same scheme and steps) only on a window P around the interface
// (the orbit's extent plus the distance a tangent wave travels in one period):
//   M = M_lin + P W P^T,   W = P^T (M - M_lin) P.
// W is integrated on a truncated region (the window with a margin on each
// side: the difference of the region maps with K_T and with K, see
// stability/region_map.hpp), M_lin is known from the linear modes: K = Phi
// diag(w^2) Phi^T, and per mode the scheme's 2 x 2 map R_q of the oscillator
// q'' = -w_q^2 q over one period. An eigenvalue mu of M that is not one of
// M_lin's solves the c x c nonlinear eigenproblem (c = 2 window sites)
//   (I + G(mu) W) y = 0,   G(mu) = P^T (M_lin - mu)^-1 P = sum_q (Phi_wq Phi_wq^T) (x) (R_q - mu)^-1,
// y = P^T v the window part of the eigenvector v = -(M_lin - mu)^-1 P W y.
// G's poles are M_lin's multipliers, on the unit circle and dense for a long
// lattice (a root search on a contour would need ~1/floor evaluations). Near a
// point mu0 the poles within -floquet_loc_exterior_arc are therefore kept
// exactly, one unknown each (s_k = b_k^T W y / (lambda_k - mu)), and the far
// ones linearized in mu: a generalized linear eigenproblem of size c + (near
// poles). Its eigenvalues near mu0 are refined by moving mu0 to them until
// they stop moving (successive linear problems, Ruhe 1973): at the fixed point
// the linearization is exact. Scan points every half arc along the upper unit
// semicircle find them all: the spectrum of a real symplectic M is symmetric
// under conjugation and mu -> 1 / mu.
//
// Exact for the finite lattice: its B-E quadruplets (the edge mode with one
// standing band wave) are the dense route's, to the window's tolerance. Not
// for orbits that are not localized (inside the band M - M_lin reaches the
// region's ends): then resolved is false and the caller keeps the damped
// route's verdict.
#include "orbits/flow.hpp"
#include "stability/floquet.hpp"
#include "stability/floquet_localized_options.hpp"
#include <complex>
#include <string>
#include <vector>

namespace nltopo {

struct ExteriorResult {
  bool resolved = false;                   // M - M_lin fits in the region: the roots below are the lattice's
  std::string why;                         // not resolved: why (one clause)
  PetscInt window_sites = 0, region_sites = 0;
  PetscReal floor = 0;                     // roots with |mu| - 1 <= floor are not searched
  PetscReal arc = 0;                       // the scan's arc (-floquet_loc_exterior_arc, or its default)
  std::vector<std::complex<PetscReal>> mu; // every root beyond 1 + floor, upper half plane, by modulus (largest first)
  std::vector<PetscReal> edge;             // each one's edge share (displacement norm within -floquet_edge_sites, whole lattice)
  PetscReal residual = NAN;                // the leading root's |P^T v - y| / |y| (the window part of v against y)
  PetscInt centres = 0, solves = 0;        // scan points and local eigenproblems solved
};

// The route at the orbit (z0, T) with floor = -floquet_tol / 10. vr, vi
// (optional, state layout): the leading root's eigenvector on the whole
// lattice (zero when there is no root). Refuses N > 6000 (the linear modes
// are kept whole on rank 0). Collective.
PetscErrorCode FloquetExterior(PeriodicFlow &flow, Vec z0, PetscReal T, const FloquetOptions &fo, const LocalizedOptions &lo, ExteriorResult *r, Vec vr,
                               Vec vi);

// The largest lattice the exterior route takes (its linear modes: N^2 reals on rank 0).
constexpr PetscInt kExteriorMaxSites = 6000;

} // namespace nltopo
