// -study zak: the half-lattice phase experiment (paper, "Numerical realization
// of Zak phase"). The left (nontrivial) half lattice is forced with the profile
// of its optical band's mu = 0 edge (the band bottom) and mu = pi edge (the band
// top), at their linear frequencies, over an energy grid. After the cut-off,
// the phase of every site at omega_ext (Fourier coefficient over whole periods)
// gives per unit cell (2j-1, 2j) (1-based; the cell of the left lattice, joined
// by the soft intra-cell bond k2) phi = phase(even) - phase(odd), wrapped to
// [-pi/2, 3 pi/2); mean and median over cells and windows; theta = phi_pi - phi_0.
// Linear truth for model.md's left layout: at the band bottom the two sites of
// a cell move in phase (phi_0 = 0, the stiff bonds between cells stretch), at
// the top out of phase (phi_pi = pi): theta = pi.
// Output: /zak of outputs.md.
#include "bands/linear_modes.hpp"
#include "core/errors.hpp"
#include "core/log.hpp"
#include "core/option_table.hpp"
#include "core/options_audit.hpp"
#include "core/signals.hpp"
#include "core/work_queue.hpp"
#include "diagnostics/phase.hpp"
#include "io/output.hpp"
#include "studies/forced_scene.hpp"
#include "studies/grid_axis.hpp"
#include "studies/partial_summary.hpp"
#include "studies/registry.hpp"
#include "studies/study.hpp"
#include "timeint/simulation.hpp"
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

