// -study sweep: a grid of forced tone-burst runs (omega_ext x E*), each the
// simulate study's run (SimulateForced, same code path), scored by MCR, t_off,
// the nonlinear/linear energy ratio and, with -sweep_kcorr, the 0-1 test.
// Runs are spread over the ranks by a shared counter (each rank integrates
// whole runs on PETSC_COMM_SELF, most expensive first), journaled as they
// finish and resumable (-sweep_resume). Output: /sweep of outputs.md.
#include "bands/linear_modes.hpp"
#include "core/cost.hpp"
#include "core/errors.hpp"
#include "core/gather.hpp"
#include "core/log.hpp"
#include "core/option_table.hpp"
#include "core/options_audit.hpp"
#include "core/signals.hpp"
#include "core/work_queue.hpp"
#include "diagnostics/zero_one.hpp"
#include "io/input.hpp"
#include "io/output.hpp"
#include "io/run_options.hpp"
#include "io/schema.hpp"
#include "studies/forced_scene.hpp"
#include "studies/grid_axis.hpp"
#include "studies/registry.hpp"
#include "studies/study.hpp"
#include "stability/lyapunov.hpp"
#include "studies/sweep_accuracy.hpp"
#include "studies/sweep_refine.hpp"
#include "studies/sweep_shard.hpp"
#include "studies/sweep_store.hpp"
#include "timeint/simulation.hpp"
#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <cmath>
#include <limits>
#include <memory>
#include <numeric>
#include <unistd.h>

