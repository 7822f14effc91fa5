#pragma once
// -cont_switch: the family born at a located branch point or period doubling
// (README.md "Branch switching"). At the event's orbit X* = (z*, T*, beta*)
// the new family leaves along the critical eigenvector phi of M:
//   branch point (kind 2, a pair through +1): the new pair's direction at +1;
//     the new orbits have period ~ T*;
//   period doubling (kind 3, a pair through -1): M phi = -phi, so z* + eps phi
//     returns to z* - eps phi after T* and to itself after 2 T*: the new
//     orbits have period ~ 2 T*. Traversed twice, the parent's orbit is a
//     fixed point of the 2 T* map with the multiplier (-1)^2 = +1 there, so
//     the doubled family branches off it as at a branch point. The two sides
//     of phi are one family (each orbit passes near z* + eps phi and, T*
//     later, near z* - eps phi).
// The first orbit is found by the shooting Newton with the pinning
// constraint phi . (z0 - z*) = eps (an arclength constraint along
// (phi, 0, 0)), which keeps it off the parent family (whose own tangent is
// orthogonal to phi at a symmetry-breaking pitchfork, and transversal to it
// otherwise). The two orbits X* (at period m T*) and X1 then start a
// continuation exactly as a resume does (orbits/continuation.hpp): the first
// step along the chord X1 - X*, of its length.
#include "stability/bifurcation_locator.hpp"

namespace nltopo {

// The period of the family born at an event of this kind, in periods of the
// parent orbit: 1 at a branch point, 2 at a period doubling, 0 for a kind
// that starts no family (folds, collisions).
PetscInt SwitchedPeriodMultiple(EventKind k);

// The start of the family born at event e (a branch point or a period
// doubling) whose orbit on the parent is Xs (BifurcationLocator::OrbitAt at
// the event, period T*), on the side sign (+1 or -1) of phi, with
// |eps| = step |z*|: a Branch of two points (X* at period m T*, m =
// SwitchedPeriodMultiple(e.kind), and X1; z0 rows on rank 0) with the step
// to take next, for ContinueBranch's resume argument. The flow must
// integrate with m times the parent's period multiple (PeriodMultipleScope,
// orbits/flow.hpp) here and for the whole family, so that its orbits have
// the parent's step size and X* is an orbit of the same discrete map. *pinned: the residual of
// X1's Newton converged; *away: |phi . (z1 - z*)| / |z1 - z*|, the share of
// the first step along phi (1: straight off the parent).
PetscErrorCode StartSwitchedBranch(Shooting &shoot, Vec Xs, const BifurcationEvent &e, PetscReal step, PetscInt sign, Branch *start, bool *pinned,
                                   PetscReal *away);

} // namespace nltopo