namespace nltopo {

namespace {

struct ZakOptions {
  // the energy grid (-zak_energy_*: studies/grid_axis.hpp), made from its fields after the table's Read
  PetscReal energy_min = 1e-2, energy_max = 1e3;
  PetscInt energy_n = 21;
  AxisSpacing energy_spacing = AxisSpacing::Log;
  std::vector<PetscReal> energy_list, energy;
  PetscInt windows = 4; // steady windows after t_off
  PetscInt samples_per_period = 16;
  PetscReal theta_tol = PETSC_PI / 4; // phases "distinct" while theta = phi_pi - phi_0 is within this of pi (mean and median)
};

PetscReal Median(std::vector<PetscReal> v)
{
  if (v.empty()) return std::numeric_limits<PetscReal>::quiet_NaN();
  std::sort(v.begin(), v.end());
  const size_t h = v.size() / 2;
  return v.size() % 2 ? v[h] : 0.5 * (v[h - 1] + v[h]);
}

PetscReal Mean(const std::vector<PetscReal> &v)
{
  if (v.empty()) return std::numeric_limits<PetscReal>::quiet_NaN();
  PetscReal s = 0;
  for (PetscReal x : v) s += x;
  return s / v.size();
}

// Row of one run: reached, t_off, mcr, mean, median, then the median of each window.
PetscInt RowWidth(const ZakOptions &o) { return 5 + o.windows; }

PetscErrorCode PhaseRun(const Lattice &lat, const LinearModes &modes, const ToneBurstOptions &fo, const SimulationOptions &sim, const ZakOptions &zo,
                        PetscInt mode, PetscReal energy, PetscReal *row)
{
  const PetscReal nan = std::numeric_limits<PetscReal>::quiet_NaN();
  PetscFunctionBeginUser;
  ToneBurstOptions pf = fo;
  pf.profile = ForceProfile::Mode;
  pf.mode = mode;
  pf.omega = modes.Omega()[mode];
  pf.energy = energy;
  const PetscReal w = pf.omega, T = 2 * PETSC_PI / w;
  SimulationOptions ps = sim;
  ps.sample_dt = T / zo.samples_per_period;
  const PetscInt N = lat.N();
  AfterCutoffSamples sink(N);
  SimulationResult r;
  PetscInt rescalings;
  ToneBurst burst;
  PetscCall(RunForced(lat, &modes, pf, ps, &sink, &burst, &r, &rescalings));
  for (PetscInt k = 0; k < RowWidth(zo); k++) row[k] = nan;
  row[0] = r.reached;
  row[1] = r.t_off;
  row[2] = r.mcr;
  if (!r.reached) PetscFunctionReturn(0);
  PetscCall(PetscLogEventBegin(Log().diagnostics, 0, 0, 0, 0));
  const PetscInt per_window = (sink.Samples() / zo.samples_per_period / zo.windows) * zo.samples_per_period;
  PetscCheck(per_window > 0, PETSC_COMM_SELF, PETSC_ERR_USER, "-study zak: only %" PetscInt_FMT " samples after t_off = %g at E* = %g; lengthen -sim_t_final",
             sink.Samples(), (double)r.t_off, (double)energy);
  std::vector<PetscReal> all, phase(N);
  for (PetscInt wdw = 0; wdw < zo.windows; wdw++) {
    const PetscInt k0 = wdw * per_window;
    const PetscReal t0 = sink.Times()[k0];
    for (PetscInt i = 0; i < N; i++) phase[i] = FourierPhase(sink.Data() + k0 * N + i, per_window, N, t0, ps.sample_dt, w);
    std::vector<PetscReal> win;
    for (PetscInt o = 0; o + 1 < N; o += 2) // 0-based o, o+1 = 1-based odd 2j-1 and even 2j: one unit cell
      win.push_back(WrapDimerPhase(phase[o + 1] - phase[o]));
    row[5 + wdw] = Median(win);
    all.insert(all.end(), win.begin(), win.end());
  }
  row[3] = Mean(all);
  row[4] = Median(all);
  PetscCall(PetscLogEventEnd(Log().diagnostics, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

const GridAxisFields<ZakOptions> kEnergyAxis = {
    "energy", &ZakOptions::energy_min, &ZakOptions::energy_max, &ZakOptions::energy_n, &ZakOptions::energy_spacing, &ZakOptions::energy_list};

const auto &kZakTable = DeclareOptionTable<ZakOptions>("zak_", "Half-lattice phase (Zak) experiment", [](OptionTable<ZakOptions> &t) {
  GridAxisRows(t, kEnergyAxis);
  t.Int("windows", &ZakOptions::windows, Closed(1, 1000), "Steady windows after t_off over which phases are taken")
      .Int("samples_per_period", &ZakOptions::samples_per_period, Closed(4, 10000), "Samples per forcing period for the Fourier coefficients")
      .Real("theta_tol", &ZakOptions::theta_tol, Open(0, PETSC_PI),
            "Threshold rule: phi_0 and phi_pi are distinct while theta = phi_pi - phi_0 (of the means and of the medians) is within this of pi")
      .Why("the upper end is pi");
});

// The left half lattice's defaults, the fixed forcing and the -zak_ block.
PetscErrorCode ZakOptionsFromOptions(MPI_Comm comm, LatticeParams *lp, ZakOptions *zo)
{
  std::vector<PetscBool> set;
  PetscFunctionBeginUser;
  PetscCall(RejectGivenOptions(comm, {"-sim_progress", "-sim_sample_dt"}, "-study zak (-zak_samples_per_period)"));
  {
    lp->layout = Layout::Left; // the nontrivial half lattice, 51 cells (N = 102) unless given
    lp->cells = 51;
    PetscCall(LatticeModelFromOptions(comm, lp));
    PetscCheck(lp->layout == Layout::Left, comm, PETSC_ERR_USER, "-study zak works on the left (nontrivial) half lattice: -lattice_layout must be left, got %s",
               LayoutName(lp->layout));
    PetscCall(RejectGivenOptions(comm, {"-force_omega", "-force_energy", "-force_profile", "-force_mode_index"},
                                 "-study zak (the optical band-edge modes, -zak_energy_*)"));
  }
  PetscCall(kZakTable.Read(comm, zo, &set));
  PetscCall(GridAxisFromTable(comm, "zak_", kZakTable, set, *zo, kEnergyAxis, &zo->energy));
  PetscFunctionReturn(0);
}

// The columns of /zak per energy, from the rows of the runs (run r = 2 e + edge),
// and the threshold: the lowest energy at which phi_0 and phi_pi are no longer distinct.
struct ZakTable {
  std::vector<PetscReal> p0m, p0d, ppm, ppd, thm, thd, w0, wp, mcr0, mcrp;
  std::vector<PetscInt> reached;
  PetscReal threshold = -1, last_distinct = -1; // threshold NaN: not determined (runs below it not done)
};

// The threshold's line: determined, or what the runs done show (an
// interrupted study concludes nothing from the runs it never did).
PetscErrorCode PrintThreshold(MPI_Comm comm, const ThresholdScan &s, PetscInt runs_missing, PetscInt runs)
{
  PetscFunctionBeginUser;
  if (s.determined && s.threshold > 0)
    PetscCall(PetscPrintf(comm, "  threshold: phi_0 and phi_pi stop being distinct at E = %g (last distinct: %g)\n", (double)s.threshold, (double)s.last_distinct));
  else if (s.determined) PetscCall(PetscPrintf(comm, "  threshold: phi_0 and phi_pi stay distinct over the whole energy range\n"));
  else {
    char upto[96] = "", above[96] = "";
    if (s.last_distinct > 0) std::snprintf(upto, sizeof upto, "distinct up to E = %g, ", (double)s.last_distinct);
    if (s.not_distinct_above > 0) std::snprintf(above, sizeof above, "; not distinct at E = %g, so the threshold lies at or below it", (double)s.not_distinct_above);
    PetscCall(PetscPrintf(comm, "  threshold: not determined (partial result: %" PetscInt_FMT " of %" PetscInt_FMT " runs not done): %snot run from E = %g%s\n",
                          runs_missing, runs, upto, (double)s.first_missing, above));
  }
  PetscFunctionReturn(0);
}

// Fills the table from the rows (done: per run, 0 not run) and prints it with the threshold.
PetscErrorCode Tabulate(MPI_Comm comm, const ZakOptions &zo, const std::vector<PetscReal> &res, const std::vector<PetscInt> &done, ZakTable *t)
{
  const PetscInt ne = (PetscInt)zo.energy.size(), width = RowWidth(zo);
  std::vector<ScanPoint> state(ne);
  PetscFunctionBeginUser;
  for (auto *c : {&t->p0m, &t->p0d, &t->ppm, &t->ppd, &t->thm, &t->thd, &t->mcr0, &t->mcrp}) c->assign(ne, 0);
  t->w0.assign(ne * zo.windows, 0), t->wp.assign(ne * zo.windows, 0);
  t->reached.assign(2 * ne, 0);
  PetscCall(PetscPrintf(comm, "       E*    phi_0 mean  median   phi_pi mean  median   theta mean  median\n"));
  for (PetscInt e = 0; e < ne; e++) {
    const PetscReal *a = &res[(2 * e) * width], *b = &res[(2 * e + 1) * width];
    t->reached[2 * e] = (PetscInt)a[0], t->reached[2 * e + 1] = (PetscInt)b[0];
    t->p0m[e] = a[3], t->p0d[e] = a[4], t->ppm[e] = b[3], t->ppd[e] = b[4], t->mcr0[e] = a[2], t->mcrp[e] = b[2];
    t->thm[e] = t->ppm[e] - t->p0m[e], t->thd[e] = t->ppd[e] - t->p0d[e];
    for (PetscInt k = 0; k < zo.windows; k++) t->w0[e * zo.windows + k] = a[5 + k], t->wp[e * zo.windows + k] = b[5 + k];
    const bool ran = done[2 * e] && done[2 * e + 1], ok = ran && a[0] > 0 && b[0] > 0;
    const bool distinct = ok && std::abs(t->thm[e] - PETSC_PI) <= zo.theta_tol && std::abs(t->thd[e] - PETSC_PI) <= zo.theta_tol;
    state[e] = !ran ? ScanPoint::NotRun : !ok ? ScanPoint::NotReached : distinct ? ScanPoint::Distinct : ScanPoint::NotDistinct;
    PetscCall(PetscPrintf(comm, "  %9.4g   %8.4f  %8.4f    %8.4f  %8.4f    %8.4f %8.4f %s\n", (double)zo.energy[e], (double)t->p0m[e], (double)t->p0d[e],
                          (double)t->ppm[e], (double)t->ppd[e], (double)t->thm[e], (double)t->thd[e],
                          !ran ? " (not run: interrupted)" : ok ? (distinct ? "" : " (not distinct)") : " (E* not reached)"));
  }
  const ThresholdScan s = ScanThreshold(zo.energy, state);
  t->threshold = s.threshold, t->last_distinct = s.last_distinct;
  PetscCall(PrintThreshold(comm, s, (PetscInt)std::count(done.begin(), done.end(), 0), (PetscInt)done.size()));
  PetscFunctionReturn(0);
}

class ZakStudy : public Study {
protected:
  PetscErrorCode ReadOptions() override
  {
    PetscFunctionBeginUser;
    PetscCall(ZakOptionsFromOptions(comm_, &sc_.lp, &zo_));
    PetscCall(sc_.ReadOptions(comm_, declaring_, false, ForcedScene::Modes::Always, NULL));
    sc_.sim.progress = 0;
    PetscCall(sc_.ReadModeOptions(comm_, declaring_));
    PetscFunctionReturn(0);
  }
  PetscErrorCode DeclareSolvers(MPI_Comm comm) override { return ForcedScene::DeclareSolvers(comm); }
  PetscErrorCode CheckResources() override { return sc_.CheckResources(PETSC_COMM_SELF); } // every rank its own lattice
  PetscErrorCode Build() override
  {
    PetscFunctionBeginUser;
    PetscCall(sc_.Build(PETSC_COMM_SELF, ForcedScene::Upto::Lattice)); // every rank integrates whole runs
    const NamedModes &nm = sc_.modes.Named();
    PetscCheck(nm.optical_bottom >= 0 && nm.optical_top >= 0, comm_, PETSC_ERR_USER, "-study zak: no optical band edges found for this lattice");
    // Paper's labels: mu = 0 is the optical band's lower edge, mu = pi its upper edge.
    edge_mode_[0] = nm.optical_bottom, edge_mode_[1] = nm.optical_top;
    PetscCall(PetscPrintf(comm_,
                          "nltopo zak: left lattice N = %" PetscInt_FMT ", mu = 0 edge omega = %.6f (mode %" PetscInt_FMT
                          "), mu = pi edge omega = %.6f (mode %" PetscInt_FMT "), %" PetscInt_FMT " energies\n",
                          sc_.lat.N(), (double)sc_.modes.Omega()[edge_mode_[0]], edge_mode_[0], (double)sc_.modes.Omega()[edge_mode_[1]], edge_mode_[1],
                          (PetscInt)zo_.energy.size()));
    PetscFunctionReturn(0);
  }
  PetscErrorCode Solve() override
  {
    const PetscInt ne = (PetscInt)zo_.energy.size(), width = RowWidth(zo_);
    std::vector<PetscReal> res; // run r = 2 e + edge
    PetscFunctionBeginUser;
    const PetscErrorCode irun = RunDistributed(
        comm_, 2 * ne, width,
        [&](PetscInt r, PetscReal *row) { return PhaseRun(sc_.lat, sc_.modes, sc_.fo, sc_.sim, zo_, edge_mode_[r % 2], zo_.energy[r / 2], row); }, &res, &ran_);
    if (!IsInterrupt(irun)) PetscCall(irun);                                 // a stop signal: the runs done are written, complete = 0
    if (!std::count(ran_.begin(), ran_.end(), 1)) PetscFunctionReturn(irun); // interrupted before any: nothing to tabulate
    for (PetscInt r = 0; r < 2 * ne; r++)
      if (!ran_[r]) { // not run: reached 0, NaN phases
        res[r * width] = 0;
        for (PetscInt k = 1; k < width; k++) res[r * width + k] = std::numeric_limits<PetscReal>::quiet_NaN();
      }
    PetscCall(Tabulate(comm_, zo_, res, ran_, &t_));
    PetscFunctionReturn(irun);
  }
  bool Interrupted(Interruption *it) const override
  {
    const PetscInt nran = (PetscInt)std::count(ran_.begin(), ran_.end(), 1);
    if (!nran) *it = {false, "before the first zak run ended", ""};
    else *it = {true, "between zak runs (" + std::to_string(nran) + " of " + std::to_string(ran_.size()) + " done)", ""};
    return true;
  }
  PetscErrorCode Write(PetscViewer v) override
  {
    const char *g = "/zak";
    PetscFunctionBeginUser;
    PetscCall(WriteArray(v, g, "energy", zo_.energy));
    PetscCall(WriteArray(v, g, "phi0_mean", t_.p0m));
    PetscCall(WriteArray(v, g, "phi0_median", t_.p0d));
    PetscCall(WriteArray(v, g, "phipi_mean", t_.ppm));
    PetscCall(WriteArray(v, g, "phipi_median", t_.ppd));
    PetscCall(WriteArray(v, g, "theta_mean", t_.thm));
    PetscCall(WriteArray(v, g, "theta_median", t_.thd));
    PetscCall(WriteArray(v, g, "phi0_window_median", t_.w0, zo_.windows));
    PetscCall(WriteArray(v, g, "phipi_window_median", t_.wp, zo_.windows));
    PetscCall(WriteArray(v, g, "mcr0", t_.mcr0));
    PetscCall(WriteArray(v, g, "mcrpi", t_.mcrp));
    PetscCall(WriteIntArray(v, g, "reached", t_.reached, 2));
    PetscCall(WriteIntArray(v, g, "done", ran_, 2)); // 0: not run (a stop signal came first)
    PetscCall(WriteAttr(v, g, "energy_threshold", t_.threshold));
    PetscCall(WriteAttr(v, g, "energy_last_distinct", t_.last_distinct));
    PetscCall(WriteAttr(v, g, "omega0", sc_.modes.Omega()[edge_mode_[0]]));
    PetscCall(WriteAttr(v, g, "omegapi", sc_.modes.Omega()[edge_mode_[1]]));
    PetscCall(WriteAttr(v, g, "mode0", edge_mode_[0])); // -force_mode_index of the runs: a -study simulate run repeats one
    PetscCall(WriteAttr(v, g, "modepi", edge_mode_[1]));
    PetscCall(WriteAttr(v, g, "samples_per_period", zo_.samples_per_period)); // with the run's t_off: the windows' samples
    PetscCall(WriteAttr(v, g, "theta_tol", zo_.theta_tol));
    PetscCall(WriteAttr(
        v, g, "threshold_rule",
        "lowest E at which theta = phi_pi - phi_0 of the means or of the medians over cells and windows is more than theta_tol from pi (-1: never in range; "
        "NaN: not determined, a run below it was not done)"));
    PetscFunctionReturn(0);
  }

private:
  ForcedScene sc_;
  ZakOptions zo_;
  PetscInt edge_mode_[2] = {-1, -1};
  std::vector<PetscInt> ran_;
  ZakTable t_;
};

} // namespace

StudyContract ZakStudyContract()
{
  using namespace schema_names;
  return {WithPrefixes({ForcedScene::OptionPrefixes(), {"-zak_"}}),
          {{"/zak",
            "",
            {{"energy", D, R, "ne", "energy", "target energies E*"},
             {"phi0_mean", D, R, "ne", "rad", "phi_0, mean over cells and windows"},
             {"phi0_median", D, R, "ne", "rad", "phi_0, median"},
             {"phipi_mean", D, R, "ne", "rad", "phi_pi, mean"},
             {"phipi_median", D, R, "ne", "rad", "phi_pi, median"},
             {"theta_mean", D, R, "ne", "rad", "phi_pi - phi_0 of the means"},
             {"theta_median", D, R, "ne", "rad", "phi_pi - phi_0 of the medians"},
             {"phi0_window_median", D, R, "ne x nwin", "rad", "phi_0 median per window"},
             {"phipi_window_median", D, R, "ne x nwin", "rad", "phi_pi median per window"},
             {"mcr0", D, R, "ne", "1", "MCR of the mu = 0 run"},
             {"mcrpi", D, R, "ne", "1", "MCR of the mu = pi run"},
             {"reached", D, I, "ne x 2", "1", "1 if E* was reached (mu = 0, pi)", codes::kYesNo},
             {"done", D, I, "ne x 2", "1", "0: not run (stop signal)", codes::kDone},
             {"energy_threshold", A, R, "scalar", "energy",
              "lowest E where phi_0, phi_pi stop being distinct (-1: never; NaN: not determined, runs below it were not done: complete = 0)"},
             {"energy_last_distinct", A, R, "scalar", "energy", "highest E below it still distinct (threshold NaN: below the first energy not run)"},
             {"omega0", A, R, "scalar", "rad/time", "frequency of the mu = 0 edge mode"},
             {"omegapi", A, R, "scalar", "rad/time", "frequency of the mu = pi edge mode"},
             {"mode0", A, I, "scalar", "1", "linear mode index (0-based, ascending omega) of the mu = 0 edge: the runs' -force_mode_index"},
             {"modepi", A, I, "scalar", "1", "linear mode index of the mu = pi edge"},
             {"samples_per_period", A, I, "scalar", "1", "-zak_samples_per_period"},
             {"theta_tol", A, R, "scalar", "rad", "-zak_theta_tol"},
             {"threshold_rule", A, S, "scalar", "1", "the threshold's definition"}}}}};
}

std::unique_ptr<Study> CreateZakStudy() { return std::make_unique<ZakStudy>(); }

} // namespace nltopo
