#pragma once
// The accuracy-aware sweep (-sweep_mcr_tol; docs/studies/sweep.md):
// each point's MCR is checked a posteriori against the same run at twice the
// step, refined by halving the step until two successive runs agree to the
// tolerance; points that do not converge, or that the 0-1 test calls chaotic,
// get twin runs with the amplitude moved by 1e-10, and where the twins spread
// by more than the tolerance the point is unpredictable: its MCR is the twins'
// mean and its spread is written next to it.
#include "effects/forcing.hpp"
#include "studies/sweep_store.hpp"
#include "timeint/simulation.hpp"

namespace nltopo {

struct McrAccuracyOptions {
  PetscReal tol = 0;   // relative; 0: off
  PetscInt levels = 3; // at most this many halvings of the step
  PetscInt twins = 4;  // twin runs of an unpredictable point (besides the first run)
  PetscReal twin_eps = 1e-10;
  PetscReal kcorr_chaotic = 0.7; // a 0-1 test score above this goes straight to the twins
};
PetscErrorCode McrAccuracyOptionsFromOptions(MPI_Comm comm, McrAccuracyOptions *o);
// -sweep_mcr_tol needs a fixed-step type (the ladder halves its step): one line otherwise.
PetscErrorCode CheckMcrAccuracyIntegrator(MPI_Comm comm, const McrAccuracyOptions &o);

// After the point's first run (r: at the scene's step, S final in burst):
// refines or replaces pt's MCR (and t_off, nl_ratio, energy_final with the
// accepted run's) and sets mcr_error, mcr_spread, predictable, runs; adds the
// work to pt->rhs.
PetscErrorCode RefineMcr(const Lattice &lat, const ToneBurst &burst, const SimulationOptions &sim, const McrAccuracyOptions &o, const SimulationResult &r,
                         SweepPoint *pt);

} // namespace nltopo
