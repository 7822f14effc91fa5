#include "studies/workprecision.hpp"
#include "core/log.hpp"
#include "core/gather.hpp"
#include "core/option_table.hpp"
#include "studies/wp_configs.hpp"
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <sstream>

namespace nltopo {

const char *const kWpObservables[5] = {"mcr", "t_off", "nl_ratio", "energy", "state"};

std::vector<std::string> DefaultWorkPrecisionConfigs(bool shooting)
{
  if (shooting) {
    // the shooting integrators (docs/integrators.md) at three steps per period each
    std::vector<std::string> c;
    for (const char *n : {"32", "64", "128"}) c.push_back(std::string("-nnm_ts_type symsplit -nnm_ts_symsplit_scheme bm4 -nnm_steps_per_period ") + n);
    for (const char *n : {"32", "64", "128"}) c.push_back(std::string("-nnm_ts_type symsplit -nnm_ts_symsplit_scheme bm6 -nnm_steps_per_period ") + n);
    for (const char *n : {"64", "128", "256"}) c.push_back(std::string("-nnm_ts_type rk -nnm_ts_rk_type 5dp -nnm_steps_per_period ") + n);
    return c;
  }
  // The shipped integrators (docs/integrators.md) at three
  // accuracies each: the splitting at three fixed steps, the adaptive pairs
  // (and the paper's ode45 analogue, rk 5dp) at three tolerances.
  std::vector<std::string> c;
  for (const char *dt : {"0.4", "0.2", "0.1"}) c.push_back(std::string("-sim_ts_type symsplit -sim_ts_symsplit_scheme bm4 -sim_ts_dt ") + dt);
  for (const char *dt : {"0.4", "0.2", "0.1"}) c.push_back(std::string("-sim_ts_type symsplit -sim_ts_symsplit_scheme bm6 -sim_ts_dt ") + dt);
  for (const char *tol : {"1e-6", "1e-8", "1e-10"})
    c.push_back(std::string("-sim_ts_type rkn -sim_ts_rkn_scheme dep86 -sim_ts_rtol ") + tol + " -sim_ts_atol " + tol);
  for (const char *tol : {"1e-6", "1e-8", "1e-10"})
    c.push_back(std::string("-sim_ts_type rk -sim_ts_rk_type 5dp -sim_ts_rtol ") + tol + " -sim_ts_atol " + tol);
  return c;
}

namespace {

using namespace wp;

struct Outcome {
  PetscReal obs[kWpNumObservables - 1] = {0}; // the scalars (mcr, t_off, nl_ratio, energy)
  OwnedVec z;                                 // final state
  PetscReal t_final = 0;
  SimulationResult r;
};

// Errors of every observable of x against y (the state: relative 2-norm).
PetscErrorCode Errors(const Outcome &x, const Outcome &y, std::vector<PetscReal> *e)
{
  PetscFunctionBeginUser;
  e->assign(kWpNumObservables, 0.0);
  PetscReal *err = e->data();
  for (int k = 0; k < kWpNumObservables - 1; k++) err[k] = Rel(x.obs[k], y.obs[k]);
  PetscCall(StateDistance(x.z, y.z, &err[kWpNumObservables - 1]));
  PetscFunctionReturn(0);
}

// One run of the scene with the options as they stand; wall = max over ranks.
// rule: the first run applies the amplitude rule (and fixes S for the rest).
PetscErrorCode RunScene(const Lattice &lat, ToneBurst *burst, bool rule, Outcome *out, PetscReal *wall)
{
  MPI_Comm comm = lat.Comm();
  SimulationOptions so;
  PetscLogDouble t0, t1;
  PetscFunctionBeginUser;
  PetscCall(SimulationOptionsFromOptions(comm, &so)); // a configuration may set -sim_dt_quartic_energy
  so.sample_dt = 0;
  so.progress = 0;
  EffectList fx(lat);
  PetscCall(BuildEffects(lat, burst, &fx));
  PetscCallMPI(MPI_Barrier(comm));
  PetscCall(PetscTime(&t0));
  if (rule) {
    PetscInt rescalings;
    PetscCall(SimulateForced(fx, so, NULL, &out->r, &rescalings));
  } else PetscCall(Simulate(fx, so, NULL, NULL, &out->r));
  PetscCall(PetscTime(&t1));
  double w = t1 - t0;
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &w, 1, MPI_DOUBLE, MPI_MAX, comm));
  *wall = w;
  const SimulationResult &r = out->r;
  out->obs[0] = r.mcr;
  out->obs[1] = r.t_off;
  out->obs[2] = r.nl_ratio;
  out->obs[3] = r.energy_final;
  out->z.reset();
  PetscCall(VecDuplicate(r.z_final, out->z.out()));
  PetscCall(VecCopy(r.z_final, out->z));
  out->t_final = so.t_final;
  PetscFunctionReturn(0);
}

} // namespace

