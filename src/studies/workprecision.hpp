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
  std::vector<std::string> configs; // each a space-separated list of -sim_ts_* / -sim_dt_quartic_energy options
  std::string reference;            // the reference integrator without its tolerance
  PetscReal reference_tol = 1e-10;  // first reference tolerance (rtol = atol), tightened x 0.1
  PetscReal reference_tol_min = 1e-13;
  PetscReal reference_dt_max = 0.05;    // step cap of the first reference, halved with each tightening
  PetscReal reference_agreement = 1e-9; // two successive references agree to this in every observable: converged
  PetscInt repeats = 3;                 // wall time: median of this many runs
  PetscInt twins = 3;                   // predictability floor: S x (1 + k eps), k = 1, -1, 2, -2, ...
  PetscReal twin_eps = 1e-10;
  // -wp_scene shooting: one orbit of the insulated NNM branch at energy nnm_energy
  bool shooting = false;
  PetscReal nnm_energy = 1;
  std::string nnm_reference;          // the reference shooting integrator without its steps per period
  PetscInt nnm_reference_steps = 512; // doubled until two successive references agree (at most 16x)
  PetscReal target = 0;               // -wp_target: the cheapest configuration meeting it, per observable (0: off)
};
PetscErrorCode WorkPrecisionOptionsFromOptions(MPI_Comm comm, WorkPrecisionOptions *o);
// The default configuration list: the shipped integrators at three accuracies each.
std::vector<std::string> DefaultWorkPrecisionConfigs(bool shooting = false);

struct WorkPrecisionRow {
  std::string config, method, accuracy; // accuracy: the config's -sim_ts_rtol / -sim_ts_dt; method: the rest
  PetscReal wall = 0;                   // median wall seconds of the solve (max over ranks)
  PetscInt rhs_evals = 0, steps = 0, rejected = 0;
  std::vector<PetscReal> error;   // per observable (WorkPrecisionResult::observables)
  std::vector<PetscReal> value;   // the run's scalar observables (simulate: mcr, t_off, nl_ratio, energy)
  std::vector<PetscReal> z_final; // the run's final state, gathered on every rank (tests)
};

struct WorkPrecisionResult {
  std::vector<std::string> observables; // error_<name>, spread_<name> of outputs.md
  std::vector<WorkPrecisionRow> rows;
  std::string reference; // the reference configuration, with its final tolerance
  bool reference_converged = false;
  std::vector<PetscReal> reference_change; // between the last two references (relative)
  std::vector<PetscReal> reference_value;  // the reference's observables (the state: its norm)
  PetscReal reference_wall = 0;
  std::vector<PetscReal> spread;      // the predictability floor
  PetscReal lyapunov = 0;             // finite-time estimate from the twins (1/s); 0 without cut-off
  PetscReal amplitude = 0;            // the S every run used
  std::vector<PetscReal> reference_z; // the reference's final state, gathered on every rank
};

// The cheapest configuration (median wall time; then fewer RHS evaluations)
// whose relative error in one observable is at most the target; config ""
// when none meets it (error: then the smallest error of any configuration).
struct WpRecommendation {
  std::string observable, config;
  PetscReal error = NAN, wall = NAN;
  PetscInt unscored = 0; // configurations without a finite error for it: not compared (they decide nothing)
};
std::vector<WpRecommendation> CheapestMeeting(const WorkPrecisionResult &res, PetscReal target);

// Runs every configuration of o on the scene (lattice, burst: S from the
// amplitude rule at the first reference, then fixed; base: the scene's
// simulation options). The options database is restored after each run.
PetscErrorCode RunWorkPrecision(const Lattice &lat, ToneBurst *burst, const WorkPrecisionOptions &o, WorkPrecisionResult *res);

// -wp_scene shooting: the orbit of the insulated branch at o.nnm_energy (the
// scene's lattice and -nnm_* options; the branch is continued to it first),
// solved by shooting with each configuration from the same guess and timed
// (Newton and the monodromy). Observables: omega (relative error), closure
// (the configuration's orbit integrated by the reference flow: |z(T) - z0| /
// |z0|), max_modulus (the largest Floquet multiplier modulus, relative
// error), det (|det M - 1| of the configuration's own monodromy).
PetscErrorCode RunWorkPrecisionShooting(MPI_Comm comm, const WorkPrecisionOptions &o, WorkPrecisionResult *res);

} // namespace nltopo
