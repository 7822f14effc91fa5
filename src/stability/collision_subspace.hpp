#pragma once
// The two colliding pairs of a Hamiltonian-Hopf curve (kind 5), told apart
// from the other pairs near the collision by their invariant subspace: at
// every point of the curve the two pairs' multipliers coincide (a Jordan
// block), so their eigenvectors do too, but the 4-dimensional real invariant
// subspace of the two pairs (their upper members and conjugates) is well
// defined. Along the curve the pairs are the ones whose subspace overlaps
// most with the last point's; where band pairs come close in b (long
// lattices, where two collision curves cross), the nearest two in b are not
// always them (docs/studies/stabilitymap.md "Limitations").
#include <petscsys.h>
#include <complex>
#include <vector>

namespace nltopo {

struct CollisionChoice {
  bool ok = false;                         // two pairs were found to collide (real or conjugate b's)
  PetscReal g = NAN, bmid = 0;             // Re (b1 - b2)^2 and Re (b1 + b2) / 2 of the chosen pairs
  std::vector<PetscReal> basis;            // their invariant subspace: n x 4, orthonormal columns (column-major)
  std::vector<std::complex<PetscReal>> mu; // every multiplier
  PetscReal overlap = 0;                   // ||prev^T basis||_F^2 / 4 of the chosen pairs (1: the same subspace; 0 without prev)
};

// a: the monodromy (n x n, column-major; overwritten). The candidates are the
// upper members (Im mu > tol |mu|) nearest bstar in b = (mu + 1/mu)/2; with
// prev (n x 4, the last point's subspace), the few whose own 2-dim subspace
// lies most in prev's are paired, and the pair whose 4-dim subspace overlaps
// most with prev is chosen, if it overlaps at least half (else none: ok
// false, another collision, not this curve's); without prev, the two nearest
// bstar. Not collective.
PetscErrorCode TrackCollision(int n, PetscReal *a, PetscReal tol, PetscReal bstar, const std::vector<PetscReal> &prev, CollisionChoice *out);

} // namespace nltopo