// The -wp_ blocks share one title, as they always have. PETSc lists a prefix
// and title once under -help, so -help shows -wp_scene alone; with titles of
// their own, the value-shape check (core/options_audit.hpp) would know
// -wp_configs and refuse a missing value with its generic line before the
// one below that says how to write it.
static const char *const kWpTitle = "Work-precision study (-study workprecision)";
static const char *const kWpReference = "-sim_ts_type rkn -sim_ts_rkn_scheme dep1210";
static const char *const kWpNnmReference = "-nnm_ts_type rk -nnm_ts_rk_type 5dp";

namespace {
enum class WpScene { Simulate, Shooting };
struct WpSceneOption {
  WpScene scene = WpScene::Simulate;
};
const char *const kWpSceneNames[] = {"simulate", "shooting"};
} // namespace

// Read first: the default configurations follow the scene.
static const auto &kWpSceneTable = DeclareOptionTable<WpSceneOption>("wp_", kWpTitle, [](OptionTable<WpSceneOption> &t) {
  t.Enum("scene", &WpSceneOption::scene, kWpSceneNames, 2,
         "What is integrated: simulate (one forced run of the scene) or shooting (one orbit of the insulated NNM branch)");
});

// Every -wp_ option is physics: two runs that differ in one do not replace each other.
static const auto &kWpTable = DeclareOptionTable<WorkPrecisionOptions>("wp_", kWpTitle, [](OptionTable<WorkPrecisionOptions> &t) {
  using W = WorkPrecisionOptions;
  t.String("reference", &W::reference, "Reference integrator (without tolerance; steps capped: the interpolant's window integrals)")
      .Default(kWpReference)
      .Real("reference_tol", &W::reference_tol, Closed(1e-16, 1e-4),
            "First reference tolerance (rtol = atol); tightened 10x until two successive references agree")
      .Real("reference_dt_max", &W::reference_dt_max, LeftOpen(0, 1e3),
            "Step cap of the first reference (halved with each tightening: the window integrals on the interpolant converge with the step)")
      .Real("nnm_energy", &W::nnm_energy, LeftOpen(0, 1e6), "-wp_scene shooting: energy of the orbit of the insulated branch")
      .String("nnm_reference", &W::nnm_reference, "-wp_scene shooting: reference integrator (without -nnm_steps_per_period; begin it with a space)")
      .Default(kWpNnmReference)
      .Int("nnm_reference_steps", &W::nnm_reference_steps, Closed(8, 100000),
           "-wp_scene shooting: steps per period of the first reference, doubled until two successive references agree")
      .Real("reference_tol_min", &W::reference_tol_min, Closed(1e-16, 1e-4), "Tightest reference tolerance")
      .Real("reference_agreement", &W::reference_agreement, Open(0, 1), "Two successive references agree to this (relative, every observable): converged")
      .Int("repeats", &W::repeats, Closed(1, 100), "Wall time of a configuration: the median of this many runs")
      .Int("twins", &W::twins, Closed(1, 100), "Predictability floor: this many reference runs with S x (1 + k eps), k = 1, -1, 2, -2, ...")
      .Real("twin_eps", &W::twin_eps, Closed(1e-15, 1e-2), "Relative change of S of the twins")
      .Real("target", &W::target, Closed(0, 1),
            "Print, and write as /workprecision/recommended, the cheapest configuration whose relative error meets this, for each observable (0: off)",
            OptionClass::Extent);
});

