#pragma once
// The localized-spectrum route for long lattices (-floquet_mf_which localized,
// docs/long-lattices.md "The localized route"): the Floquet multipliers of the
// perturbations localized at the interface, at a cost independent of N.
//
// The tangent (variational) equations only, never the orbit, are damped
// outside a window of W cells on each side of the interface:
//   xi'' = -K_T(u(t)) xi - c(n) xi',
// c(n) = 0 in the window, a smooth ramp (3x^2 - 2x^3 over R cells: a step
// would reflect) up to c, then c over `pad` more cells. A wave that leaves the
// window is absorbed and never returns, as on an infinite lattice: the
// extended (band) multipliers move inside the unit circle by a margin set by
// W and c, not by N, and a localized mode coupled to the band continuum gets
// the multiplier of that coupling in the long-lattice limit (a B-E Krein
// collision of opposite signatures becomes a resonance growing at its Fermi
// golden-rule rate; one of equal signatures decays). Such multipliers do not
// depend on W and c once the window holds the mode and the ramp is smooth
// (LocalizedIndependence checks it).
//
// The damped tangent problem is truncated to the window plus the absorbing
// layer (2 (W + R + pad) + 2 sites): one integration of the orbit on the whole
// lattice records the tangent stiffness K_T(u) of that region at every stage
// of the splitting (the orbit's own -nnm_ts_symsplit_scheme and steps), then
// the region's 2n x 2n damped monodromy (n its sites) is integrated column by
// column, the columns shared among the ranks, and its eigenvalues are taken by
// LAPACK on rank 0 (all of them: no Krylov convergence risk). The damping is
// an exact factor exp(-c h) on the tangent momentum after every step. Needs
// the symplectic flow (-nnm_ts_type symsplit, the default).
#include "stability/floquet_localized_options.hpp"
#include "stability/floquet_mf.hpp"
#include "stability/verdict.hpp"
#include <complex>
#include <vector>

