#pragma once
// Two stiff dimers joined by a weak soft bond (layout right, Nc = 2, gamma =
// 0.9): two weakly coupled identical hardening oscillators, mirror-symmetric,
// whose upper optical NNM loses stability in a pitchfork that first-order
// averaging predicts (test_floquet.cpp, test_bifurcations.cpp).
#include "bands/linear_modes.hpp"
#include "helpers.hpp"
#include "orbits/continuation.hpp"

namespace nltopo::test {

struct CoupledDimers {
  Lattice lat;
  EffectList fx{lat};
  LinearModes modes;
  PeriodicFlow flow;
  Shooting shoot;
  PetscErrorCode Setup()
  {
    LatticeParams p;
    PetscFunctionBeginUser;
    p.layout = Layout::Right;
    p.cells = 2;
    p.gamma = 0.9;
    PetscCall(lat.Setup(PETSC_COMM_WORLD, p));
    PetscCall(modes.Compute(lat, LinearModesOptions()));
    PetscCall(BuildLatticeEffects(lat, &fx));
    PetscCall(flow.Setup(fx, FlowOptions()));
    PetscCall(shoot.Setup(flow, ShootingOptions()));
    PetscFunctionReturn(0);
  }
  // The NNM family of linear mode j up to omega_max, in small steps (to resolve the onset).
  PetscErrorCode Continue(PetscInt j, PetscReal omega_max, PointHook *hook, Branch *out = nullptr)
  {
    ContinuationOptions co;
    Branch b;
    PetscFunctionBeginUser;
    co.verbose = PETSC_FALSE;
    co.max_change = 0.05;
    co.omega_max = omega_max;
    PetscCall(ContinueBranch(shoot, modes.Mode(j), 2 * PETSC_PI / modes.Omega()[j], co, "dimers", out ? out : &b, hook));
    PetscFunctionReturn(0);
  }
};

} // namespace nltopo::test
