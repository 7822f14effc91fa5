#pragma once
// -cont_switch: the family born at a located branch point (README.md
// "Branch switching"). At the event's orbit X* = (z*, T*, beta*) the
// bifurcated family leaves along the critical eigenvector phi of M (the new
// pair's direction at +1). Its first orbit is found by the shooting Newton
// with the pinning constraint phi . (z0 - z*) = eps (an arclength constraint
// along (phi, 0, 0)), which keeps it off the parent family (whose own
// tangent is orthogonal to phi at a symmetry-breaking pitchfork, and
// transversal to it otherwise). The two orbits X* and X1 then start a
// continuation exactly as a resume does (orbits/continuation.hpp): the first
// step along the chord X1 - X*, of its length.
#include "stability/bifurcation_locator.hpp"

namespace nltopo {

// The start of the family born at event e (a branch point) whose orbit is Xs
// (BifurcationLocator::OrbitAt at the event), on the side sign (+1 or -1) of
// phi, with |eps| = step |z*|:
// a Branch of two points (X* and X1; z0 rows on rank 0) with the step to take
// next, for ContinueBranch's resume argument. *pinned: the residual of X1's
// Newton converged; *away: |phi . (z1 - z*)| / |z1 - z*|, the share of the
// first step along phi (1: straight off the parent).
PetscErrorCode StartSwitchedBranch(Shooting &shoot, Vec Xs, const BifurcationEvent &e, PetscReal step, PetscInt sign, Branch *start, bool *pinned,
                                   PetscReal *away);

} // namespace nltopo
