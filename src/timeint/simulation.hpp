#pragma once
// One forced (or free) run of the lattice with PETSc TS (options prefix -sim_):
// the tone burst until E >= E* (located with a TS event where the TS type can
// roll back; checked after every step otherwise), then free motion; RMS per
// site, MCR and the nonlinear/linear potential ratio over the window after the
// cut-off. Every study that integrates a forced run calls this one function.
#include "effects/rhs.hpp"
#include <vector>

namespace nltopo {

struct SimulationOptions {
  PetscReal t_final = 1000;  // simulated time
  PetscReal sample_dt = 1.0; // spacing of the stored samples (0: store none)
  PetscReal progress = 10;   // wall seconds between progress lines (0: none)
  bool stop_at_cutoff = false; // end the run at the cut-off (amplitude search probes)
};
PetscErrorCode SimulationOptionsFromOptions(MPI_Comm comm, SimulationOptions *o);

// Receives the state at every sample time (t = 0, dt_s, 2 dt_s, ...).
class SampleSink {
public:
  virtual ~SampleSink() = default;
  virtual PetscErrorCode Sample(PetscReal t, Vec z, const EnergyParts &e) = 0;
};

struct SimulationResult {
  PetscReal t_off = -1;        // time the forcing stopped (-1: never)
  PetscReal window_start = 0;  // start of the RMS window (t_off, else README.md's rule)
  PetscReal energy_final = 0;
  PetscReal mcr = 0, nl_ratio = 0;
  PetscInt steps = 0, rejected = 0;
  bool reached = false;        // E* reached while the forcing was on
  EffectCounters counters;     // counters.rhs = RHS evaluations
  OwnedVec rms;                // RMS displacement per site (SiteDM)
  OwnedVec z_final;            // final state
};

// Amplitude rule, nonlinear part (README.md): from the linear rule's S, run the
// burst alone (to t0 + 3 tau) and double S until E* is reached, at most
// -force_amplitude_retries times. *doublings = -1 if E* was never reached.
PetscErrorCode SearchAmplitude(const Lattice &lat, ToneBurst *burst, const SimulationOptions &o, PetscInt *doublings);

// forcing may be NULL (free run). z0 NULL starts from rest.
PetscErrorCode Simulate(const Lattice &lat, const ToneBurst *forcing, const SimulationOptions &o, Vec z0, SampleSink *sink,
                        SimulationResult *r);

} // namespace nltopo