namespace nltopo {

namespace {

struct SweepOptions {
  // the grid (-sweep_omega_*, -sweep_energy_*: studies/grid_axis.hpp), made from its fields after the table's Read
  PetscReal omega_min = std::sqrt(3.0) / 2, omega_max = 1.5 * std::sqrt(3.0), energy_min = 1e-3, energy_max = 1e3;
  PetscInt omega_n = 50, energy_n = 50;
  AxisSpacing omega_spacing = AxisSpacing::Linear, energy_spacing = AxisSpacing::Log;
  std::vector<PetscReal> omega_list, energy_list;
  std::vector<PetscReal> omega, energy;
  PetscBool resume = PETSC_FALSE, kcorr = PETSC_FALSE;
  PetscInt group_size = 1;                              // -sweep_group_size: ranks per point
  PetscBool lyapunov = PETSC_FALSE;                     // -sweep_lyapunov
  PetscReal lyapunov_renorm = 10, lyapunov_efolds = 20; // -sweep_lyapunov_renorm, -sweep_lyapunov_efolds
  std::string shard_text;                               // -sweep_shard i/n ("": the whole grid), parsed into shard
  SweepShard shard;
  // -sweep_refine_*: a refinement level (studies/sweep_refine.hpp); then omega, energy above are the fine lattice's axes
  std::string refine_from;
  PetscReal refine_mcr = 0.02, refine_kcorr = 0.3, refine_ratio = 1.0;
  PetscInt refine_max_points = 0;
  std::vector<PetscReal> base_omega, base_energy; // the base grid's axes (the -sweep_* axes)
  RefineLattice lattice;
  RefineSelection selection;
  PetscReal checkpoint = 5, progress = 10;
  // 0-1 test (-kcorr_*)
  PetscInt kcorr_nc = 32, kcorr_site_stride = 1; // 32 c values: the median is stable to ~0.02 on the test series (tests/unit)
  PetscReal kcorr_rms_fraction = 0.1;
  PetscReal kcorr_record = 1500; // free motion analysed after t_off (s)
  PetscInt kcorr_lags = 20;
  PetscInt kcorr_seed = 1;
  PetscReal kcorr_sample_dt = 0; // 0: a quarter of the insulated period, pi / (2 sqrt(k_hat))
  McrAccuracyOptions mcr;        // -sweep_mcr_tol
  BandEdges bands{};             // of the infinite lattice, written with the map
  // The forcing profile, the same at every point (S alone follows omega and E*),
  // the linear insulated mode (empty without one) and the exponential fit:
  // written with the map (the paper's Fig. 8a-b).
  std::vector<PetscReal> eta, insulated;
  bool exponential = false;
  PetscReal exp_a = 0, exp_b = 0;
};

const GridAxisFields<SweepOptions> kOmegaAxis = {
    "omega", &SweepOptions::omega_min, &SweepOptions::omega_max, &SweepOptions::omega_n, &SweepOptions::omega_spacing, &SweepOptions::omega_list};
const GridAxisFields<SweepOptions> kEnergyAxis = {
    "energy", &SweepOptions::energy_min, &SweepOptions::energy_max, &SweepOptions::energy_n, &SweepOptions::energy_spacing, &SweepOptions::energy_list};

const auto &kSweepTable = DeclareOptionTable<SweepOptions>("sweep_", "Sweep: grid of forced runs (omega_ext x E*)", [](OptionTable<SweepOptions> &t) {
  GridAxisRows(t, kOmegaAxis);
  GridAxisRows(t, kEnergyAxis);
  t.Bool("resume", &SweepOptions::resume, "Continue the sweep stored in <output>.partial.h5 (or -output): compute only the points not done",
         OptionClass::Bookkeeping)
      .Bool("kcorr", &SweepOptions::kcorr, "Score every run with the 0-1 test for chaos (-kcorr_* options)")
      .Int("group_size", &SweepOptions::group_size, Closed(1, 1000000),
           "Ranks per point: each point's lattice distributed over a group of this many consecutive ranks (PetscSubcomm), the groups drawing points "
           "from one queue (long lattices); it must divide the number of ranks",
           OptionClass::Bookkeeping)
      .Bool("lyapunov", &SweepOptions::lyapunov,
            "Give every point the maximal finite-time Lyapunov exponent of its free motion over [t_off, t_final] (Benettin's method on the tangent flow, "
            "about the run's cost once more) and a regime: regular, chaotic or unpredictable")
      .Real("lyapunov_renorm", &SweepOptions::lyapunov_renorm, LeftOpen(0, 1e6), "Time between the renormalisations of the tangent vector (-sweep_lyapunov)")
      .Real("lyapunov_efolds", &SweepOptions::lyapunov_efolds, LeftOpen(0, 1e6),
            "A point is chaotic when lyapunov x (t_final - t_off) reaches this many e-folds (regular motion grows polynomially: a few ln(window))")
      .Real("checkpoint", &SweepOptions::checkpoint, LeftOpen(0, 1e7), "Rewrite <output>.partial.h5 with the points done so far every this many wall seconds",
            OptionClass::Bookkeeping)
      .Real("progress", &SweepOptions::progress, Closed(0, 1e7), "Report progress every this many wall seconds (0: never)", OptionClass::Bookkeeping)
      .String("shard", &SweepOptions::shard_text,
              "Compute share i of n of the grid (i/n, 0 <= i < n), split by a cost model; -study merge joins the n shard files "
              "(docs/studies/sweep.md, shards and merge)",
              OptionClass::Bookkeeping)
      .Default("the whole grid")
      .String("refine_from", &SweepOptions::refine_from,
              "Compute one adaptive refinement level: read this complete sweep file (a grid, a merged shard set or a previous level) and compute the "
              "edge midpoints and centres of its (omega, log E*) quadtree leaves whose corners' scores differ by more than the -sweep_refine_* "
              "thresholds; the output holds every point under /sweep/refined (docs/studies/sweep.md, adaptive refinement)",
              OptionClass::Bookkeeping)
      .Default("no refinement")
      .Real("refine_mcr", &SweepOptions::refine_mcr, LeftOpen(0, 1e6),
            "Refine a cell whose corners' MCRs differ by more than this (absolute) and by more than their twins' mcr_spread (the noise floor)",
            OptionClass::Bookkeeping)
      .Real("refine_kcorr", &SweepOptions::refine_kcorr, LeftOpen(0, 1e6),
            "Refine a cell whose corners' 0-1 test K differ by more than this (with -sweep_kcorr)", OptionClass::Bookkeeping)
      .Real("refine_ratio", &SweepOptions::refine_ratio, LeftOpen(0, 1e6), "Refine a cell whose corners' ln(nl_ratio) differ by more than this (relative)",
            OptionClass::Bookkeeping)
      .Int("refine_max_points", &SweepOptions::refine_max_points, Closed(0, PETSC_MAX_INT),
           "At most this many new points: the cells with the largest differences (relative to their thresholds) first (0: no cap)", OptionClass::Bookkeeping);
});

const auto &kZeroOneTable = DeclareOptionTable<SweepOptions>("kcorr_", "0-1 test for chaos (with -sweep_kcorr)", [](OptionTable<SweepOptions> &t) {
  t.Int("nc", &SweepOptions::kcorr_nc, Closed(1, 10000), "Number of random frequencies c in (pi/5, 4 pi/5); K is the median over them")
      .Int("seed", &SweepOptions::kcorr_seed, Closed(PETSC_MIN_INT, PETSC_MAX_INT), "Seed of the c draw (the same c for every run)")
      .Real("sample_dt", &SweepOptions::kcorr_sample_dt, Closed(0, 1e6),
            "Sampling interval of u after t_off (0: pi / (2 sqrt(k_hat)), a quarter of the insulated period)")
      .Default("pi / (2 sqrt(k_hat))")
      .Real("rms_fraction", &SweepOptions::kcorr_rms_fraction, Closed(0, 1),
            "Test only sites whose RMS after t_off is at least this fraction of the largest (docs/model.md, the 0-1 test)")
      .Real("record", &SweepOptions::kcorr_record, LeftOpen(0, 1e6),
            "Length of the free motion after t_off that the test analyses; the run continues past -sim_t_final when needed")
      .Int("lags", &SweepOptions::kcorr_lags, Closed(0, 100000), "Lags m at which D(m) is evaluated, evenly spread over 1..n/10 (0: all)")
      .Int("site_stride", &SweepOptions::kcorr_site_stride, Closed(1, PETSC_MAX_INT),
           "Test every this many sites (1: all; the score is the max over tested sites)");
});

PetscErrorCode SweepOptionsFromOptions(MPI_Comm comm, SweepOptions *o)
{
  std::vector<PetscBool> set;
  PetscFunctionBeginUser;
  PetscCall(kSweepTable.Read(comm, o, &set));
  PetscCall(GridAxisFromTable(comm, "sweep_", kSweepTable, set, *o, kOmegaAxis, &o->omega));
  PetscCall(GridAxisFromTable(comm, "sweep_", kSweepTable, set, *o, kEnergyAxis, &o->energy));
  PetscCall(ParseSweepShard(comm, o->shard_text, o->omega.size() * o->energy.size(), &o->shard));
  PetscCall(McrAccuracyOptionsFromOptions(comm, &o->mcr));
  PetscCheck(o->refine_from.empty() || !o->shard.On(), comm, PETSC_ERR_USER,
             "-sweep_refine_from %s with -sweep_shard %s: a refinement level runs as one job (on any number of ranks), not as shards", o->refine_from.c_str(),
             o->shard_text.c_str());
  PetscCall(kZeroOneTable.Read(comm, o));
  // the record is kept as samples per tested site: at most 2e6 of them
  PetscCheck(o->kcorr_sample_dt == 0 || o->kcorr_record / o->kcorr_sample_dt <= 2e6, comm, PETSC_ERR_USER,
             "-kcorr_record / -kcorr_sample_dt must be at most 2e6 samples, got %g / %g", (double)o->kcorr_record, (double)o->kcorr_sample_dt);
  PetscCheck(o->kcorr_lags == 0 || o->kcorr_lags >= 3, comm, PETSC_ERR_USER, "-kcorr_lags must be 0 (all) or lie in [3, 100000], got %" PetscInt_FMT,
             o->kcorr_lags);
  PetscCall(RejectGivenOptions(comm, {"-force_omega", "-force_energy"}, "the sweep axes (-sweep_omega_*, -sweep_energy_*) per point"));
  PetscFunctionReturn(0);
}

// -sweep_shard is bookkeeping, which the overwrite rule (io/run_options.hpp)
// does not compare: a fresh run refuses, unless -output_overwrite, to replace
// another shard's output of the same sweep, or a whole sweep by a shard.
PetscErrorCode CheckShardOverwrite(MPI_Comm comm, const std::string &path, const SweepShard &s)
{
  PetscMPIInt rank;
  PetscBool overwrite = PETSC_FALSE;
  char msg[1024] = "";
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCall(PetscOptionsGetBool(NULL, NULL, "-output_overwrite", &overwrite, NULL));
  std::string study;
  long index = 0, count = 0;
  if (!rank && !overwrite && ReadRootAttribute(path, "study", &study) && study == "sweep") {
    ReadRootAttribute(path, "/sweep/shard_index", &index);
    ReadRootAttribute(path, "/sweep/shard_count", &count);
    auto name = [](long i, long n) { return n ? "shard " + std::to_string(i) + "/" + std::to_string(n) : std::string("the whole grid"); };
    if (count != s.count || (count && index != s.index))
      PetscCall(PetscSNPrintf(msg, sizeof msg, "-output %s holds %s of this sweep (this run: %s); choose another -output or give -output_overwrite",
                              path.c_str(), name(index, count).c_str(), name(s.index, s.count).c_str()));
  }
  PetscCallMPI(MPI_Bcast(msg, sizeof msg, MPI_CHAR, 0, comm));
  PetscCheck(!msg[0], comm, PETSC_ERR_FILE_WRITE, "%s", msg);
  PetscFunctionReturn(0);
}

// complete: false for the file a sweep keeps while it runs (and leaves when
// interrupted) at <path>.partial.h5, true once every point is done: at path.
// A shard (-sweep_shard) writes its points only: each per-point dataset 1-D
// over them, in the order of /sweep/shard_points (their grid indices).
PetscErrorCode WriteSweep(const std::string &path, const SweepGrid &g, const SweepOptions &so, PetscInt computed, PetscReal wall, bool complete)
{
  OutputFile out;
  // the points of the per-point datasets: this run's (a shard's: 1-D), or, for a refinement level, the base grid's (its points on the fine lattice)
  std::vector<size_t> at;
  if (g.scattered) {
    const size_t s = (size_t)1 << so.lattice.depth;
    for (size_t e = 0; e < so.base_energy.size(); e++)
      for (size_t o = 0; o < so.base_omega.size(); o++) at.push_back(so.lattice.Index(s * e, s * o));
  } else
    for (size_t k = 0; k < g.Count(); k++) at.push_back(g.At(k));
  const size_t n = at.size();
  std::vector<PetscReal> v(n);
  std::vector<PetscInt> iv(n);
  const PetscInt no = g.shard.On() ? 1 : (PetscInt)(g.scattered ? so.base_omega.size() : g.omega.size()); // the per-point datasets' columns
  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(Log().output, 0, 0, 0, 0));
  PetscCall(out.Open(PETSC_COMM_SELF, complete ? path : PartialPath(path)));
  PetscViewer w = out.Viewer();
  const char *grp = "/sweep";
  PetscCall(WriteArray(w, grp, "omega", g.scattered ? so.base_omega : g.omega));
  PetscCall(WriteArray(w, grp, "energy", g.scattered ? so.base_energy : g.energy));
  auto doubles = [&](const char *name, PetscReal SweepPoint::*field) -> PetscErrorCode {
    PetscFunctionBeginUser;
    for (size_t i = 0; i < n; i++) v[i] = g.pts[at[i]].*field;
    PetscCall(WriteArray(w, grp, name, v, no));
    PetscFunctionReturn(0);
  };
  auto ints = [&](const char *name, PetscInt SweepPoint::*field) -> PetscErrorCode {
    PetscFunctionBeginUser;
    for (size_t i = 0; i < n; i++) iv[i] = g.pts[at[i]].*field;
    PetscCall(WriteIntArray(w, grp, name, iv, no));
    PetscFunctionReturn(0);
  };
  for (const auto &f : SweepRealFields()) PetscCall(doubles(f.name, f.field));
  for (const auto &f : SweepIntFields()) PetscCall(ints(f.name, f.field));
  for (size_t i = 0; i < n; i++) iv[i] = g.done[at[i]];
  PetscCall(WriteIntArray(w, grp, "done", iv, no));
  if (g.scattered) {
    PetscCall(WriteRefinedSamples(w, g, so.lattice));
    const char *rg = "/sweep/refined";
    PetscCall(WriteAttr(w, rg, "points_new", (PetscInt)so.selection.points.size()));
    PetscCall(WriteAttr(w, rg, "leaves", (PetscInt)so.selection.leaves));
    PetscCall(WriteAttr(w, rg, "cells_over", (PetscInt)so.selection.over));
    PetscCall(WriteAttr(w, rg, "cells_refined", (PetscInt)so.selection.refined));
    PetscCall(WriteAttr(w, rg, "refine_mcr", so.refine_mcr));
    PetscCall(WriteAttr(w, rg, "refine_kcorr", so.refine_kcorr));
    PetscCall(WriteAttr(w, rg, "refine_ratio", so.refine_ratio));
    PetscCall(WriteAttr(w, rg, "refine_max_points", so.refine_max_points));
    PetscCall(WriteAttr(w, rg, "refine_from", so.refine_from.c_str()));
  }
  if (g.shard.On()) {
    PetscCall(WriteIntArray(w, grp, "shard_points", std::vector<PetscInt>(g.points.begin(), g.points.end())));
    PetscCall(WriteAttr(w, grp, "shard_index", g.shard.index));
    PetscCall(WriteAttr(w, grp, "shard_count", g.shard.count));
  }
  PetscCall(WriteBandEdges(w, grp, so.bands));
  PetscCall(WriteArray(w, grp, "force_eta", so.eta));
  if (!so.insulated.empty()) PetscCall(WriteArray(w, grp, "insulated_mode", so.insulated));
  if (so.exponential) {
    PetscCall(WriteAttr(w, grp, "force_exp_a", so.exp_a));
    PetscCall(WriteAttr(w, grp, "force_exp_b", so.exp_b));
  }
  PetscCall(WriteAttr(w, grp, "points_done", g.Done()));
  PetscCall(WriteAttr(w, grp, "points_computed", computed)); // by this invocation (a resume computes only the missing ones)
  PetscCall(WriteAttr(w, grp, "kcorr_computed", (PetscInt)so.kcorr));
  PetscCall(WriteAttr(w, grp, "mcr_tol", so.mcr.tol)); // 0: the scene's own integration, one run per point
  PetscCall(WriteAttr(w, grp, "mcr_dt_phase", so.mcr.dt_phase));
  PetscCall(WriteAttr(w, grp, "mcr_dt_energy", so.mcr.dt_energy));
  PetscCall(WriteAttr(w, grp, "kcorr_nc", so.kcorr_nc));
  PetscCall(WriteAttr(w, grp, "kcorr_sample_dt", so.kcorr_sample_dt));
  PetscCall(WriteAttr(w, grp, "kcorr_rms_fraction", so.kcorr_rms_fraction));
  PetscCall(WriteAttr(w, grp, "kcorr_record", so.kcorr_record));
  PetscCall(WriteAttr(w, grp, "kcorr_lags", so.kcorr_lags));
  PetscCall(WriteAttr(w, grp, "lyapunov_computed", (PetscInt)so.lyapunov));
  PetscCall(WriteAttr(w, grp, "lyapunov_renorm", so.lyapunov_renorm));
  PetscCall(WriteAttr(w, grp, "lyapunov_efolds", so.lyapunov_efolds));
  PetscCall(WriteAttr(
      w, grp, "amplitude_rule",
      "linear Gaussian-burst energy = -force_amplitude_safety * E*; a run whose burst ends before E* is repeated with a larger S (x "
      "(1.2 E*/E_peak)^(1/p), p the log-log slope of the misses) up to -force_amplitude_retries times (docs/model.md, the amplitude rule); reached = 0 marks points that never reached E*"));
  PetscCall(out.Commit("sweep", wall, complete));
  PetscCall(PetscLogEventEnd(Log().output, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

// -sweep_lyapunov: the FTLE of the free motion from the cut-off state over
// the MCR window, in the run's own (mean) step, and the point's regime
// (codes::kRegime): unpredictable where the twins said so, else chaotic where
// the tangent vector grew by -sweep_lyapunov_efolds e-folds, else regular.
PetscErrorCode PointLyapunov(const Lattice &lat, const SimulationOptions &ps, const SweepOptions &so, const SimulationResult &r, SweepPoint *pt)
{
  LyapunovResult ly;
  PetscFunctionBeginUser;
  EffectList free_fx(lat);
  PetscCall(BuildEffects(lat, NULL, &free_fx));
  const PetscReal window = ps.t_final - r.t_off, dt = (ps.t_final - ps.t_start) / std::max<PetscInt>(1, r.steps);
  PetscCall(FiniteTimeLyapunov(free_fx, r.z_off, window, so.lyapunov_renorm, dt, &ly));
  pt->lyapunov = ly.exponent, pt->lyapunov_half = ly.half;
  pt->regime = pt->predictable == 0 ? 2 : ly.exponent * window >= so.lyapunov_efolds ? 1 : 0;
  PetscFunctionReturn(0);
}

// One grid point: the simulate study's run, then (with -sweep_kcorr) the 0-1 test.
PetscErrorCode ComputePoint(const Lattice &lat, const LinearModes &modes, const ToneBurstOptions &fo, const SimulationOptions &sim, const SweepOptions &so,
                            const ZeroOneTest &zero_one, PetscReal omega, PetscReal energy, SweepPoint *pt)
{
  PetscFunctionBeginUser;
  ToneBurstOptions pf = fo;
  pf.omega = omega;
  pf.energy = energy;
  ToneBurst burst;
  const SimulationOptions first = McrFirstRunOptions(so.mcr, sim, omega, energy, so.bands.optical_top); // -sweep_mcr_dt_phase: the step rule
  SimulationOptions ps = first;
  AfterCutoffSamples sink(lat.N());
  if (so.kcorr) ps.sample_dt = so.kcorr_sample_dt;
  ps.keep_cutoff_state = so.lyapunov;
  SimulationResult r;
  PetscInt rescalings;
  PetscLogDouble p0, p1;
  PetscCall(PetscTime(&p0));
  PetscCall(RunForced(lat, &modes, pf, ps, so.kcorr ? &sink : NULL, &burst, &r, &rescalings));
  pt->rhs = r.rhs_all_attempts;
  if (so.kcorr && r.reached && r.t_off + so.kcorr_record > ps.t_final) {
    // The test needs a longer free record than the run has after t_off: the
    // linear lattice's ~N modes read as chaos in records much shorter than
    // 2 pi / (their spacing) (docs/model.md "The 0-1 test for chaos"). Continue the free motion.
    SimulationOptions cont = ps;
    SimulationResult rc;
    cont.t_start = ps.t_final;
    cont.t_final = r.t_off + so.kcorr_record;
    sink.Continue(r.t_off);
    EffectList free_fx(lat); // the free motion after the cut-off
    PetscCall(BuildEffects(lat, NULL, &free_fx));
    PetscCall(Simulate(free_fx, cont, r.z_final, &sink, &rc));
    pt->rhs += rc.counters.rhs;
  }
  if (so.kcorr) {
    PetscCall(PetscLogEventBegin(Log().diagnostics, 0, 0, 0, 0));
    PetscReal K = std::numeric_limits<PetscReal>::quiet_NaN(); // too short a record after the cut-off
    const PetscInt ns = sink.Samples(), N = lat.N();
    if (ns >= 100) {
      // Sites too quiet to matter carry only the radiated bulk spectrum,
      // which the test reads as chaos even in linear runs (docs/model.md).
      std::vector<PetscReal> ms(N, 0.0);
      for (PetscInt j = 0; j < ns; j++)
        for (PetscInt s = 0; s < N; s++) ms[s] += sink.Data()[j * N + s] * sink.Data()[j * N + s];
      const PetscReal floor = so.kcorr_rms_fraction * so.kcorr_rms_fraction * *std::max_element(ms.begin(), ms.end());
      std::vector<PetscInt> sites;
      for (PetscInt s = 0; s < N; s += so.kcorr_site_stride)
        if (ms[s] >= floor && ms[s] > 0) sites.push_back(s);
      PetscLogEvent ev; // the test itself, inside Diagnostics
      PetscCall(NamedLogEvent("ZeroOneTest", &ev));
      PetscCall(PetscLogEventBegin(ev, 0, 0, 0, 0));
      K = zero_one.ScoreMax(sink.Data(), ns, N, sites); // -1 without sites
      PetscCall(PetscLogEventEnd(ev, 0, 0, 0, 0));
    }
    pt->kcorr = K;
    PetscCall(PetscLogEventEnd(Log().diagnostics, 0, 0, 0, 0));
  } else {
    pt->kcorr = std::numeric_limits<PetscReal>::quiet_NaN();
  }
  pt->mcr = r.mcr, pt->t_off = r.t_off, pt->nl_ratio = r.nl_ratio, pt->amplitude = burst.Amplitude(), pt->energy_final = r.energy_final;
  pt->reached = r.reached, pt->rescalings = rescalings, pt->steps = r.steps;
  if (so.mcr.tol > 0) { // the first run's options, S as the amplitude rule left it
    PetscReal scene_dt;
    PetscCall(SimulationGivenStep(&scene_dt));
    PetscCall(RefineMcr(lat, burst, first, McrFirstStep(first, scene_dt, energy), so.mcr, r, pt));
  }
  if (so.lyapunov && r.reached && r.z_off) PetscCall(PointLyapunov(lat, ps, so, r, pt));
  PetscCall(PetscTime(&p1));
  pt->seconds = p1 - p0;
  PetscFunctionReturn(0);
}

// Rank 0 writes the file itself: it merges every rank's journal into it
// (checkpoints while the sweep runs, the final file at the end).
class SweepStudy : public Study {
public:
  ~SweepStudy() override { PetscSubcommDestroy(&subcomm_); } // the lattice (sc_) on its child is destroyed first: members in reverse order

protected:
  PetscErrorCode ReadOptions() override
  {
    PetscFunctionBeginUser;
    PetscCallMPI(MPI_Comm_rank(comm_, &rank_));
    PetscCallMPI(MPI_Comm_size(comm_, &size_));
    PetscCall(RejectGivenOptions(comm_, {"-sim_progress", "-sim_sample_dt"}, "-study sweep (progress: -sweep_progress; no samples are stored)"));
    PetscCall(LatticeModelFromOptions(comm_, &sc_.lp));
    PetscCall(SweepOptionsFromOptions(comm_, &so_));
    PetscCall(sc_.ReadOptions(comm_, declaring_, false, ForcedScene::Modes::Always, "a sweep needs a forcing"));
    if (!declaring_) PetscCall(CheckMcrAccuracyIntegrator(comm_, so_.mcr));
    PetscCall(sc_.ReadModeOptions(comm_, declaring_));
    if (!declaring_) PetscCall(MakeGroups());
    PetscFunctionReturn(0);
  }
  // -sweep_group_size g: the ranks in groups of g consecutive ones (PetscSubcomm), each group one point at a time
  PetscErrorCode MakeGroups()
  {
    PetscFunctionBeginUser;
    const PetscInt g = so_.group_size;
    PetscCheck(size_ % g == 0, comm_, PETSC_ERR_USER, "-sweep_group_size %" PetscInt_FMT " must divide the number of ranks (%d)", g, size_);
    PetscCheck(g == 1 || !so_.kcorr, comm_, PETSC_ERR_USER,
               "-sweep_kcorr needs -sweep_group_size 1 (the 0-1 test reads every site's record on one rank); got -sweep_group_size %" PetscInt_FMT, g);
    if (g > 1) {
      PetscCall(PetscSubcommCreate(comm_, &subcomm_));
      PetscCall(PetscSubcommSetNumber(subcomm_, (PetscInt)(size_ / g)));
      PetscCall(PetscSubcommSetType(subcomm_, PETSC_SUBCOMM_CONTIGUOUS));
      group_ = PetscSubcommChild(subcomm_);
    }
    PetscCallMPI(MPI_Comm_rank(group_, &grank_));
    PetscFunctionReturn(0);
  }
  PetscErrorCode DeclareSolvers(MPI_Comm comm) override { return ForcedScene::DeclareSolvers(comm); }
  PetscErrorCode CheckResources() override { return sc_.CheckResources(group_); } // every group its own lattice
  // -sweep_resume continues -output's partial output, or -output itself (no -output_overwrite needed).
  PetscErrorCode OutputPath(std::string *path) override
  {
    int partial = 0;
    PetscFunctionBeginUser;
    PetscCall(OutputPathFromOptions(
        comm_, name_, path, [&](const std::string &) { return (bool)so_.resume; }, "-sweep_resume"));
    PetscCheck(so_.refine_from.empty() || !SameFile(so_.refine_from, *path), comm_, PETSC_ERR_USER,
               "-sweep_refine_from %s is -output: a refinement level writes a new file", so_.refine_from.c_str());
    if (!so_.resume) PetscCall(CheckShardOverwrite(comm_, *path, so_.shard));
    if (!so_.resume) PetscFunctionReturn(0);
    if (!rank_) partial = !access(PartialPath(*path).c_str(), F_OK);
    PetscCallMPI(MPI_Bcast(&partial, 1, MPI_INT, 0, comm_));
    resume_from_ = partial ? PartialPath(*path) : *path;
    PetscCall(CheckResumeOptions(comm_, resume_from_, name_, "-sweep_resume")); // the same physics and numerics, or one line naming the first difference
    PetscFunctionReturn(0);
  }
  bool WritesOwnFile() const override { return true; }
  PetscErrorCode Build() override
  {
    PetscFunctionBeginUser;
    // Every group (a rank, or -sweep_group_size ranks) integrates whole runs on its own copy of the lattice.
    // The forcing at the default omega and E*: its profile does not depend on them.
    PetscCall(sc_.Build(group_, ForcedScene::Upto::Burst));
    if (so_.lyapunov) { // the exponent follows the tangent flow of the free, conservative lattice (every group alike: one line)
      EffectList free_fx(sc_.lat);
      PetscErrorCode code = 0;
      char msg[512] = "";
      PetscCall(BuildEffects(sc_.lat, NULL, &free_fx));
      PetscCall(CaptureError([&]() { return free_fx.RequireConservative("-sweep_lyapunov (the tangent flow of the free lattice after the cut-off)"); }, &code,
                             msg, sizeof msg));
      PetscCall(FailTogether(comm_, code, msg));
    }
    // The lattice's frequencies (linear 1.0..2.24 at the defaults, higher when
    // hardened) then map to c = omega dt inside the test's range (pi/5, 4 pi/5).
    if (so_.kcorr_sample_dt == 0) so_.kcorr_sample_dt = PETSC_PI / (2 * std::sqrt(sc_.lp.KHat()));
    so_.bands = InfiniteBandEdges(sc_.lp);
    PetscCall(sc_.burst.Profile(sc_.lat, &so_.eta));
    so_.exponential = sc_.fo.profile == ForceProfile::Exponential;
    so_.exp_a = sc_.burst.ExponentialA(), so_.exp_b = sc_.burst.ExponentialB();
    if (sc_.modes.Insulated()) PetscCall(GatherVec(sc_.modes.Insulated(), true, &so_.insulated));
    zero_one_ = std::make_unique<const ZeroOneTest>(so_.kcorr_nc, (unsigned long)so_.kcorr_seed, so_.kcorr_lags);
    // -sweep_shard: this run's points (every rank computes the same split)
    double share = 1;
    grid_.shard = so_.shard;
    if (so_.shard.On()) grid_.points = SweepShardPoints(so_.energy, so_.omega.size(), SweepCostEnergy(sc_.lp, sc_.sim.dt_quartic_energy), so_.shard, &share);
    if (so_.refine_from.empty()) PetscCall(StartGrid());
    else PetscCall(StartRefinedGrid());

    // The missing points, most expensive (highest E*, then highest omega) first.
    const size_t no = so_.omega.size(), ne = so_.energy.size();
    for (size_t k = 0; k < grid_.Count(); k++)
      if (!grid_.done[grid_.At(k)]) todo_.push_back(grid_.At(k));
    std::stable_sort(todo_.begin(), todo_.end(), [&](size_t a, size_t b) { return a / no != b / no ? a / no > b / no : a % no > b % no; });
    if (grid_.scattered) // a refinement level: its points on the fine lattice
      PetscCall(PetscPrintf(
          comm_, "nltopo sweep: %zu points on a lattice of %zu omega x %zu E*, %zu to compute on %d rank(s)%s, N = %" PetscInt_FMT ", t_final = %g\n",
          grid_.Count(), no, ne, todo_.size(), size_, so_.kcorr ? ", with the 0-1 test" : "", sc_.lat.N(), (double)sc_.sim.t_final));
    else
      PetscCall(PetscPrintf(comm_, "nltopo sweep: %zu omega x %zu E* = %zu points, %zu to compute on %d rank(s)%s%s, N = %" PetscInt_FMT ", t_final = %g\n", no,
                            ne, grid_.Size(), todo_.size(), size_, so_.group_size > 1 ? (" in groups of " + std::to_string(so_.group_size)).c_str() : "",
                            so_.kcorr ? ", with the 0-1 test" : "", sc_.lat.N(), (double)sc_.sim.t_final));
    if (so_.shard.On())
      PetscCall(PetscPrintf(
          comm_, "  shard %" PetscInt_FMT " of %" PetscInt_FMT ": %zu of the %zu points, %.1f %% of the modelled cost (-study merge joins the shards)\n",
          so_.shard.index, so_.shard.count, grid_.Count(), grid_.Size(), 100 * share));
    {
      PetscErrorCode jerr = 0;
      char jmsg[1024];
      PetscCall(CaptureError([&]() { return journal_.Open(path_, rank_); }, &jerr, jmsg, sizeof(jmsg)));
      PetscCall(FailTogether(comm_, jerr, jmsg)); // one rank's journal: every rank stops
    }
    PetscCall(queue_.Create(comm_, (PetscInt)todo_.size()));
    PetscFunctionReturn(0);
  }
  PetscErrorCode Solve() override
  {
    PetscLogDouble t_last_ck, t_last_pr, now;
    PetscFunctionBeginUser;
    sc_.sim.progress = 0;
    sc_.sim.sample_dt = 0;
    // One updating line on a terminal; periodic lines otherwise. Under mpiexec
    // (OpenMPI gives ranks a pty even when the output goes to a file) lines.
    tty_ = !rank_ && isatty(fileno(stdout)) && !getenv("OMPI_COMM_WORLD_SIZE") && !getenv("PMI_RANK");
    const size_t no = so_.omega.size();
    PetscInt item;
    t_last_ck = t_last_pr = t_start_;
    PetscCall(PetscTime(&t_loop_));
    // A rank stops drawing points at a stop signal (the point it is integrating
    // ends at its next time step and is dropped: a resume recomputes it) or when
    // its journal or rank 0's checkpoint cannot be written; WorkQueue::Stop makes
    // the others stop after their current point. Then all ranks meet below.
    PetscErrorCode failed = 0;
    char fail_msg[1024] = "";
    const bool grouped = so_.group_size > 1, leader = grank_ == 0;
    for (;;) {
      int stop = StopSignalLocal();
      if (grouped) PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &stop, 1, MPI_INT, MPI_MAX, group_)); // a group stops as one
      if (stop) {
        if (leader) PetscCall(queue_.Stop());
        break;
      }
      if (leader) PetscCallAbort(PETSC_COMM_WORLD, queue_.Next(&item)); // MPI itself failing: nothing to save
      if (grouped) PetscCallMPI(MPI_Bcast(&item, 1, MPIU_INT, 0, group_));
      if (item < 0) break;
      const size_t idx = todo_[item];
      SweepPoint pt;
      PetscErrorCode ierr = 0;
      char msg[1024] = "";
      PetscCall(
          CaptureError([&]() { return ComputePoint(sc_.lat, sc_.modes, sc_.fo, sc_.sim, so_, *zero_one_, so_.omega[idx % no], so_.energy[idx / no], &pt); },
                       &ierr, msg, sizeof(msg)));
      if (grouped) { // the group's members agree on the point's outcome (the leader's message)
        PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &ierr, 1, MPI_INT, MPI_MAX, group_));
        PetscCallMPI(MPI_Bcast(msg, sizeof msg, MPI_CHAR, 0, group_));
      }
      if (IsInterrupt(ierr)) {
        if (leader) PetscCall(queue_.Stop());
        break;
      }
      if (ierr && leader) { // one failed run (e.g. a diverging integration) is flagged; the sweep goes on
        std::fprintf(stderr, "nltopo: warning: sweep point E* = %g, omega = %g failed (flagged failed = 1): %s\n", (double)so_.energy[idx / no],
                     (double)so_.omega[idx % no], msg);
        const PetscReal nan = std::numeric_limits<PetscReal>::quiet_NaN();
        pt = SweepPoint();
        pt.mcr = pt.t_off = pt.kcorr = pt.nl_ratio = pt.amplitude = pt.energy_final = nan;
        pt.failed = 1;
      }
      if (leader) PetscCall(CaptureError([&]() { return journal_.Append(idx, pt); }, &failed, fail_msg, sizeof(fail_msg)));
      if (grouped) PetscCallMPI(MPI_Bcast(&failed, 1, MPI_INT, 0, group_));
      if (failed) { // a rank that cannot journal stops every rank
        if (leader) PetscCall(queue_.Stop());
        break;
      }
      computed_ += leader;
      if (!rank_) { // rank 0 merges what every rank journaled: checkpoint file and progress
        PetscCall(PetscTime(&now));
        const bool ck = now - t_last_ck >= so_.checkpoint, pr = so_.progress > 0 && (tty_ || now - t_last_pr >= so_.progress);
        if (ck || pr) {
          PetscCall(CaptureError(
              [&]() -> PetscErrorCode {
                PetscInt lines;
                PetscFunctionBeginUser;
                PetscCall(grid_.MergeJournals(path_, &lines));
                if (ck) PetscCall(WriteSweep(path_, grid_, so_, computed_, now - t_start_, false));
                PetscFunctionReturn(0);
              },
              &failed, fail_msg, sizeof(fail_msg)));
          if (failed) PetscCall(queue_.Stop()); // rank 0's group stops below, the others after their point
          if (ck) t_last_ck = now;
          if (pr && (tty_ ? now - t_last_pr >= 0.5 : true)) {
            PetscCall(PrintProgress(now));
            t_last_pr = now;
          }
        }
      }
      if (grouped) PetscCallMPI(MPI_Bcast(&failed, 1, MPI_INT, 0, group_)); // rank 0's checkpoint failed: its group stops with it
      if (failed) break;
    }
    journal_.Close();
    PetscCallMPI(MPI_Barrier(comm_)); // every journal is complete
    // A journal or checkpoint failure: every rank fails with its message; the
    // last checkpoint and the journals stay for -sweep_resume.
    PetscCall(FailTogether(comm_, failed, fail_msg));
    PetscFunctionReturn(0);
  }
  PetscErrorCode Write(PetscViewer) override
  {
    PetscLogDouble now = 0;
    PetscErrorCode failed = 0;
    char fail_msg[1024] = "";
    PetscFunctionBeginUser;
    PetscCall(AuditOptionsBeforeCommit(comm_)); // collective; rank 0 alone commits the file below
    PetscInt total_computed = 0;
    int sig;
    PetscCall(InterruptRequested(comm_, &sig));
    PetscCallMPI(MPI_Reduce(&computed_, &total_computed, 1, MPIU_INT, MPI_SUM, 0, comm_));
    PetscCall(CostReduceWorld()); // rank 0 writes the card of every rank's integrations
    PetscInt done_now = 0;
    if (!rank_) {
      // The journals hold every point done; merged into -output they are no
      // longer needed, also when the sweep was interrupted (the file is then
      // complete = 0 and -sweep_resume continues from it alone).
      PetscCall(CaptureError(
          [&]() -> PetscErrorCode {
            PetscInt lines;
            PetscFunctionBeginUser;
            PetscCall(grid_.MergeJournals(path_, &lines));
            if (so_.mcr.tol > 0) {
              PetscReal worst = 0;
              for (size_t k = 0; k < grid_.Count(); k++)
                if (const size_t i = grid_.At(k); grid_.done[i] && grid_.pts[i].predictable == 1 && grid_.pts[i].mcr_error <= so_.mcr.tol)
                  worst = std::max(worst, grid_.pts[i].mcr_error);
              CostSetErrorEstimate(worst, "the largest mcr_error of the points converged to -sweep_mcr_tol (relative)");
            }
            PetscCall(PetscTime(&now));
            done_now = grid_.Done();
            PetscCall(WriteSweep(path_, grid_, so_, total_computed, now - t_start_, done_now == (PetscInt)grid_.Count()));
            PetscFunctionReturn(0);
          },
          &failed, fail_msg, sizeof(fail_msg)));
      if (!failed) {
        for (const std::string &f : JournalFiles(path_)) std::remove(f.c_str());
        PetscCall(PrintSummary(total_computed, now));
      }
    }
    PetscCall(FailTogether(comm_, failed, fail_msg));
    PetscCallMPI(MPI_Bcast(&done_now, 1, MPIU_INT, 0, comm_));
    PetscCheck(!sig || done_now == (PetscInt)grid_.Count(), comm_, PETSC_ERR_SIG,
               "interrupted by %s between sweep points (%" PetscInt_FMT " of %zu done, %" PetscInt_FMT
               " by this run); partial output %s (complete = 0); -sweep_resume continues it",
               SignalName(sig), done_now, grid_.Count(), total_computed, PartialPath(path_).c_str());
    PetscFunctionReturn(0);
  }

private:
  // Rank 0 builds the starting grid (fresh, or the stored one plus journals)
  // and writes it: the file exists (and is valid) from the start.
  PetscErrorCode StartGrid()
  {
    int err = 0;
    char msg[512] = "";
    PetscFunctionBeginUser;
    grid_.Reset(so_.omega, so_.energy);
    if (!rank_) {
      PetscErrorCode ierr = 0;
      PetscInt merged = 0;
      PetscCall(CaptureError(
          [&]() -> PetscErrorCode {
            PetscFunctionBeginUser;
            if (so_.resume) {
              PetscCheck(!access(resume_from_.c_str(), F_OK), PETSC_COMM_SELF, PETSC_ERR_FILE_OPEN, "-sweep_resume: no sweep file %s or %s to resume",
                         PartialPath(path_).c_str(), path_.c_str());
              PetscCall(grid_.Load(resume_from_));
              PetscCall(grid_.MergeJournals(path_, &merged));
            }
            PetscCall(WriteSweep(path_, grid_, so_, 0, 0, false)); // the file exists (and is valid) from the start
            PetscFunctionReturn(0);
          },
          &ierr, msg, sizeof(msg)));
      if (ierr) err = 1;
      else {
        for (const std::string &f : JournalFiles(path_)) std::remove(f.c_str()); // merged (resume) or stale (fresh start)
        if (so_.resume)
          PetscCall(PetscPrintf(PETSC_COMM_SELF, "nltopo sweep: resuming %s: %" PetscInt_FMT " of %zu points done (%" PetscInt_FMT " from journals)\n",
                                resume_from_.c_str(), grid_.Done(), grid_.Count(), merged));
      }
    }
    PetscCallMPI(MPI_Bcast(&err, 1, MPI_INT, 0, comm_));
    PetscCallMPI(MPI_Bcast(msg, sizeof(msg), MPI_CHAR, 0, comm_));
    PetscCheck(!err, comm_, PETSC_ERR_USER, "%s", msg);
    PetscCallMPI(MPI_Bcast(grid_.done.data(), (PetscMPIInt)grid_.Size(), MPIU_INT, 0, comm_));
    PetscFunctionReturn(0);
  }
  // -sweep_refine_from: rank 0 loads the previous level, selects the leaves to
  // refine and (-sweep_resume) the points already done, and writes the file;
  // every rank gets the fine lattice, the level's points and their done flags.
  PetscErrorCode StartRefinedGrid()
  {
    int err = 0;
    char msg[1024] = "";
    PetscInt depth = 0, npts = 0;
    PetscFunctionBeginUser;
    so_.base_omega = so_.omega, so_.base_energy = so_.energy;
    const bool log_e = so_.energy_spacing == AxisSpacing::Log;
    if (!rank_) {
      const std::string problem = RefineSourceProblem(so_.refine_from);
      PetscErrorCode ierr = 0;
      PetscInt merged = 0;
      if (!problem.empty()) {
        err = 1;
        PetscCall(PetscStrncpy(msg, problem.c_str(), sizeof msg));
      } else
        PetscCall(CaptureError(
            [&]() -> PetscErrorCode {
              PetscFunctionBeginUser;
              PetscCall(LoadRefineSource(so_.refine_from, so_.base_omega, so_.base_energy, log_e, &grid_, &so_.lattice));
              const SweepRefineOptions ro{so_.refine_from, so_.refine_mcr, so_.refine_kcorr, so_.refine_ratio, so_.refine_max_points};
              so_.selection = SelectRefinement(grid_, so_.lattice, ro, so_.kcorr);
              std::vector<size_t> all(grid_.points.size() + so_.selection.points.size());
              std::merge(grid_.points.begin(), grid_.points.end(), so_.selection.points.begin(), so_.selection.points.end(), all.begin());
              grid_.points = all;
              PetscCall(PetscPrintf(PETSC_COMM_SELF,
                                    "nltopo sweep: refinement depth %" PetscInt_FMT " from %s: %zu points, %zu leaves, %zu over the thresholds, %zu refined "
                                    "(MCR %" PetscInt_FMT ", K %" PetscInt_FMT ", nl_ratio %" PetscInt_FMT ", predictability %" PetscInt_FMT
                                    "): %zu new points\n",
                                    so_.lattice.depth, so_.refine_from.c_str(), all.size() - so_.selection.points.size(), so_.selection.leaves,
                                    so_.selection.over, so_.selection.refined, so_.selection.by_mcr, so_.selection.by_kcorr, so_.selection.by_ratio,
                                    so_.selection.by_predictable, so_.selection.points.size()));
              if (so_.resume) {
                PetscCheck(!access(resume_from_.c_str(), F_OK), PETSC_COMM_SELF, PETSC_ERR_FILE_OPEN, "-sweep_resume: no sweep file %s or %s to resume",
                           PartialPath(path_).c_str(), path_.c_str());
                PetscCall(LoadRefinedPartial(resume_from_, so_.lattice, &grid_));
                PetscCall(grid_.MergeJournals(path_, &merged));
              }
              PetscCall(WriteSweep(path_, grid_, so_, 0, 0, false)); // the file exists (and is valid) from the start
              PetscFunctionReturn(0);
            },
            &ierr, msg, sizeof(msg)));
      if (ierr) err = 1;
      else if (!err)
        for (const std::string &f : JournalFiles(path_)) std::remove(f.c_str()); // merged (resume) or stale (fresh start)
      depth = so_.lattice.depth, npts = (PetscInt)grid_.points.size();
    }
    PetscCallMPI(MPI_Bcast(&err, 1, MPI_INT, 0, comm_));
    PetscCallMPI(MPI_Bcast(msg, sizeof(msg), MPI_CHAR, 0, comm_));
    PetscCheck(!err, comm_, PETSC_ERR_USER, "%s", msg);
    PetscCallMPI(MPI_Bcast(&depth, 1, MPIU_INT, 0, comm_));
    PetscCallMPI(MPI_Bcast(&npts, 1, MPIU_INT, 0, comm_));
    if (rank_) {
      so_.lattice.depth = depth;
      grid_.Reset(RefinedAxis(so_.base_omega, false, depth), RefinedAxis(so_.base_energy, log_e, depth));
      grid_.scattered = true;
      so_.lattice.no = grid_.omega.size(), so_.lattice.ne = grid_.energy.size();
    }
    std::vector<PetscInt> p(npts);
    if (!rank_) std::copy(grid_.points.begin(), grid_.points.end(), p.begin());
    PetscCallMPI(MPI_Bcast(p.data(), (PetscMPIInt)npts, MPIU_INT, 0, comm_));
    grid_.points.assign(p.begin(), p.end());
    PetscCallMPI(MPI_Bcast(grid_.done.data(), (PetscMPIInt)grid_.Size(), MPIU_INT, 0, comm_));
    so_.omega = grid_.omega, so_.energy = grid_.energy; // the points' axes (ComputePoint)
    PetscFunctionReturn(0);
  }
  // Rank 0: points done (from the merged journals), rate and ETA.
  PetscErrorCode PrintProgress(PetscLogDouble now) const
  {
    PetscFunctionBeginUser;
    const PetscInt d = grid_.Done();
    const double rate = (d - (PetscInt)(grid_.Count() - todo_.size())) / (now - t_loop_);
    const double eta = rate > 0 ? (grid_.Count() - d) / rate : 0;
    PetscCall(PetscPrintf(PETSC_COMM_SELF, "%s  [sweep] %" PetscInt_FMT " / %zu points (%.1f %%), %.2f points/s, ETA %.0f s%s", tty_ ? "\r" : "", d,
                          grid_.Count(), 100.0 * d / grid_.Count(), rate, eta, tty_ ? "   " : "\n"));
    if (tty_) fflush(stdout);
    PetscFunctionReturn(0);
  }
  // Rank 0, once the final file is written: what the grid holds, and the "wrote" line.
  PetscErrorCode PrintSummary(PetscInt total_computed, PetscLogDouble now) const
  {
    PetscInt missed = 0, nfailed = 0;
    PetscFunctionBeginUser;
    for (size_t k = 0; k < grid_.Count(); k++) {
      const size_t i = grid_.At(k);
      missed += grid_.done[i] && !grid_.pts[i].reached && !grid_.pts[i].failed;
      nfailed += grid_.done[i] && grid_.pts[i].failed;
    }
    if (tty_) PetscCall(PetscPrintf(PETSC_COMM_SELF, "\n")); // end the updating progress line
    if (so_.mcr.tol > 0) {
      PetscInt unpredictable = 0, short_of_tol = 0, runs = 0;
      for (size_t k = 0; k < grid_.Count(); k++) {
        const size_t i = grid_.At(k);
        if (!grid_.done[i] || grid_.pts[i].failed) continue;
        unpredictable += grid_.pts[i].predictable == 0;
        short_of_tol += grid_.pts[i].predictable == 1 && !(grid_.pts[i].mcr_error <= so_.mcr.tol);
        runs += grid_.pts[i].runs;
      }
      PetscCall(PetscPrintf(PETSC_COMM_SELF,
                            "  -sweep_mcr_tol %g: %" PetscInt_FMT " integrations; %" PetscInt_FMT
                            " point(s) unpredictable (predictable = 0: mcr is the twins' mean, mcr_spread their spread), %" PetscInt_FMT
                            " predictable but short of the tolerance after %" PetscInt_FMT " halvings (mcr_error > tol)\n",
                            (double)so_.mcr.tol, runs, unpredictable, short_of_tol, so_.mcr.levels));
    }
    PetscCall(PetscPrintf(PETSC_COMM_SELF,
                          "  computed %" PetscInt_FMT " points in %.2f s (%.2f points/s on %d ranks); %" PetscInt_FMT
                          " point(s) never reached E* (reached = 0), %" PetscInt_FMT " failed (failed = 1)\n",
                          total_computed, (double)(now - t_loop_), total_computed / std::max(1e-9, (double)(now - t_loop_)), size_, missed, nfailed));
    // an interrupted sweep: the counts above are of the points done; the others are not computed (done = 0), not "missed"
    if (grid_.Done() < (PetscInt)grid_.Count())
      PetscCall(PetscPrintf(PETSC_COMM_SELF, "  partial result: %" PetscInt_FMT " of %zu points done (interrupted: done = 0 marks the others, complete = 0)\n",
                            grid_.Done(), grid_.Count()));
    PetscCall(PetscPrintf(PETSC_COMM_SELF, "  wrote %s\n", path_.c_str()));
    PetscFunctionReturn(0);
  }

