#pragma once
// An NNM set-up for the unit tests: a lattice, its linear modes, its own
// effects, the periodic-orbit flow and the shooting on them (default options),
// and the continuation of the family of linear mode j.
#include "bands/linear_modes.hpp"
#include "helpers.hpp"
#include "orbits/continuation.hpp"

namespace nltopo::test {

struct NnmFixture {
  Lattice lat;
  EffectList fx{lat};
  LinearModes modes;
  PeriodicFlow flow;
  Shooting shoot;
  PetscErrorCode Setup(const LatticeParams &p)
  {
    PetscFunctionBeginUser;
    PetscCall(lat.Setup(PETSC_COMM_WORLD, p));
    PetscCall(modes.Compute(lat, LinearModesOptions()));
    PetscCall(BuildLatticeEffects(lat, &fx));
    PetscCall(flow.Setup(fx, FlowOptions()));
    PetscCall(shoot.Setup(flow, ShootingOptions()));
    PetscFunctionReturn(0);
  }
  PetscErrorCode Continue(PetscInt j, const ContinuationOptions &o, Branch *b, PointHook *hook = nullptr)
  {
    PetscFunctionBeginUser;
    PetscCall(ContinueBranch(shoot, modes.Mode(j), 2 * PETSC_PI / modes.Omega()[j], o, "test", b, hook));
    PetscFunctionReturn(0);
  }
};

} // namespace nltopo::test
