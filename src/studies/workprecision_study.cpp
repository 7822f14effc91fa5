// -study workprecision: what accuracy costs for one forced run (the scene:
// every option outside -wp_*); /workprecision of outputs.md.
#include "bands/linear_modes.hpp"
#include "core/errors.hpp"
#include "core/log.hpp"
#include "core/options_audit.hpp"
#include "io/output.hpp"
#include "stability/floquet.hpp"
#include "studies/nnm_setup.hpp"
#include "studies/registry.hpp"
#include "studies/workprecision.hpp"

namespace nltopo {

PetscErrorCode WorkprecisionStudyOptions(MPI_Comm comm)
{
  LatticeParams lp;
  ToneBurstOptions fo;
  SimulationOptions so;
  LinearModesOptions mo;
  WorkPrecisionOptions wo;
  PetscBool store_u = PETSC_FALSE;
  PetscInt stride = 1;
  PetscFunctionBeginUser;
  PetscCall(WorkPrecisionOptionsFromOptions(comm, &wo));
  if (wo.shooting) { // the insulated NNM: lattice, modes, flow, shooting, continuation, Floquet
    NnmSetup nnm;
    FloquetOptions flo;
    PetscCall(nnm.DeclareOptions(comm));
    PetscCall(FloquetOptionsFromOptions(comm, &flo));
    PetscCall(DeclareOutputOptions(comm, "workprecision"));
    PetscFunctionReturn(0);
  }
  PetscCall(LatticeParamsFromOptions(comm, &lp));
  PetscCall(ToneBurstOptionsFromOptions(comm, lp, &fo));
  PetscCall(SimulationOptionsFromOptions(comm, &so));
  // A simulate scene's output options are accepted and ignored (nothing is sampled):
  // any simulate options file can be the base scene.
  PetscOptionsBegin(comm, "sim_", "Simulate study output (ignored by -study workprecision)", NULL);
  PetscCall(PetscOptionsBool("-store_u", "Ignored here (a simulate scene's option)", NULL, store_u, &store_u, NULL));
  PetscCall(PetscOptionsInt("-store_u_stride", "Ignored here (a simulate scene's option)", NULL, stride, &stride, NULL));
  PetscOptionsEnd();
  PetscCall(LinearModesOptionsFromOptions(comm, &mo));
  PetscCall(DeclareEPS(comm, "linear_"));
  PetscCall(DeclareTS(comm, "sim_"));
  PetscCall(DeclareOutputOptions(comm, "workprecision"));
  PetscFunctionReturn(0);
}

PetscErrorCode WorkprecisionStudy(MPI_Comm comm)
{
  LatticeParams lp;
  ToneBurstOptions fo;
  SimulationOptions so;
  LinearModesOptions mo;
  WorkPrecisionOptions wo;
  std::string path;
  OutputFile out;
  Lattice lat;
  LinearModes modes;
  ToneBurst burst;
  WorkPrecisionResult res;
  PetscLogDouble t_start, t_end;
  PetscFunctionBeginUser;
  PetscCall(PetscTime(&t_start));
  PetscCall(LogRegister());
  PetscCall(PetscLogStagePush(Log().setup));
  PetscCall(WorkPrecisionOptionsFromOptions(comm, &wo));
  PetscCall(OutputPathFromOptions(comm, "workprecision", &path));
  if (wo.shooting) {
    NnmSetup nnm;
    PetscCall(nnm.ReadOptions(comm)); // bad options fail before the output file exists
    PetscCall(out.Open(comm, path));
    PetscCall(PetscLogStagePop());
    PetscCall(PetscPrintf(comm, "nltopo workprecision: the insulated NNM at E = %g, N = %" PetscInt_FMT "; %zu shooting configurations x %" PetscInt_FMT
                                " repeats, reference %s from %" PetscInt_FMT " steps per period\n",
                          (double)wo.nnm_energy, nnm.lp.N(), wo.configs.size(), wo.repeats, wo.nnm_reference.c_str(), wo.nnm_reference_steps));
    PetscCall(PetscLogStagePush(Log().solve));
    PetscCall(RunWorkPrecisionShooting(comm, wo, &res));
    PetscCall(PetscLogStagePop());
    PetscCall(PetscPrintf(comm, "  reference: %s (%s; last change: omega %.1e, max|mu| %.1e), omega = %.12f, max|mu| = %.10f\n", res.reference.c_str(),
                          res.reference_converged ? "converged" : "NOT converged", (double)res.reference_change[0], (double)res.reference_change[2],
                          (double)res.reference_value[0], (double)res.reference_value[2]));
  } else {
    PetscCall(LatticeParamsFromOptions(comm, &lp));
    PetscCall(ToneBurstOptionsFromOptions(comm, lp, &fo));
    PetscCheck(fo.profile != ForceProfile::None, comm, PETSC_ERR_USER, "-force_profile none: -study workprecision scores a forced run (MCR after the cut-off)");
    PetscCall(SimulationOptionsFromOptions(comm, &so));
    PetscCall(LinearModesOptionsFromOptions(comm, &mo));
    PetscCall(out.Open(comm, path));
    PetscCall(lat.Setup(comm, lp));
    const bool need_modes = fo.profile == ForceProfile::Mode || fo.profile == ForceProfile::Exponential || fo.amplitude < 0;
    if (need_modes) PetscCall(modes.Compute(lat, mo));
    PetscCall(burst.Setup(lat, fo, need_modes ? &modes : NULL));
    PetscCall(PetscLogStagePop());

    PetscCall(PetscPrintf(comm, "nltopo workprecision: N = %" PetscInt_FMT ", omega_ext = %.6f, E* = %g, t_final = %g; %zu configurations x %" PetscInt_FMT
                                " repeats, reference %s from rtol = atol = %g, %" PetscInt_FMT " twins at S x (1 +- %g)\n",
                          lat.N(), (double)burst.Omega(), (double)burst.EnergyStar(), (double)so.t_final, wo.configs.size(), wo.repeats, wo.reference.c_str(),
                          (double)wo.reference_tol, wo.twins, (double)wo.twin_eps));
    PetscCall(PetscLogStagePush(Log().solve));
    PetscCall(RunWorkPrecision(lat, &burst, wo, &res));
    PetscCall(PetscLogStagePop());
    PetscCall(PetscPrintf(comm, "  reference: %s (%s; last change: MCR %.1e, state %.1e), MCR = %.10f, t_off = %.6f\n", res.reference.c_str(),
                          res.reference_converged ? "converged" : "NOT converged", (double)res.reference_change[0],
                          (double)res.reference_change[kWpNumObservables - 1], (double)res.reference_value[0], (double)res.reference_value[1]));
    PetscCall(PetscPrintf(comm, "  predictability floor (%" PetscInt_FMT " twins, S x (1 + k %g)): MCR %.1e, t_off %.1e, state %.1e; finite-time Lyapunov %.3g /s%s\n",
                          wo.twins, (double)wo.twin_eps, (double)res.spread[0], (double)res.spread[1], (double)res.spread[kWpNumObservables - 1],
                          (double)res.lyapunov, res.spread[0] > 1e-3 ? " (chaotic: single-run MCRs are samples)" : ""));
  }

  PetscCall(PetscLogStagePush(Log().write));
  PetscViewer v = out.Viewer();
  const char *g = "/workprecision";
  std::vector<std::string> config, method, accuracy;
  std::vector<PetscReal> wall;
  std::vector<PetscInt> rhs, steps, rejected;
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
  PetscCall(WriteAttr(v, g, "scene", wo.shooting ? "shooting" : "simulate"));
  PetscCall(WriteAttr(v, g, "reference", res.reference.c_str()));
  PetscCall(WriteAttr(v, g, "reference_converged", (PetscInt)res.reference_converged));
  PetscCall(WriteAttr(v, g, "reference_wall_seconds", res.reference_wall));
  PetscCall(WriteAttr(v, g, "lyapunov", res.lyapunov));
  PetscCall(WriteAttr(v, g, "twins", wo.twins));
  PetscCall(WriteAttr(v, g, "twin_eps", wo.twin_eps));
  PetscCall(WriteAttr(v, g, "repeats", wo.repeats));
  if (wo.shooting) PetscCall(WriteAttr(v, g, "nnm_energy", wo.nnm_energy));
  else {
    PetscCall(WriteAttr(v, g, "amplitude", res.amplitude));
    PetscCall(WriteAttr(v, g, "omega_ext", burst.Omega()));
    PetscCall(WriteAttr(v, g, "energy_star", burst.EnergyStar()));
  }
  PetscCall(PetscTime(&t_end));
  PetscCall(out.Commit("workprecision", t_end - t_start));
  PetscCall(PetscLogStagePop());
  PetscCall(PetscPrintf(comm, "  wrote %s\n", path.c_str()));
  PetscFunctionReturn(0);
}

} // namespace nltopo
