#pragma once
// What accuracy costs for one forced run (-study workprecision, /workprecision
// of outputs.md): a list of integrator configurations, each run on the same
// scene (the same forcing amplitude S), timed, and scored against a converged
// reference; and the predictability floor, the spread of each observable under
// a 1e-10 change of S at reference accuracy. The study writes the table; the
// tests call the engine directly.
#include "effects/forcing.hpp"
#include "timeint/simulation.hpp"
#include <string>
#include <vector>

namespace nltopo {

// The observables of a forced run whose errors are reported (outputs.md
// error_<name>): MCR, cut-off time, nonlinear/linear energy ratio, energy at
// the end, and the final state (z = [u, v], relative 2-norm).
extern const char *const kWpObservables[5];
constexpr int kWpNumObservables = 5;

struct WorkPrecisionOptions {
  std::vector<std::string> configs;   // each a space-separated list of -sim_ts_* / -sim_dt_quartic_energy options
  std::string reference;              // the reference integrator without its tolerance
  PetscReal reference_tol = 1e-10;    // first reference tolerance (rtol = atol), tightened x 0.1
  PetscReal reference_tol_min = 1e-13;
  PetscReal reference_dt_max = 0.05;  // step cap of the first reference, halved with each tightening
  PetscReal reference_agreement = 1e-9; // two successive references agree to this in every observable: converged
  PetscInt repeats = 3;               // wall time: median of this many runs
  PetscInt twins = 3;                 // predictability floor: S x (1 + k eps), k = 1, -1, 2, -2, ...
  PetscReal twin_eps = 1e-10;
};
PetscErrorCode WorkPrecisionOptionsFromOptions(MPI_Comm comm, WorkPrecisionOptions *o);
// The default configuration list: the shipped integrators at three accuracies each.
std::vector<std::string> DefaultWorkPrecisionConfigs();

struct WorkPrecisionRow {
  std::string config, method, accuracy; // accuracy: the config's -sim_ts_rtol / -sim_ts_dt; method: the rest
  PetscReal wall = 0;                   // median wall seconds of the solve (max over ranks)
  PetscInt rhs_evals = 0, steps = 0, rejected = 0;
  PetscReal error[kWpNumObservables] = {0};
  PetscReal value[kWpNumObservables - 1] = {0}; // the run's scalar observables (mcr, t_off, nl_ratio, energy)
  std::vector<PetscReal> z_final;               // the run's final state, gathered on every rank (tests)
};

struct WorkPrecisionResult {
  std::vector<WorkPrecisionRow> rows;
  std::string reference;                         // the reference configuration, with its final tolerance
  bool reference_converged = false;
  PetscReal reference_change[kWpNumObservables] = {0}; // between the last two references (relative)
  PetscReal reference_value[kWpNumObservables] = {0};  // the reference's observables (the state: its norm)
  PetscReal reference_wall = 0;
  PetscReal spread[kWpNumObservables] = {0};     // the predictability floor
  PetscReal lyapunov = 0;                        // finite-time estimate from the twins (1/s); 0 without cut-off
  PetscReal amplitude = 0;                       // the S every run used
  std::vector<PetscReal> reference_z;            // the reference's final state, gathered on every rank
};

// Runs every configuration of o on the scene (lattice, burst: S from the
// amplitude rule at the first reference, then fixed; base: the scene's
// simulation options). The options database is restored after each run.
PetscErrorCode RunWorkPrecision(const Lattice &lat, ToneBurst *burst, const WorkPrecisionOptions &o, WorkPrecisionResult *res);

} // namespace nltopo
