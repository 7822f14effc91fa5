// -study workprecision: what accuracy costs for one forced run (the scene:
// every option outside -wp_*); /workprecision of outputs.md.
#include "bands/linear_modes.hpp"
#include "core/errors.hpp"
#include "core/log.hpp"
#include "core/options_audit.hpp"
#include "io/output.hpp"
#include "stability/floquet.hpp"
#include "studies/forced_scene.hpp"
#include "studies/nnm_setup.hpp"
#include "studies/registry.hpp"
#include "studies/simulate_store.hpp"
#include "studies/study.hpp"
#include "studies/workprecision.hpp"
#include <cstdio>

namespace nltopo {

namespace {

// Two scenes, -wp_scene chooses: a forced run (simulate; the scene's lattice,
// forcing and integrator) or one orbit of the insulated NNM (shooting,
// studies/workprecision_shooting.cpp, which builds its own objects).
class WorkprecisionStudy : public Study {
protected:
  PetscErrorCode ReadOptions() override
  {
    PetscFunctionBeginUser;
    PetscCall(WorkPrecisionOptionsFromOptions(comm_, &wo_));
    if (wo_.shooting) {                   // the insulated NNM: lattice, modes, flow, shooting, continuation, Floquet
      PetscCall(nnm_.ReadOptions(comm_)); // bad options fail before the output file exists
      if (!declaring_) PetscCall(RejectGivenOptions(comm_, {"-cont_energy_max"}, "-study workprecision -wp_scene shooting (-wp_nnm_energy)"));
      if (declaring_) {
        FloquetOptions flo; // read by RunWorkPrecisionShooting
        PetscCall(FloquetOptionsFromOptions(comm_, &flo));
      }
      PetscFunctionReturn(0);
    }
    PetscCall(sc_.ReadOptions(comm_, declaring_, true, ForcedScene::Modes::Needed, "-study workprecision scores a forced run (MCR after the cut-off)"));
    if (declaring_) {
      // A simulate scene's output options are accepted and ignored (nothing is sampled):
      // any simulate options file can be the base scene.
      SimulateStoreOptions store;
      PetscCall(SimulateStoreOptionsFromOptions(comm_, &store));
    }
    PetscCall(sc_.ReadModeOptions(comm_, true)); // accepted whether or not the forcing needs the modes
    PetscFunctionReturn(0);
  }
  PetscErrorCode DeclareSolvers(MPI_Comm comm) override
  {
    PetscFunctionBeginUser;
    if (wo_.shooting) PetscCall(nnm_.DeclareSolvers(comm));
    else PetscCall(ForcedScene::DeclareSolvers(comm));
    PetscFunctionReturn(0);
  }
  PetscErrorCode CheckResources() override { return wo_.shooting ? nnm_.CheckResources(comm_) : sc_.CheckResources(comm_); }
  PetscErrorCode Build() override
  {
    PetscFunctionBeginUser;
    if (wo_.shooting) PetscFunctionReturn(0);              // RunWorkPrecisionShooting builds the NNM's objects
    PetscCall(sc_.Build(comm_, ForcedScene::Upto::Burst)); // RunWorkPrecision builds the effects of each run
    PetscFunctionReturn(0);
  }
  PetscErrorCode Solve() override
  {
    PetscFunctionBeginUser;
    if (wo_.shooting) {
      PetscCall(PetscPrintf(comm_,
                            "nltopo workprecision: the insulated NNM at E = %g, N = %" PetscInt_FMT "; %zu shooting configurations x %" PetscInt_FMT
                            " repeats, reference %s from %" PetscInt_FMT " steps per period\n",
                            (double)wo_.nnm_energy, nnm_.lp.N(), wo_.configs.size(), wo_.repeats, wo_.nnm_reference.c_str(), wo_.nnm_reference_steps));
      PetscCall(RunWorkPrecisionShooting(comm_, wo_, &res_));
      PetscCall(PetscPrintf(comm_, "  reference: %s (%s; last change: omega %.1e, max|mu| %.1e), omega = %.12f, max|mu| = %.10f\n", res_.reference.c_str(),
                            res_.reference_converged ? "converged" : "NOT converged", (double)res_.reference_change[0], (double)res_.reference_change[2],
                            (double)res_.reference_value[0], (double)res_.reference_value[2]));
      PetscCall(PrintRecommended());
      PetscFunctionReturn(0);
    }
    PetscCall(PetscPrintf(comm_,
                          "nltopo workprecision: N = %" PetscInt_FMT ", omega_ext = %.6f, E* = %g, t_final = %g; %zu configurations x %" PetscInt_FMT
                          " repeats, reference %s from rtol = atol = %g, %" PetscInt_FMT " twins at S x (1 +- %g)\n",
                          sc_.lat.N(), (double)sc_.burst.Omega(), (double)sc_.burst.EnergyStar(), (double)sc_.sim.t_final, wo_.configs.size(), wo_.repeats,
                          wo_.reference.c_str(), (double)wo_.reference_tol, wo_.twins, (double)wo_.twin_eps));
    PetscCall(RunWorkPrecision(sc_.lat, &sc_.burst, wo_, &res_));
    PetscCall(PetscPrintf(comm_, "  reference: %s (%s; last change: MCR %.1e, state %.1e), MCR = %.10f, t_off = %.6f\n", res_.reference.c_str(),
                          res_.reference_converged ? "converged" : "NOT converged", (double)res_.reference_change[0],
                          (double)res_.reference_change[kWpNumObservables - 1], (double)res_.reference_value[0], (double)res_.reference_value[1]));
    PetscCall(PetscPrintf(
        comm_, "  predictability floor (%" PetscInt_FMT " twins, S x (1 + k %g)): MCR %.1e, t_off %.1e, state %.1e; finite-time Lyapunov %.3g /s%s\n",
        wo_.twins, (double)wo_.twin_eps, (double)res_.spread[0], (double)res_.spread[1], (double)res_.spread[kWpNumObservables - 1], (double)res_.lyapunov,
        res_.spread[0] > 1e-3 ? " (chaotic: single-run MCRs are samples)" : ""));
    PetscCall(PrintRecommended());
    PetscFunctionReturn(0);
  }
  // -wp_target: the cheapest configuration meeting it, per observable.
  PetscErrorCode PrintRecommended()
  {
    PetscFunctionBeginUser;
    if (wo_.target <= 0) PetscFunctionReturn(0);
    const std::vector<WpRecommendation> rec = CheapestMeeting(res_, wo_.target);
    PetscCall(PetscPrintf(comm_, "  cheapest configuration with relative error <= -wp_target %g:\n", (double)wo_.target));
    for (size_t q = 0; q < rec.size(); q++) {
      const char *floor = q < res_.spread.size() && res_.spread[q] > wo_.target ? " (the target is below this observable's predictability floor)" : "";
      char unscored[160] = ""; // configurations without an error for it: neither "none" nor "the cheapest" covers them
      if (rec[q].unscored)
        std::snprintf(unscored, sizeof unscored, " [%" PetscInt_FMT " of %zu configurations have no finite error for it and are not compared]", rec[q].unscored,
                      res_.rows.size());
      if (rec[q].config.empty())
        PetscCall(PetscPrintf(comm_, "    %-8s none of the configurations%s (smallest error %.2e)%s%s\n", rec[q].observable.c_str(),
                              rec[q].unscored ? " compared" : "", (double)rec[q].error, floor, unscored));
      else
        PetscCall(PetscPrintf(comm_, "    %-8s %s  (error %.2e, %.4g s)%s%s\n", rec[q].observable.c_str(), rec[q].config.c_str(), (double)rec[q].error,
                              (double)rec[q].wall, floor, unscored));
    }
    PetscFunctionReturn(0);
  }
  PetscErrorCode Write(PetscViewer v) override
  {
    const WorkPrecisionResult &res = res_;
    const char *g = "/workprecision";
    std::vector<std::string> config, method, accuracy;
    std::vector<PetscReal> wall;
    std::vector<PetscInt> rhs, steps, rejected;
    PetscFunctionBeginUser;
    for (const auto &r : res.rows) {
      config.push_back(r.config), method.push_back(r.method), accuracy.push_back(r.accuracy);
      wall.push_back(r.wall), rhs.push_back(r.rhs_evals), steps.push_back(r.steps), rejected.push_back(r.rejected);
    }
    PetscCall(WriteStringArray(v, g, "config", config));
    PetscCall(WriteStringArray(v, g, "method", method));
    PetscCall(WriteStringArray(v, g, "accuracy", accuracy));
    PetscCall(WriteArray(v, g, "wall_seconds", wall));
    PetscCall(WriteIntArray(v, g, "rhs_evals", rhs));
    PetscCall(WriteIntArray(v, g, "steps", steps));
    PetscCall(WriteIntArray(v, g, "rejected_steps", rejected));
    for (size_t q = 0; q < res.observables.size(); q++) {
      std::vector<PetscReal> e;
      for (const auto &r : res.rows) e.push_back(r.error[q]);
      const std::string &name = res.observables[q];
      PetscCall(WriteArray(v, g, ("error_" + name).c_str(), e));
      PetscCall(WriteAttr(v, g, ("spread_" + name).c_str(), res.spread[q]));
      PetscCall(WriteAttr(v, g, ("reference_change_" + name).c_str(), res.reference_change[q]));
      PetscCall(WriteAttr(v, g, ("reference_" + name).c_str(), res.reference_value[q]));
    }
    PetscCall(WriteAttr(v, g, "scene", wo_.shooting ? "shooting" : "simulate"));
    PetscCall(WriteAttr(v, g, "reference", res.reference.c_str()));
    PetscCall(WriteAttr(v, g, "reference_converged", (PetscInt)res.reference_converged));
    PetscCall(WriteAttr(v, g, "reference_wall_seconds", res.reference_wall));
    PetscCall(WriteAttr(v, g, "lyapunov", res.lyapunov));
    PetscCall(WriteAttr(v, g, "twins", wo_.twins));
    PetscCall(WriteAttr(v, g, "twin_eps", wo_.twin_eps));
    PetscCall(WriteAttr(v, g, "repeats", wo_.repeats));
    if (wo_.shooting) PetscCall(WriteAttr(v, g, "nnm_energy", wo_.nnm_energy));
    else {
      PetscCall(WriteAttr(v, g, "amplitude", res.amplitude));
      PetscCall(WriteAttr(v, g, "omega_ext", sc_.burst.Omega()));
      PetscCall(WriteAttr(v, g, "energy_star", sc_.burst.EnergyStar()));
    }
    if (wo_.target > 0) {
      const char *gr = "/workprecision/recommended";
      std::vector<std::string> obs, cfg;
      std::vector<PetscReal> err, wall;
      std::vector<PetscInt> unscored;
      for (const WpRecommendation &r : CheapestMeeting(res, wo_.target))
        obs.push_back(r.observable), cfg.push_back(r.config), err.push_back(r.error), wall.push_back(r.wall), unscored.push_back(r.unscored);
      PetscCall(WriteStringArray(v, gr, "observable", obs));
      PetscCall(WriteStringArray(v, gr, "config", cfg));
      PetscCall(WriteArray(v, gr, "error", err));
      PetscCall(WriteArray(v, gr, "wall_seconds", wall));
      PetscCall(WriteIntArray(v, gr, "unscored", unscored));
      PetscCall(WriteAttr(v, gr, "target", wo_.target));
    }
    PetscFunctionReturn(0);
  }

private:
  WorkPrecisionOptions wo_;
  NnmSetup nnm_;   // shooting: its options only (the header's N)
  ForcedScene sc_; // simulate: the scene
  WorkPrecisionResult res_;
};

} // namespace

StudyContract WorkprecisionStudyContract()
{
  using namespace schema_names;
  return {WithPrefixes({ForcedScene::OptionPrefixes(), NnmSetup::OptionPrefixes(), {"-floquet", "-wp_"}}),
          {{"/workprecision",
            "",
            {{"config", D, S, "nc", "1", "the solver configuration as options"},
             {"method", D, S, "nc", "1", "method name"},
             {"accuracy", D, S, "nc", "1", "accuracy setting"},
             {"wall_seconds", D, R, "nc", "s", "median wall time"},
             {"rhs_evals", D, I, "nc", "1", "RHS evaluations"},
             {"steps", D, I, "nc", "1", "accepted steps"},
             {"rejected_steps", D, I, "nc", "1", "rejected steps"},
             {"error_<observable>", D, R, "nc", "1", "relative error against the reference"},
             {"spread_<observable>", A, R, "scalar", "1", "predictability floor"},
             {"reference_change_<observable>", A, R, "scalar", "1", "change between the last two references"},
             {"reference_<observable>", A, R, "scalar", "as <observable>", "the reference's value"},
             {"scene", A, S, "scalar", "1", "simulate or shooting"},
             {"reference", A, S, "scalar", "1", "the reference configuration"},
             {"reference_converged", A, I, "scalar", "1", "1 if the reference converged", codes::kYesNo},
             {"reference_wall_seconds", A, R, "scalar", "s", "wall time of the reference"},
             {"lyapunov", A, R, "scalar", "1/time", "finite-time Lyapunov estimate (1/s)"},
             {"twins", A, I, "scalar", "1", "-wp_twins"},
             {"twin_eps", A, R, "scalar", "1", "-wp_twin_eps"},
             {"repeats", A, I, "scalar", "1", "-wp_repeats"},
             {"nnm_energy", A, R, "scalar", "energy", "shooting scene: orbit energy"},
             {"amplitude", A, R, "scalar", "force", "simulate scene: forcing amplitude"},
             {"omega_ext", A, R, "scalar", "rad/time", "simulate scene: forcing frequency"},
             {"energy_star", A, R, "scalar", "energy", "simulate scene: E*"}}},
           {"/workprecision/recommended",
            "",
            {{"observable", D, S, "nobs", "1", "each observable"},
             {"config", D, S, "nobs", "1", "the cheapest configuration (median wall time) whose relative error meets -wp_target; empty: none does"},
             {"error", D, R, "nobs", "1", "its relative error (none meets the target: the smallest error of any configuration)"},
             {"wall_seconds", D, R, "nobs", "s", "its median wall time (NaN: none meets the target)"},
             {"unscored", D, I, "nobs", "1", "configurations without a finite error for the observable: not compared, so neither config nor \"none\" covers them (0: all compared)"},
             {"target", A, R, "scalar", "1", "-wp_target"}}}}};
}

std::unique_ptr<Study> CreateWorkprecisionStudy() { return std::make_unique<WorkprecisionStudy>(); }

} // namespace nltopo
