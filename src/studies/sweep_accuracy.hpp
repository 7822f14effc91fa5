#pragma once
// The accuracy-aware sweep (-sweep_mcr_tol; docs/studies/sweep.md "The
// accuracy-aware sweep"): each point's first run, at a step the rule
// -sweep_mcr_dt chooses from E* and the tolerance (or the scene's), is checked
// against a run at twice the step and a twin of that run with the amplitude
// moved by 1e-10. Where both agree the first run stands; where the step is too
// coarse the step is halved until two successive runs agree; where the twin
// moves the MCR the point is probed with more twins, and if they spread by more
// than the tolerance it is unpredictable: its MCR is their mean and its spread
// is written next to it.
#include "effects/forcing.hpp"
#include "studies/sweep_store.hpp"
#include "timeint/simulation.hpp"

namespace nltopo {

struct McrAccuracyOptions {
  PetscReal tol = 0;   // relative; 0: off
  PetscInt levels = 3; // at most this many halvings of the step
  PetscInt twins = 4;  // twin runs of an unpredictable point (besides the first run)
  PetscReal twin_eps = 1e-10;
  PetscReal dt_phase = 0;  // the step rule: the forcing's phase per step at tol 1e-3 (0: off, the scene's -sim_ts_dt and -sim_dt_quartic_energy)
  PetscReal dt_energy = 0; // the step rule: E* where the hardened bonds' frequency reaches the linear top (0: the scene's -sim_dt_quartic_energy)
};
// Which step a point's first run takes: the scene's options, or with the rule
// (-sweep_mcr_dt_phase phi; docs/studies/sweep.md "The accuracy-aware sweep")
// h = (tol / 1e-3)^(1/4) min(phi / omega_ext, phi / omega_hard) capped at
// 1 / omega_top, omega_hard = omega_top (E* / E_q)^(1/4): a fixed phase per step
// of the forcing and of the hardened bonds, and a step well inside the scheme's
// stability on the linear lattice.
SimulationOptions McrFirstRunOptions(const McrAccuracyOptions &o, const SimulationOptions &sim, PetscReal omega_ext, PetscReal energy,
                                     PetscReal omega_top);
// The first run's step (before it is shortened to divide the run into equal
// steps), given the scene's -sim_ts_dt.
PetscReal McrFirstStep(const SimulationOptions &first, PetscReal scene_dt, PetscReal energy);
PetscErrorCode McrAccuracyOptionsFromOptions(MPI_Comm comm, McrAccuracyOptions *o);
// -sweep_mcr_tol needs a fixed-step type (the ladder halves its step): one line otherwise.
PetscErrorCode CheckMcrAccuracyIntegrator(MPI_Comm comm, const McrAccuracyOptions &o);

// After the point's first run (r: with the options first, S final in burst):
// refines or replaces pt's MCR (and t_off, nl_ratio, energy_final with the
// accepted run's) and sets mcr_error, mcr_spread, predictable, runs, mcr_dt;
// adds the work to pt->rhs. h is the first run's step (McrFirstStep).
PetscErrorCode RefineMcr(const Lattice &lat, const ToneBurst &burst, const SimulationOptions &first, PetscReal h, const McrAccuracyOptions &o,
                         const SimulationResult &r, SweepPoint *pt);

} // namespace nltopo
