#pragma once
// The pieces every NNM study composes: lattice, its effects (conservative:
// NNM families need a conserved energy), linear modes, periodic flow, shooting
// and continuation options; read first (bad options fail before any output
// file exists), built after.
#include "bands/linear_modes.hpp"
#include "core/options_audit.hpp"
#include "orbits/continuation.hpp"
#include "orbits/shooting_system.hpp"
#include <string>
#include <vector>

namespace nltopo {

struct NnmSetup {
  LatticeParams lp;
  LinearModesOptions mo;
  FlowOptions fo;
  ShootingOptions so;
  ContinuationOptions co;
  Lattice lat;
  EffectList fx{lat};
  LinearModes modes;
  PeriodicFlow flow;
  Shooting shoot;

  // The prefixes of the options it reads (studies/registry.hpp StudyContract).
  static std::vector<std::string> OptionPrefixes() { return {"-lattice_", "-linear_", "-nnm_", "-cont_"}; }

  PetscErrorCode ReadOptions(MPI_Comm comm)
  {
    PetscFunctionBeginUser;
    PetscCall(LatticeModelFromOptions(comm, &lp));
    PetscCall(LinearModesOptionsFromOptions(comm, &mo));
    PetscCall(FlowOptionsFromOptions(comm, &fo));
    PetscCall(ShootingOptionsFromOptions(comm, &so));
    PetscCall(ContinuationOptionsFromOptions(comm, &co));
    PetscFunctionReturn(0);
  }
  // The solver objects' prefixes (-nnm_snes_*, -nnm_start_snes_*, -nnm_ts_*,
  // -linear_eps_*), for the studies' DeclareSolvers (studies/study.hpp).
  PetscErrorCode DeclareSolvers(MPI_Comm comm)
  {
    PetscFunctionBeginUser;
    PetscCall(DeclareSNES(comm, "nnm_"));
    PetscCall(DeclareSNES(comm, "nnm_start_"));
    PetscCall(DeclareTS(comm, "nnm_"));
    PetscCall(DeclareEPS(comm, "linear_"));
    PetscFunctionReturn(0);
  }
  // The memory of what Build allocates, from the options alone (Study::CheckResources):
  // the lattice, the linear modes' dense path, the dense shooting Jacobian.
  PetscErrorCode CheckResources(MPI_Comm comm) const
  {
    PetscMPIInt rank, size;
    PetscFunctionBeginUser;
    PetscCallMPI(MPI_Comm_rank(comm, &rank));
    PetscCallMPI(MPI_Comm_size(comm, &size));
    const PetscInt N = lp.N(), owned = N / size + (rank < N % size ? 1 : 0); // the DMDA's split of the sites
    PetscCall(CheckLatticeMemory(comm, N));
    PetscCall(CheckLinearModesMemory(comm, N, mo));
    if (so.jacobian == ShootingJacobian::Dense) PetscCall(CheckDenseJacobianMemory(comm, N, 2 * owned + 2));
    PetscFunctionReturn(0);
  }
  // study: "-study continuation", for the refusal of non-conservative effects.
  PetscErrorCode Build(MPI_Comm comm, const char *study)
  {
    PetscFunctionBeginUser;
    PetscCall(lat.Setup(comm, lp));
    PetscCall(BuildEffects(lat, nullptr, &fx));
    PetscCall(fx.RequireConservative(study));
    // before the linear modes, which take minutes on a lattice too long for it
    if (so.jacobian == ShootingJacobian::Dense) PetscCall(CheckDenseJacobianMemory(comm, lat.N(), 2 * lat.OwnedCount() + 2));
    PetscCall(modes.Compute(lat, mo));
    PetscCall(flow.Setup(fx, fo));
    PetscCall(shoot.Setup(flow, so));
    PetscFunctionReturn(0);
  }
};

} // namespace nltopo
