#pragma once
// The maximal finite-time Lyapunov exponent (FTLE) of the free lattice flow
// over a window, by Benettin's method (Benettin, Galgani, Giorgilli & Strelcyn,
// Meccanica 15, 1980): one tangent vector integrated along the trajectory by
// the tangent (variational) flow of orbits/flow.hpp, renormalised to unit
// length every `renorm` time units,
//   lambda = (1 / T_w) sum_k ln |w_k|,
// w_k the tangent vector at the end of interval k before its renormalisation.
// On regular motion |w| grows at most polynomially, so lambda T_w stays
// bounded by a few times ln T_w as T_w grows (lambda -> 0 like ln T_w / T_w);
// on chaotic motion lambda converges to a positive exponent. `half` is the
// same estimate over the first half of the window: |lambda - half| says how
// far the finite-time value has converged (docs/studies/sweep.md).
#include "effects/effect.hpp"
#include <cmath>

namespace nltopo {

struct LyapunovResult {
  PetscReal exponent = NAN; // lambda over the window (1/time)
  PetscReal half = NAN;     // lambda over its first half
  PetscReal window = 0;     // T_w
  PetscInt intervals = 0;   // renormalisations
};

// The start vector's entry at natural state index k ([u_1..u_N, v_1..v_N]),
// before normalisation.
inline PetscReal LyapunovStartValue(PetscInt k) { return std::sin(0.7548776662466927 * (k + 1) + 0.3); }

// fx: the free (conservative) effects of the lattice; z0: the state at the
// window's start (not changed); each interval (window / ceil(window / renorm)
// long) integrated in fixed steps of at most dt by the flow's scheme
// (-nnm_ts_type, the symplectic splitting by default). Collective on fx's lattice.
PetscErrorCode FiniteTimeLyapunov(const EffectList &fx, Vec z0, PetscReal window, PetscReal renorm, PetscReal dt, LyapunovResult *r);

} // namespace nltopo