std::vector<WpRecommendation> CheapestMeeting(const WorkPrecisionResult &res, PetscReal target)
{
  std::vector<WpRecommendation> out;
  for (size_t q = 0; q < res.observables.size(); q++) {
    WpRecommendation best{res.observables[q], "", NAN, NAN};
    const WorkPrecisionRow *pick = nullptr;
    for (const WorkPrecisionRow &r : res.rows) {
      const PetscReal e = q < r.error.size() ? r.error[q] : NAN;
      if (!std::isfinite(e)) {
        best.unscored++;
        continue;
      }
      if (e > target) {
        if (!pick && !(best.error <= e)) best.error = e; // the smallest error, while none meets the target
        continue;
      }
      if (!pick || r.wall < pick->wall || (r.wall == pick->wall && r.rhs_evals < pick->rhs_evals)) pick = &r;
    }
    if (pick) best.config = pick->config, best.error = pick->error[q], best.wall = pick->wall;
    out.push_back(best);
  }
  return out;
}

// -wp_configs, up to 200 configurations in one value.
// raw: a String row holds PETSC_MAX_PATH_LEN (4096) characters, -wp_configs up
// to 16382; a StringList row (PetscOptionsStringArray) drops empty items and
// reads a missing value as not given, which the "has no value" line needs.
static PetscErrorCode ReadWpConfigs(MPI_Comm comm, char *configs, size_t len, PetscBool *given)
{
  PetscFunctionBeginUser;
  PetscOptionsBegin(comm, "wp_", kWpTitle, NULL);
  PetscCall(PetscOptionsString("-configs",
                               "Comma-separated integrator configurations, each a space-separated list of -sim_ts_* options (begin the list with a space)",
                               NULL, configs, configs, len, given));
  PetscOptionsEnd();
  PetscFunctionReturn(0);
}

PetscErrorCode WorkPrecisionOptionsFromOptions(MPI_Comm comm, WorkPrecisionOptions *o)
{
  char configs[16384];
  PetscBool given;
  std::vector<PetscBool> set;
  WpSceneOption scene{o->shooting ? WpScene::Shooting : WpScene::Simulate};
  PetscFunctionBeginUser;
  PetscCall(kWpSceneTable.Read(comm, &scene));
  o->shooting = scene.scene == WpScene::Shooting;
  if (o->configs.empty()) o->configs = DefaultWorkPrecisionConfigs(o->shooting);
  if (o->reference.empty()) o->reference = kWpReference;
  if (o->nnm_reference.empty()) o->nnm_reference = kWpNnmReference;
  PetscCall(PetscStrncpy(configs, Join(o->configs, ",").c_str(), sizeof(configs)));
  PetscCall(ReadWpConfigs(comm, configs, sizeof(configs), &given));
  PetscCall(kWpTable.Read(comm, o, &set));
  const bool given_ref = kWpTable.Given(set, "reference"), given_nnm_ref = kWpTable.Given(set, "nnm_reference");
  // PETSc takes a value that begins with "-x" for the next option (command line
  // and options files alike), leaving -wp_configs empty: say how to write it.
  PetscCheck(!given || configs[0], comm, PETSC_ERR_USER,
             "-wp_configs has no value: PETSc reads a value that begins with '-' as the next option; begin the list with a space, "
             "-wp_configs \" -sim_ts_type rk -sim_ts_rtol 1e-8 -sim_ts_atol 1e-8, -sim_ts_type symsplit -sim_ts_dt 0.1\"");
  PetscCheck(!given_ref || !o->reference.empty(), comm, PETSC_ERR_USER,
             "-wp_reference has no value: PETSc reads a value that begins with '-' as the next option; begin it with a space, "
             "-wp_reference \" -sim_ts_type rkn -sim_ts_rkn_scheme dep1210\"");
  PetscCheck(!given_nnm_ref || !o->nnm_reference.empty(), comm, PETSC_ERR_USER,
             "-wp_nnm_reference has no value: PETSc reads a value that begins with '-' as the next option; begin it with a space");
  o->nnm_reference = SplitList(o->nnm_reference, ',').empty() ? "" : SplitList(o->nnm_reference, ',')[0];
  if (given) {
    o->configs = SplitList(configs, ',');
    PetscCheck(std::strlen(configs) < sizeof(configs) - 1, comm, PETSC_ERR_USER, "-wp_configs: longer than %zu characters", sizeof(configs) - 2);
  }
  o->reference = SplitList(o->reference, ',').empty() ? "" : SplitList(o->reference, ',')[0];
  PetscCheck(!o->configs.empty() && o->configs.size() <= 200, comm, PETSC_ERR_USER, "-wp_configs must hold 1 to 200 configurations, got %zu",
             o->configs.size());
  OptionPairs p;
  for (size_t k = 0; k < o->configs.size(); k++) PetscCall(ParseConfig(comm, "-wp_configs: configuration", o->configs[k], &p, o->shooting));
  PetscCall(ParseConfig(comm, "-wp_nnm_reference", o->nnm_reference, &p, true));
  for (const auto &pr : p)
    PetscCheck(LowerName(pr.first) != "-nnm_steps_per_period", comm, PETSC_ERR_USER,
               "-wp_nnm_reference: leave out -nnm_steps_per_period (-wp_nnm_reference_steps sets it)");
  PetscCall(ParseConfig(comm, "-wp_reference", o->reference, &p));
  for (const auto &pr : p)
    PetscCheck(LowerName(pr.first) != "-sim_ts_rtol" && LowerName(pr.first) != "-sim_ts_atol" && LowerName(pr.first) != "-sim_ts_adapt_dt_max", comm, PETSC_ERR_USER,
               "-wp_reference \"%s\": leave out %s (the study sets the reference tolerance and step cap: -wp_reference_tol, -wp_reference_dt_max)",
               o->reference.c_str(), pr.first.c_str());
  PetscCheck(o->reference_tol_min <= o->reference_tol, comm, PETSC_ERR_USER,
             "-wp_reference_tol_min and -wp_reference_tol must satisfy 1e-16 <= min <= tol <= 1e-4, got %g and %g", (double)o->reference_tol_min,
             (double)o->reference_tol);
  PetscFunctionReturn(0);
}

