#pragma once
// The pieces every NNM study composes: lattice, linear modes, periodic flow,
// shooting and continuation options; read first (bad options fail before any
// output file exists), built after.
#include "bands/linear_modes.hpp"
#include "orbits/continuation.hpp"

namespace nltopo {

struct NnmSetup {
  LatticeParams lp;
  LinearModesOptions mo;
  FlowOptions fo;
  ShootingOptions so;
  ContinuationOptions co;
  Lattice lat;
  LinearModes modes;
  PeriodicFlow flow;
  Shooting shoot;

  PetscErrorCode ReadOptions(MPI_Comm comm)
  {
    PetscFunctionBeginUser;
    PetscCall(LatticeParamsFromOptions(comm, &lp));
    PetscCall(LinearModesOptionsFromOptions(comm, &mo));
    PetscCall(FlowOptionsFromOptions(comm, &fo));
    PetscCall(ShootingOptionsFromOptions(comm, &so));
    PetscCall(ContinuationOptionsFromOptions(comm, &co));
    PetscFunctionReturn(0);
  }
  PetscErrorCode Build(MPI_Comm comm)
  {
    PetscFunctionBeginUser;
    PetscCall(lat.Setup(comm, lp));
    PetscCall(modes.Compute(lat, mo));
    PetscCall(flow.Setup(lat, fo));
    PetscCall(shoot.Setup(flow, so));
    PetscFunctionReturn(0);
  }
};

} // namespace nltopo
