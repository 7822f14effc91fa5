#pragma once
// One forced (or free) run of the lattice with PETSc TS (options prefix -sim_):
// the tone burst until E >= E* (located with a TS event where the TS type can
// roll back; checked after every step otherwise), then free motion; RMS per
// site, MCR and the nonlinear/linear potential ratio over the window after the
// cut-off. Every study that integrates a forced run calls this one function.
#include "effects/forcing.hpp"
#include "effects/rhs.hpp"
#include <vector>

namespace nltopo {

struct SimulationOptions {
  PetscReal t_final = 1000;        // simulated time (the run ends here)
  PetscReal t_start = 0;           // the run starts here (continuing an earlier run from its final state)
  PetscReal sample_dt = 1.0;       // spacing of the stored samples (0: store none)
  PetscReal progress = 10;         // wall seconds between progress lines (0: none)
  PetscReal dt_quartic_energy = 0; // fixed-step types: above this energy the step shrinks as (this / E)^(1/4) (0: off)
  PetscReal dt_scale = 1;          // fixed-step types: the step times this (set by code: the sweep's accuracy ladder)
  PetscReal dt_base = 0;           // fixed-step types: this step in place of -sim_ts_dt (set by code: the sweep's step rule; 0: -sim_ts_dt)
  bool abort_if_missed = false;    // end the run at the end of the burst (t0 + 3 tau) if E* was not reached
  bool keep_cutoff_state = false;  // keep the state at the cut-off in SimulationResult::z_off (set by code: the sweep's Lyapunov exponent)
};
PetscErrorCode SimulationOptionsFromOptions(MPI_Comm comm, SimulationOptions *o);
// Fixed-step types: the factor (E_q / E)^(1/4) on the step above E_q =
// o.dt_quartic_energy (1 at or below it, or with E_q = 0).
PetscReal QuarticStepFactor(const SimulationOptions &o, PetscReal energy);
// The step -sim_ts_dt gives (the initial step Simulate sets when it is not given):
// a fixed-step type's step before dt_base, dt_scale and the quartic shrinking.
PetscErrorCode SimulationGivenStep(PetscReal *dt);

// Receives the state at every sample time (t = 0, dt_s, 2 dt_s, ...).
class SampleSink {
public:
  virtual ~SampleSink() = default;
  virtual PetscErrorCode Sample(PetscReal t, Vec z, const EnergyParts &e) = 0;
  // Whether the sample at time t is wanted (t_off < 0 while the forcing is on);
  // unwanted samples are not interpolated at all.
  virtual bool Wants(PetscReal t, PetscReal t_off) const { return true; }
  // A new attempt of the same run starts (amplitude rule): forget what was sampled.
  virtual void Restart() {}
  // Before the run: at most this many samples will be offered (a sink that
  // keeps them all reserves its storage once, instead of growing per sample).
  virtual void Reserve(PetscInt samples) {}
};

// Displacements of every site (owned block, serial runs: all of them) at the
// sample times from the cut-off on, through a forced run and, if asked, its
// free continuation (Continue(t_off) before the continued Simulate).
class AfterCutoffSamples : public SampleSink {
public:
  explicit AfterCutoffSamples(PetscInt n) : n_(n) {}
  bool Wants(PetscReal t, PetscReal t_off) const override
  {
    const PetscReal off = continued_off_ >= 0 ? continued_off_ : t_off;
    return off >= 0 && t >= off;
  }
  void Continue(PetscReal t_off) { continued_off_ = t_off; }
  void Restart() override { u_.clear(), t_.clear(); }
  PetscErrorCode Sample(PetscReal t, Vec z, const EnergyParts &e) override;
  PetscInt Samples() const { return (PetscInt)t_.size(); }
  const PetscReal *Data() const { return u_.data(); } // Samples() x n, row-major
  const std::vector<PetscReal> &Times() const { return t_; }

private:
  PetscInt n_;
  std::vector<PetscReal> u_, t_;
  PetscReal continued_off_ = -1;
};

struct SimulationResult {
  PetscReal t_off = -1;       // time the forcing stopped (-1: never)
  PetscReal window_start = 0; // start of the RMS window (t_off, else docs/model.md's rule)
  PetscReal energy_final = 0;
  PetscReal mcr = 0, nl_ratio = 0;
  PetscInt steps = 0, rejected = 0;
  bool reached = false;          // E* reached while the forcing was on
  bool aborted = false;          // stopped at the end of the burst, E* missed (abort_if_missed)
  PetscReal energy_peak = 0;     // largest E at a step end while the forcing was on
  EffectCounters counters;       // counters.rhs = RHS evaluations (of this run)
  PetscInt rhs_all_attempts = 0; // RHS evaluations of every attempt of SimulateForced (the work done)
  OwnedVec rms;                  // RMS displacement per site (SiteDM)
  OwnedVec z_final;              // final state
  OwnedVec z_off;                // the state at the cut-off (SimulationOptions::keep_cutoff_state; NULL otherwise or if never cut off)
};

// A forced run under the amplitude rule (docs/model.md "The amplitude rule"): with S
// from the rule, a run whose burst ends (t0 + 3 tau) before E* is reached is
// stopped there and repeated with S scaled by (1.2 E* / E_peak)^(1/p), at least
// 2 and at most 100, with p = 1 after the first miss and then the log-log slope
// of E_peak against S over the last two attempts (clamped to [0.3, 2]), at most
// -force_amplitude_retries times; the last attempt runs to t_final whatever
// happens (and says reached = false). With a given -force_amplitude: one run.
// *rescalings = attempts - 1, or -1 if E* was never reached.
// The tone burst is the scene's forcing effect (fx.Burst(), rescaled in place).
PetscErrorCode SimulateForced(const EffectList &fx, const SimulationOptions &o, SampleSink *sink, SimulationResult *r, PetscInt *rescalings);

// The scene's effects fx (effects/effect.hpp); a free run when it has no
// forcing. z0 NULL starts from rest.
PetscErrorCode Simulate(const EffectList &fx, const SimulationOptions &o, Vec z0, SampleSink *sink, SimulationResult *r);

} // namespace nltopo