  ForcedScene sc_; // its lattice on PETSC_COMM_SELF, the forcing at the default omega and E*
  SweepOptions so_;
  PetscMPIInt rank_ = 0, size_ = 1;
  PetscSubcomm subcomm_ = nullptr;   // -sweep_group_size > 1: the groups
  MPI_Comm group_ = PETSC_COMM_SELF; // this rank's group (its lattice's communicator)
  PetscMPIInt grank_ = 0;            // rank in the group: 0 draws the points and journals them
  std::unique_ptr<const ZeroOneTest> zero_one_;
  SweepGrid grid_;
  std::string resume_from_;  // -sweep_resume: <output>.partial.h5 if there is one, else -output
  std::vector<size_t> todo_; // grid indices to compute, in the order they are handed out
  Journal journal_;
  WorkQueue queue_;
  bool tty_ = false;
  PetscInt computed_ = 0; // points this rank computed
  PetscLogDouble t_loop_ = 0;
};

} // namespace

StudyContract SweepStudyContract()
{
  using namespace schema_names;
  const std::vector<Field> sweep = WithBandEdges(
      {{"omega", D, R, "no", "rad/time", "forcing frequencies"},
       {"energy", D, R, "ne", "energy", "target energies E*"},
       // per point, in the order of the journal (studies/sweep_store.cpp): reals, then ints
       {"mcr", D, R, "ne x no", "1", "MCR"},
       {"t_off", D, R, "ne x no", "time", "cut-off time (-1: never)"},
       {"kcorr", D, R, "ne x no", "1", "0-1 test K (NaN without -sweep_kcorr)"},
       {"nl_ratio", D, R, "ne x no", "1", "nonlinear / linear energy"},
       {"amplitude", D, R, "ne x no", "force", "forcing amplitude S"},
       {"energy_final", D, R, "ne x no", "energy", "energy at the end"},
       {"seconds", D, R, "ne x no", "s", "wall time of the point"},
       {"mcr_error", D, R, "ne x no", "1", "estimated relative MCR error (-sweep_mcr_tol)"},
       {"mcr_spread", D, R, "ne x no", "1", "MCR spread over the twins where unpredictable, else 0"},
       {"mcr_dt", D, R, "ne x no", "time",
        "-sweep_mcr_tol: the step of the run behind mcr (the finest where the step was halved), or of the twins where unpredictable (NaN "
        "without)"},
       {"lyapunov", D, R, "ne x no", "1/time",
        "maximal finite-time Lyapunov exponent of the free motion over [t_off, t_final] (Benettin, tangent flow; NaN without "
        "-sweep_lyapunov or where E* was not reached)"},
       {"lyapunov_half", D, R, "ne x no", "1/time", "the same over the window's first half (its convergence: |lyapunov - lyapunov_half|)"},
       {"reached", D, I, "ne x no", "1", "1 if E* was reached", codes::kYesNo},
       {"rescalings", D, I, "ne x no", "1", "amplitude repeats"},
       {"rhs_evals", D, I, "ne x no", "1", "RHS evaluations of every attempt"},
       {"steps", D, I, "ne x no", "1", "accepted steps"},
       {"failed", D, I, "ne x no", "1", "1 if the run stopped with an error", codes::kYesNo},
       {"predictable", D, I, "ne x no", "1", "1, 0, or -1 without -sweep_mcr_tol", codes::kPredictable},
       {"mcr_runs", D, I, "ne x no", "1", "integrations spent on the point"},
       {"regime", D, I, "ne x no", "1", "regular, chaotic (predictable MCR) or unpredictable, from lyapunov, the twins and the window", codes::kRegime},
       {"done", D, I, "ne x no", "1", "1 if the point is computed", codes::kDone},
       {"points_done", A, I, "scalar", "1", "points computed so far"},
       {"points_computed", A, I, "scalar", "1", "points computed by this invocation"},
       {"kcorr_computed", A, I, "scalar", "1", "1 with -sweep_kcorr", codes::kYesNo},
       {"mcr_tol", A, R, "scalar", "1", "-sweep_mcr_tol (0: off)"},
       {"mcr_dt_phase", A, R, "scalar", "rad", "-sweep_mcr_dt_phase: the step rule's phase per step at tolerance 1e-3 (0: the scene's step)"},
       {"mcr_dt_energy", A, R, "scalar", "energy", "-sweep_mcr_dt_energy (0: the scene's -sim_dt_quartic_energy)"},
       {"kcorr_nc", A, I, "scalar", "1", "-kcorr_nc"},
       {"kcorr_sample_dt", A, R, "scalar", "time", "-kcorr_sample_dt"},
       {"kcorr_rms_fraction", A, R, "scalar", "1", "-kcorr_rms_fraction"},
       {"kcorr_record", A, R, "scalar", "time", "-kcorr_record"},
       {"kcorr_lags", A, I, "scalar", "1", "-kcorr_lags"},
       {"lyapunov_computed", A, I, "scalar", "1", "1 with -sweep_lyapunov", codes::kYesNo},
       {"lyapunov_renorm", A, R, "scalar", "time", "-sweep_lyapunov_renorm"},
       {"lyapunov_efolds", A, R, "scalar", "1", "-sweep_lyapunov_efolds"},
       {"amplitude_rule", A, S, "scalar", "1", "how S was chosen"},
       {"force_eta", D, R, "N", "1", "forcing profile eta per site, the same at every point (S scales it)"},
       {"insulated_mode", D, R, "N", "1", "linear insulated mode, the exponential profile's fit target (absent without one)"},
       {"force_exp_a", A, R, "scalar", "1", "-force_profile exponential: fitted a of eta_n = a e^{b |n - m|} (-1)^{n/2}"},
       {"force_exp_b", A, R, "scalar", "1", "-force_profile exponential: fitted b (per site)"}});
  // -sweep_refine_from: every point so far as scattered samples, each per-point field of the grid 1-D over them
  std::vector<Field> refined = {
      {"omega", D, R, "ns", "rad/time", "forcing frequency of each sample"},
      {"energy", D, R, "ns", "energy", "target energy E* of each sample"},
      {"level", D, I, "ns", "1", "quadtree depth at which the sample was added (0: the base grid)"},
      {"omega_index", D, I, "ns", "1", "omega column on the fine lattice (the base omega axis with interval midpoints inserted depth times)"},
      {"energy_index", D, I, "ns", "1", "E* row on the fine lattice (midpoints geometric on a log axis)"},
      {"done", D, I, "ns", "1", "1 if the sample is computed", codes::kDone}};
  for (const Field &f : sweep)
    if (f.kind == D && !std::strcmp(f.shape, "ne x no") && std::strcmp(f.name, "done"))
      refined.push_back({f.name, D, f.type, "ns", f.units, f.meaning, f.codes});
  refined.insert(refined.end(), {{"depth", A, I, "scalar", "1", "depth of the fine lattice: the deepest level"},
                                 {"points_new", A, I, "scalar", "1", "samples this level added"},
                                 {"leaves", A, I, "scalar", "1", "quadtree leaves examined"},
                                 {"cells_over", A, I, "scalar", "1", "leaves whose corners differ beyond a threshold"},
                                 {"cells_refined", A, I, "scalar", "1", "leaves refined (-sweep_refine_max_points may stop short of cells_over)"},
                                 {"refine_mcr", A, R, "scalar", "1", "-sweep_refine_mcr"},
                                 {"refine_kcorr", A, R, "scalar", "1", "-sweep_refine_kcorr"},
                                 {"refine_ratio", A, R, "scalar", "1", "-sweep_refine_ratio"},
                                 {"refine_max_points", A, I, "scalar", "1", "-sweep_refine_max_points (0: no cap)"},
                                 {"refine_from", A, S, "scalar", "1", "-sweep_refine_from: the previous level's file"}});
  return {WithPrefixes({ForcedScene::OptionPrefixes(), {"-sweep_", "-kcorr_"}}),
          {{"/sweep", "", sweep},
           {"/sweep/refined", "", refined},
           {"/sweep",
            "sweep_shard",
            {{"shard_points", D, I, "npts", "1",
              "grid index e * no + w (energy row e, omega column w) of each point of the shard, ascending; in a shard file every per-point "
              "dataset (ne x no in a whole-grid file, done included) is 1-D over these points, in this order"},
             {"shard_index", A, I, "scalar", "1", "i of -sweep_shard i/n"},
             {"shard_count", A, I, "scalar", "1", "n of -sweep_shard i/n"}}}}};
}

std::unique_ptr<Study> CreateSweepStudy() { return std::make_unique<SweepStudy>(); }

} // namespace nltopo
