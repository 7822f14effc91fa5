#pragma once
// The pieces every forced-run study composes (simulate, sweep, zak, perturb,
// workprecision), as NnmSetup (studies/nnm_setup.hpp) is for the NNM studies:
// lattice, tone-burst forcing, integrator options and, when the forcing needs
// them, the linear modes; read first (bad options fail before any output file
// exists), built after. RunForced is one run of the scene at a forcing.
#include "bands/linear_modes.hpp"
#include "core/options_audit.hpp"
#include "timeint/simulation.hpp"
#include <string>
#include <vector>

namespace nltopo {

struct ForcedScene {
  LatticeParams lp; // read by ReadOptions unless the study read it (zak: its own defaults; perturb: NnmSetup's)
  ToneBurstOptions fo;
  SimulationOptions sim;
  LinearModesOptions mo;
  Lattice lat;
  LinearModes modes;
  ToneBurst burst;    // the scene's forcing (Build with_burst)
  EffectList fx{lat}; // its effects with that forcing

  // When the linear modes are computed: when the forcing needs them, or always
  // (the study itself uses them: band edges, the insulated mode, the edge modes).
  enum class Modes { Needed, Always };
  // The prefixes of the options the scene reads (studies/registry.hpp StudyContract).
  static std::vector<std::string> OptionPrefixes() { return {"-lattice_", "-force_", "-sim_", "-linear_"}; }
  // The one rule: a mode or exponential profile, or the amplitude rule (a
  // forcing without -force_amplitude) needs the linear modes (ToneBurst::Setup).
  static bool NeedsLinearModes(const ToneBurstOptions &fo)
  {
    return fo.profile == ForceProfile::Mode || fo.profile == ForceProfile::Exponential || (fo.profile != ForceProfile::None && fo.amplitude < 0);
  }
  bool ModesComputed() const { return modes_ == Modes::Always || NeedsLinearModes(fo); }

  // read_lattice: false when the study has read lp itself. why_forcing: the
  // error when -force_profile none is given ("-force_profile none: <why>"), or
  // NULL when a run without forcing is allowed. declaring (Study::declaring_):
  // every block is read whatever the options say, and nothing is refused.
  PetscErrorCode ReadOptions(MPI_Comm comm, bool declaring, bool read_lattice, Modes modes, const char *why_forcing)
  {
    PetscFunctionBeginUser;
    modes_ = modes;
    if (read_lattice) PetscCall(LatticeModelFromOptions(comm, &lp));
    PetscCall(ToneBurstOptionsFromOptions(comm, lp, &fo));
    PetscCheck(declaring || !why_forcing || fo.profile != ForceProfile::None, comm, PETSC_ERR_USER, "-force_profile none: %s", why_forcing);
    PetscCall(SimulationOptionsFromOptions(comm, &sim));
    PetscFunctionReturn(0);
  }
  // The mode options (-linear_*), after the study's own blocks: when the modes
  // are computed, or always (declaring, or a study that accepts them anyway).
  PetscErrorCode ReadModeOptions(MPI_Comm comm, bool always)
  {
    PetscFunctionBeginUser;
    if (always || ModesComputed()) PetscCall(LinearModesOptionsFromOptions(comm, &mo)); // the mode profiles and the amplitude rule
    PetscFunctionReturn(0);
  }
  // The solvers of a forced run: -linear_eps_* (the mode profiles and the amplitude rule) and -sim_ts_*.
  static PetscErrorCode DeclareSolvers(MPI_Comm comm)
  {
    PetscFunctionBeginUser;
    PetscCall(DeclareEPS(comm, "linear_"));
    PetscCall(DeclareTS(comm, "sim_"));
    PetscFunctionReturn(0);
  }
  // What Build builds: the lattice on comm (PETSC_COMM_SELF: every rank
  // integrates whole runs) and its modes as ModesComputed says; then the
  // scene's forcing at the options' omega_ext and E*; then its effects.
  enum class Upto { Lattice, Burst, Effects };
  PetscErrorCode Build(MPI_Comm comm, Upto upto)
  {
    PetscFunctionBeginUser;
    PetscCall(lat.Setup(comm, lp));
    if (ModesComputed()) PetscCall(modes.Compute(lat, mo));
    // -force_mode_index counts all N modes: the shift-invert path (N above
    // -linear_dense_max) holds only those near the band edges, whose k-th is another mode
    PetscCheck(fo.profile != ForceProfile::Mode || modes.Complete(), comm, PETSC_ERR_USER,
               "-force_mode_index %" PetscInt_FMT ": linear mode indices count all N = %" PetscInt_FMT
               " modes, but N > -linear_dense_max %" PetscInt_FMT " computes only those near the band edges; raise -linear_dense_max to at least N",
               fo.mode, lat.N(), mo.dense_max);
    if (upto != Upto::Lattice) PetscCall(burst.Setup(lat, fo, ModesOrNull()));
    if (upto == Upto::Effects) PetscCall(BuildEffects(lat, &burst, &fx));
    PetscFunctionReturn(0);
  }
  const LinearModes *ModesOrNull() const { return ModesComputed() ? &modes : NULL; }
  // The memory of what Build allocates on comm, from the options alone
  // (Study::CheckResources): the lattice and, when computed, the linear modes' dense path.
  PetscErrorCode CheckResources(MPI_Comm comm) const
  {
    PetscFunctionBeginUser;
    PetscCall(CheckLatticeMemory(comm, lp.N()));
    if (ModesComputed()) PetscCall(CheckLinearModesMemory(comm, lp.N(), mo));
    PetscFunctionReturn(0);
  }

private:
  Modes modes_ = Modes::Needed;
};

// One forced run on lat with forcing pf (burst: set up here, kept for its
// amplitude): its effects, then SimulateForced.
inline PetscErrorCode RunForced(const Lattice &lat, const LinearModes *modes, const ToneBurstOptions &pf, const SimulationOptions &sim, SampleSink *sink,
                                ToneBurst *burst, SimulationResult *r, PetscInt *rescalings)
{
  PetscFunctionBeginUser;
  PetscCall(burst->Setup(lat, pf, modes));
  EffectList fx(lat);
  PetscCall(BuildEffects(lat, burst, &fx));
  PetscCall(SimulateForced(fx, sim, sink, r, rescalings));
  PetscFunctionReturn(0);
}

} // namespace nltopo