PetscErrorCode RunWorkPrecision(const Lattice &lat, ToneBurst *burst, const WorkPrecisionOptions &o, WorkPrecisionResult *res)
{
  MPI_Comm comm = lat.Comm();
  OptionPairs ref_opts;
  PetscFunctionBeginUser;
  *res = WorkPrecisionResult();
  res->observables.assign(kWpObservables, kWpObservables + kWpNumObservables);
  res->reference_change.assign(kWpNumObservables, 0.0);
  res->reference_value.assign(kWpNumObservables, 0.0);
  res->spread.assign(kWpNumObservables, 0.0);
  PetscCall(ParseConfig(comm, "-wp_reference", o.reference, &ref_opts));

  // The converged reference: the reference integrator at rtol = atol = tol,
  // tol / 10, ... until two successive runs agree in every observable.
  Outcome ref, prev;
  bool have_prev = false;
  PetscReal tol = o.reference_tol, cap = o.reference_dt_max;
  char tol_s[32], cap_s[32];
  // the reference integrator at rtol = atol = t with the steps capped at h
  auto reference = [&ref_opts](PetscReal t, PetscReal h) {
    char ts[32], hs[32];
    OptionPairs opts = ref_opts;
    std::snprintf(ts, sizeof(ts), "%g", (double)t);
    std::snprintf(hs, sizeof(hs), "%.17g", (double)h);
    opts.push_back({"-sim_ts_rtol", ts});
    opts.push_back({"-sim_ts_atol", ts});
    opts.push_back({"-sim_ts_adapt_dt_max", hs});
    return opts;
  };
  for (;;) {
    ScopedConfig sc;
    PetscCall(sc.Apply(reference(tol, cap)));
    PetscCall(RunScene(lat, burst, !have_prev, &ref, &res->reference_wall));
    PetscCall(sc.Restore());
    PetscCall(PetscSNPrintf(tol_s, sizeof(tol_s), "%g", (double)tol));
    PetscCall(PetscSNPrintf(cap_s, sizeof(cap_s), "%g", (double)cap));
    res->reference = o.reference + " -sim_ts_rtol " + tol_s + " -sim_ts_atol " + tol_s + " -sim_ts_adapt_dt_max " + cap_s;
    if (have_prev) {
      PetscCall(Errors(prev, ref, &res->reference_change));
      PetscReal worst = 0;
      for (PetscReal c : res->reference_change) worst = std::isnan(c) || c > worst ? c : worst; // a NaN change never agrees (std::max would drop it)
      PetscCall(PetscInfo(NULL, "work-precision reference at %s: largest change %g\n", tol_s, (double)worst));
      if (worst <= o.reference_agreement) {
        res->reference_converged = true;
        break;
      }
    }
    if (tol * 0.1 < o.reference_tol_min * (1 - 1e-9)) break;
    tol *= 0.1;
    cap *= 0.5;
    std::swap(prev, ref);
    have_prev = true;
  }
  res->amplitude = burst->Amplitude();
  for (int k = 0; k < kWpNumObservables - 1; k++) res->reference_value[k] = ref.obs[k];
  PetscCall(VecNorm(ref.z, NORM_2, &res->reference_value[kWpNumObservables - 1]));
  PetscCall(GatherVec(ref.z, true, &res->reference_z));

  // The predictability floor: twins of the reference with S x (1 + k eps).
  {
    ScopedConfig sc;
    PetscCall(sc.Apply(reference(tol, cap)));
    std::vector<PetscReal> lo(ref.obs, ref.obs + kWpNumObservables - 1), hi = lo, lyap;
    PetscReal state_spread = 0;
    for (PetscInt j = 0; j < o.twins; j++) {
      const PetscReal k = (j % 2 ? -1.0 : 1.0) * (PetscReal)(j / 2 + 1);
      ToneBurst twin = *burst;
      twin.ScaleAmplitude(1 + k * o.twin_eps);
      Outcome t;
      PetscReal wall, d;
      PetscCall(RunScene(lat, &twin, false, &t, &wall));
      for (int q = 0; q < kWpNumObservables - 1; q++) lo[q] = std::min(lo[q], t.obs[q]), hi[q] = std::max(hi[q], t.obs[q]);
      PetscCall(StateDistance(t.z, ref.z, &d));
      state_spread = std::max(state_spread, d);
      // ln(|dz(T)| / (eps |k| |z(T)|)) over the free motion after the cut-off:
      // the difference a change of S leaves is ~ eps |k| |z| when the forcing stops.
      const PetscReal t_free = t.t_final - (ref.obs[1] > 0 ? ref.obs[1] : 0);
      if (d > 0 && t_free > 0) lyap.push_back(std::log(d / (o.twin_eps * std::abs(k))) / t_free);
    }
    PetscCall(sc.Restore());
    for (int q = 0; q < kWpNumObservables - 1; q++) res->spread[q] = (hi[q] - lo[q]) / (ref.obs[q] != 0 ? std::abs(ref.obs[q]) : 1);
    res->spread[kWpNumObservables - 1] = state_spread;
    if (!lyap.empty()) {
      std::sort(lyap.begin(), lyap.end());
      res->lyapunov = lyap[lyap.size() / 2];
    }
  }

  // Every configuration: median wall of o.repeats runs, work counters, errors.
  for (size_t c = 0; c < o.configs.size(); c++) {
    WorkPrecisionRow row;
    Outcome out;
    PetscCall(TimeConfiguration(
        comm, o.configs[c], false, o.repeats, [&](PetscReal *w) { return RunScene(lat, burst, false, &out, w); }, &row));
    row.rhs_evals = out.r.counters.rhs;
    row.steps = out.r.steps;
    row.rejected = out.r.rejected;
    PetscCall(Errors(out, ref, &row.error));
    row.value.assign(out.obs, out.obs + kWpNumObservables - 1);
    PetscCall(GatherVec(out.z, true, &row.z_final));
    PetscCall(PetscPrintf(comm, "  %-40s %-10s %9.4f s %9" PetscInt_FMT " RHS  MCR error %.2e  state error %.2e\n", row.method.c_str(), row.accuracy.c_str(),
                          (double)row.wall, row.rhs_evals, (double)row.error[0], (double)row.error[kWpNumObservables - 1]));
    res->rows.push_back(row);
  }
  PetscFunctionReturn(0);
}

} // namespace nltopo