namespace nltopo {

// LocalizedOptions: stability/floquet_localized_options.hpp (part of FloquetMfOptions)

// The truncated region of a lattice with an interface: sites lo..hi (natural
// order), the interface cell's first site, the damping rate of each site.
struct LocalizedRegion {
  PetscInt lo = 0, hi = -1, iface = 0;
  std::vector<PetscReal> c;
  PetscInt Sites() const { return hi - lo + 1; }
  // Whether region site s (0-based) lies in the undamped window.
  bool InWindow(PetscInt s) const { return c[s] == 0; }
};
LocalizedRegion MakeLocalizedRegion(PetscInt N, PetscInt iface, const LocalizedOptions &o);

// What the eigen part returns (rank 0's LAPACK, broadcast).
struct LocalizedSpectrum {
  std::vector<std::complex<PetscReal>> all; // every multiplier of the damped region map
  std::vector<PetscInt> trivial;            // indices into all of the trivial pair (eigenvector along f(z0)); at most 2
  // the leading nontrivial multipliers, one per conjugate pair (upper half plane), by modulus
  std::vector<std::complex<PetscReal>> mu;
  std::vector<PetscReal> edge;   // each one's edge share (displacement norm within -floquet_edge_sites of the interface)
  std::vector<PetscReal> inside; // each one's share of the displacement norm in the undamped window
  std::vector<PetscReal> kappa;  // each one's Krein value -i v^H J v / |v|^2
  std::vector<PetscReal> vector; // the leading one's eigenvector: [re | im], each 2n in region layout [u(lo..hi), v(lo..hi)]
};

// The eigen part on one process: a (2n x 2n column-major, region layout
// [u_lo..u_hi, v_lo..v_hi], overwritten) the damped region map; f (2n, may be
// empty) the field f(z0) on the region, whose direction marks the trivial pair
// among the multipliers within 1e-2 of 1; nev leading pairs.
PetscErrorCode LocalizedEigen(PetscInt n2, PetscReal *a, const LocalizedRegion &reg, const std::vector<PetscReal> &f, PetscInt nev, const FloquetOptions &fo,
                              LocalizedSpectrum *out);

// The damped region map of the orbit (z0, T, beta) as a dense 2n x 2n matrix
// (column-major, region layout) on rank 0 (empty elsewhere), and f(z0) on the
// region. Collective.
PetscErrorCode LocalizedMonodromy(PeriodicFlow &flow, Vec z0, PetscReal T, PetscReal beta, const LocalizedRegion &reg, std::vector<PetscReal> *a,
                                  std::vector<PetscReal> *f);

// The route: the leading localized multipliers (r: re, im, max_modulus,
// krein, instability, resolution = delta, products = the region's columns)
// and the verdict v, with delta = max(-floquet_tol, the change of the leading
// |mu| when the window is halved (-floquet_loc_resolve), the change when W and
// c are halved and doubled (-floquet_loc_check)):
//   unstable-localized / -extended(mu, class)  |mu| > 1 + delta, the vector in the window
//                                              (class: LocalizedClass)
//   stable-to(delta)                           |mu| <= 1 + -floquet_tol and no other beyond 1 + delta
//   unresolved(reason, bound)                  1 + -floquet_tol < |mu| <= 1 + delta (the window's
//                                              resolution), a growing vector in the absorbing
//                                              layer, or LAPACK failed (bound +inf)
// For an unstable verdict also the eigenvector in full-lattice state layout
// (zero outside the region; vi zero for a real multiplier), for
// ConfirmLocalizedGrowth. vr, vi may be null. Collective.
PetscErrorCode FloquetLocalized(PeriodicFlow &flow, Vec z0, PetscReal T, PetscReal beta, const FloquetOptions &fo, const LocalizedOptions &lo, PetscInt nev,
                                LeadingMultipliers *r, OrbitVerdict *v, Vec vr, Vec vi);

// The class of a localized route's eigenvector: Localisation of its edge
// share, except that a vector with more than kRadiatingShare of its
// displacement norm in the absorbing layer (1 - inside) radiates into the band
// continuum: a B-E resonance (class 2), however large its edge share. (The
// dense route's B-E eigenvector mixes the edge mode with one standing band
// wave spread over the lattice; the damped one holds the edge mode and the
// outgoing tail only, so its edge share alone would read E-E.)
constexpr PetscReal kRadiatingShare = 1e-3;
PetscInt LocalizedClass(const FloquetOptions &fo, PetscReal edge, PetscReal inside);

// ConfirmGrowth for the localized route: v = vr + i vi integrated k periods
// on the undamped lattice, its growth measured on the window's sites only.
// The eigenvector of a B-E resonance keeps emitting an outgoing wave whose
// norm adds to the whole vector's, which therefore grows faster than
// |mu|^k (benchmarks/README.md "Issue 35: the localized route"): the window
// holds the mode, whose growth is |mu|^k.
PetscErrorCode ConfirmLocalizedGrowth(PeriodicFlow &flow, Vec z0, PetscReal T, PetscReal beta, Vec vr, Vec vi, const LocalizedOptions &lo,
                                      const FloquetOptions &o, OrbitVerdict *v);

// The independence check: the leading localized multiplier at (W, c) and with
// W and c each halved and doubled (five solves). change[k]: |mu_k - mu_0| of
// variant k (W/2, 2W, c/2, 2c), mu_k the variant's multiplier nearest mu_0
// among its leading nev. Collective.
struct LocalizedIndependenceResult {
  std::complex<PetscReal> mu0;
  std::vector<std::complex<PetscReal>> mu; // the four variants'
  std::vector<PetscReal> change;           // |mu_k - mu0|
  PetscReal max_change = 0;                // the largest
  PetscReal max_modulus_change = 0;        // the largest ||mu_k| - |mu0||
};
PetscErrorCode LocalizedIndependence(PeriodicFlow &flow, Vec z0, PetscReal T, PetscReal beta, const FloquetOptions &fo, const LocalizedOptions &lo,
                                     PetscInt nev, LocalizedIndependenceResult *res);

} // namespace nltopo
