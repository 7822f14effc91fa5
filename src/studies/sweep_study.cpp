// -study sweep: a grid of forced tone-burst runs (omega_ext x E*), each the
// simulate study's run (SimulateForced, same code path), scored by MCR, t_off,
// the nonlinear/linear energy ratio and, with -sweep_kcorr, the 0-1 test.
// Runs are spread over the ranks by a shared counter (each rank integrates
// whole runs on PETSC_COMM_SELF, most expensive first), journaled as they
// finish and resumable (-sweep_resume). Output: /sweep of outputs.md.
#include "bands/linear_modes.hpp"
#include "core/cost.hpp"
#include "core/errors.hpp"
#include "core/log.hpp"
#include "core/options_audit.hpp"
#include "core/signals.hpp"
#include "core/work_queue.hpp"
#include "diagnostics/zero_one.hpp"
#include "io/output.hpp"
#include "io/run_options.hpp"
#include "io/schema.hpp"
#include "studies/grid_axis.hpp"
#include "studies/registry.hpp"
#include "studies/sweep_accuracy.hpp"
#include "studies/sweep_store.hpp"
#include "timeint/simulation.hpp"
#include <algorithm>
#include <cstdlib>
#include <cmath>
#include <limits>
#include <numeric>
#include <unistd.h>

namespace nltopo {

namespace {

struct SweepOptions {
  std::vector<PetscReal> omega, energy;
  PetscBool resume = PETSC_FALSE, kcorr = PETSC_FALSE;
  PetscReal checkpoint = 5, progress = 10;
  // 0-1 test (-kcorr_*)
  PetscInt kcorr_nc = 32, kcorr_site_stride = 1; // 32 c values: the median is stable to ~0.02 on the test series (README.md)
  PetscReal kcorr_rms_fraction = 0.1;
  PetscReal kcorr_record = 1500; // free motion analysed after t_off (s)
  PetscInt kcorr_lags = 20;
  PetscInt kcorr_seed = 1;
  PetscReal kcorr_sample_dt = 0; // 0: a quarter of the insulated period, pi / (2 sqrt(k_hat))
  McrAccuracyOptions mcr;        // -sweep_mcr_tol
  BandEdges bands{};             // of the infinite lattice, written with the map
};

PetscErrorCode SweepOptionsFromOptions(MPI_Comm comm, SweepOptions *o)
{
  PetscFunctionBeginUser;
  const PetscReal w0 = std::sqrt(3.0);
  PetscOptionsBegin(comm, "sweep_", "Sweep: grid of forced runs (omega_ext x E*)", NULL);
  PetscCall(ReadAxis(PetscOptionsObject, comm, "sweep_", "omega", w0 / 2, 1.5 * w0, 50, false, &o->omega));
  PetscCall(ReadAxis(PetscOptionsObject, comm, "sweep_", "energy", 1e-3, 1e3, 50, true, &o->energy));
  PetscCall(PetscOptionsBool("-resume", "Continue the sweep stored in -output: compute only the points not done", NULL, o->resume, &o->resume, NULL));
  PetscCall(PetscOptionsBool("-kcorr", "Score every run with the 0-1 test for chaos (-kcorr_* options)", NULL, o->kcorr, &o->kcorr, NULL));
  PetscCall(PetscOptionsReal("-checkpoint", "Rewrite -output with the points done so far every this many wall seconds", NULL, o->checkpoint, &o->checkpoint, NULL));
  PetscCall(PetscOptionsReal("-progress", "Report progress every this many wall seconds (0: never)", NULL, o->progress, &o->progress, NULL));
  PetscOptionsEnd();
  PetscCall(McrAccuracyOptionsFromOptions(comm, &o->mcr));
  PetscCheck(o->checkpoint > 0 && o->checkpoint <= 1e7, comm, PETSC_ERR_USER, "-sweep_checkpoint must lie in (0, 1e7] seconds, got %g", (double)o->checkpoint);
  PetscCheck(o->progress >= 0 && o->progress <= 1e7, comm, PETSC_ERR_USER, "-sweep_progress must lie in [0, 1e7] seconds, got %g", (double)o->progress);
  PetscOptionsBegin(comm, "kcorr_", "0-1 test for chaos (with -sweep_kcorr)", NULL);
  PetscCall(PetscOptionsInt("-nc", "Number of random frequencies c in (pi/5, 4 pi/5); K is the median over them", NULL, o->kcorr_nc, &o->kcorr_nc, NULL));
  PetscCall(PetscOptionsInt("-seed", "Seed of the c draw (the same c for every run)", NULL, o->kcorr_seed, &o->kcorr_seed, NULL));
  PetscCall(PetscOptionsReal("-sample_dt", "Sampling interval of u after t_off (0: pi / (2 sqrt(k_hat)), a quarter of the insulated period)", NULL,
                             o->kcorr_sample_dt, &o->kcorr_sample_dt, NULL));
  PetscCall(PetscOptionsReal("-rms_fraction", "Test only sites whose RMS after t_off is at least this fraction of the largest (README.md)", NULL,
                             o->kcorr_rms_fraction, &o->kcorr_rms_fraction, NULL));
  PetscCall(PetscOptionsReal("-record", "Length of the free motion after t_off that the test analyses; the run continues past -sim_t_final when needed", NULL,
                             o->kcorr_record, &o->kcorr_record, NULL));
  PetscCall(PetscOptionsInt("-lags", "Lags m at which D(m) is evaluated, evenly spread over 1..n/10 (0: all)", NULL, o->kcorr_lags, &o->kcorr_lags, NULL));
  PetscCall(PetscOptionsInt("-site_stride", "Test every this many sites (1: all; the score is the max over tested sites)", NULL, o->kcorr_site_stride,
                            &o->kcorr_site_stride, NULL));
  PetscOptionsEnd();
  PetscCheck(o->kcorr_nc >= 1 && o->kcorr_nc <= 10000, comm, PETSC_ERR_USER, "-kcorr_nc must lie in [1, 10000], got %" PetscInt_FMT, o->kcorr_nc);
  PetscCheck(o->kcorr_sample_dt >= 0 && o->kcorr_sample_dt <= 1e6, comm, PETSC_ERR_USER, "-kcorr_sample_dt must lie in [0, 1e6], got %g", (double)o->kcorr_sample_dt);
  PetscCheck(o->kcorr_rms_fraction >= 0 && o->kcorr_rms_fraction <= 1, comm, PETSC_ERR_USER, "-kcorr_rms_fraction must lie in [0, 1], got %g",
             (double)o->kcorr_rms_fraction);
  PetscCheck(o->kcorr_record > 0 && o->kcorr_record <= 1e6, comm, PETSC_ERR_USER, "-kcorr_record must lie in (0, 1e6], got %g", (double)o->kcorr_record);
  // the record is kept as samples per tested site: at most 2e6 of them
  PetscCheck(o->kcorr_sample_dt == 0 || o->kcorr_record / o->kcorr_sample_dt <= 2e6, comm, PETSC_ERR_USER,
             "-kcorr_record / -kcorr_sample_dt must be at most 2e6 samples, got %g / %g", (double)o->kcorr_record, (double)o->kcorr_sample_dt);
  PetscCheck(o->kcorr_lags == 0 || (o->kcorr_lags >= 3 && o->kcorr_lags <= 100000), comm, PETSC_ERR_USER,
             "-kcorr_lags must be 0 (all) or lie in [3, 100000], got %" PetscInt_FMT, o->kcorr_lags);
  PetscCheck(o->kcorr_site_stride >= 1, comm, PETSC_ERR_USER, "-kcorr_site_stride must be >= 1, got %" PetscInt_FMT, o->kcorr_site_stride);
  PetscCall(RejectGivenOptions(comm, {"-force_omega", "-force_energy"}, "the sweep axes (-sweep_omega_*, -sweep_energy_*) per point"));
  PetscFunctionReturn(0);
}

// complete: false for the file a sweep keeps while it runs (and leaves when
// interrupted or failed), true once every point is done.
PetscErrorCode WriteSweep(const std::string &path, const SweepGrid &g, const SweepOptions &so, PetscInt computed, PetscReal wall, bool complete)
{
  OutputFile out;
  const size_t n = g.Size();
  std::vector<PetscReal> v(n);
  std::vector<PetscInt> iv(n);
  const PetscInt no = (PetscInt)g.omega.size();
  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(Log().output, 0, 0, 0, 0));
  PetscCall(out.Open(PETSC_COMM_SELF, path));
  PetscViewer w = out.Viewer();
  const char *grp = "/sweep";
  PetscCall(WriteArray(w, grp, "omega", g.omega));
  PetscCall(WriteArray(w, grp, "energy", g.energy));
  auto doubles = [&](const char *name, PetscReal SweepPoint::*field) -> PetscErrorCode {
    PetscFunctionBeginUser;
    for (size_t i = 0; i < n; i++) v[i] = g.pts[i].*field;
    PetscCall(WriteArray(w, grp, name, v, no));
    PetscFunctionReturn(0);
  };
  auto ints = [&](const char *name, PetscInt SweepPoint::*field) -> PetscErrorCode {
    PetscFunctionBeginUser;
    for (size_t i = 0; i < n; i++) iv[i] = g.pts[i].*field;
    PetscCall(WriteIntArray(w, grp, name, iv, no));
    PetscFunctionReturn(0);
  };
  for (const auto &f : SweepRealFields()) PetscCall(doubles(f.name, f.field));
  for (const auto &f : SweepIntFields()) PetscCall(ints(f.name, f.field));
  PetscCall(WriteIntArray(w, grp, "done", g.done, no));
  PetscCall(WriteBandEdges(w, grp, so.bands));
  PetscCall(WriteAttr(w, grp, "points_done", g.Done()));
  PetscCall(WriteAttr(w, grp, "points_computed", computed)); // by this invocation (a resume computes only the missing ones)
  PetscCall(WriteAttr(w, grp, "kcorr_computed", (PetscInt)so.kcorr));
  PetscCall(WriteAttr(w, grp, "mcr_tol", so.mcr.tol)); // 0: the scene's own integration, one run per point
  PetscCall(WriteAttr(w, grp, "kcorr_nc", so.kcorr_nc));
  PetscCall(WriteAttr(w, grp, "kcorr_sample_dt", so.kcorr_sample_dt));
  PetscCall(WriteAttr(w, grp, "kcorr_rms_fraction", so.kcorr_rms_fraction));
  PetscCall(WriteAttr(w, grp, "kcorr_record", so.kcorr_record));
  PetscCall(WriteAttr(w, grp, "kcorr_lags", so.kcorr_lags));
  PetscCall(WriteAttr(w, grp, "amplitude_rule",
                      "linear Gaussian-burst energy = -force_amplitude_safety * E*; a run whose burst ends before E* is repeated with a larger S (x "
                      "(1.2 E*/E_peak)^(1/p), p the log-log slope of the misses) up to -force_amplitude_retries times (README.md, Amplitude rule); reached = 0 marks points that never reached E*"));
  PetscCall(out.Commit("sweep", wall, complete));
  PetscCall(PetscLogEventEnd(Log().output, 0, 0, 0, 0));
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
  PetscCall(burst.Setup(lat, pf, &modes));
  SimulationOptions ps = sim;
  AfterCutoffSamples sink(lat.N());
  if (so.kcorr) ps.sample_dt = so.kcorr_sample_dt;
  SimulationResult r;
  PetscInt rescalings;
  PetscLogDouble p0, p1;
  PetscCall(PetscTime(&p0));
  EffectList fx(lat), free_fx(lat); // the scene, and its free motion after the cut-off
  PetscCall(BuildEffects(lat, &burst, &fx));
  PetscCall(SimulateForced(fx, ps, so.kcorr ? &sink : NULL, &r, &rescalings));
  pt->rhs = r.rhs_all_attempts;
  if (so.kcorr && r.reached && r.t_off + so.kcorr_record > ps.t_final) {
    // The test needs a longer free record than the run has after t_off: the
    // linear lattice's ~N modes read as chaos in records much shorter than
    // 2 pi / (their spacing) (README.md "0-1 test"). Continue the free motion.
    SimulationOptions cont = ps;
    SimulationResult rc;
    cont.t_start = ps.t_final;
    cont.t_final = r.t_off + so.kcorr_record;
    sink.Continue(r.t_off);
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
      // which the test reads as chaos even in linear runs (README.md).
      std::vector<PetscReal> ms(N, 0.0);
      for (PetscInt j = 0; j < ns; j++)
        for (PetscInt s = 0; s < N; s++) ms[s] += sink.Data()[j * N + s] * sink.Data()[j * N + s];
      const PetscReal floor = so.kcorr_rms_fraction * so.kcorr_rms_fraction * *std::max_element(ms.begin(), ms.end());
      K = -1;
      for (PetscInt s = 0; s < N; s += so.kcorr_site_stride)
        if (ms[s] >= floor && ms[s] > 0) K = std::max(K, zero_one.Score(sink.Data() + s, ns, N));
    }
    pt->kcorr = K;
    PetscCall(PetscLogEventEnd(Log().diagnostics, 0, 0, 0, 0));
  } else {
    pt->kcorr = std::numeric_limits<PetscReal>::quiet_NaN();
  }
  pt->mcr = r.mcr, pt->t_off = r.t_off, pt->nl_ratio = r.nl_ratio, pt->amplitude = burst.Amplitude(), pt->energy_final = r.energy_final;
  pt->reached = r.reached, pt->rescalings = rescalings, pt->steps = r.steps;
  if (so.mcr.tol > 0) PetscCall(RefineMcr(lat, burst, sim, so.mcr, r, pt)); // the scene's options, S as the rule left it
  PetscCall(PetscTime(&p1));
  pt->seconds = p1 - p0;
  PetscFunctionReturn(0);
}

} // namespace

PetscErrorCode SweepStudyOptions(MPI_Comm comm)
{
  LatticeParams lp;
  SweepOptions so;
  ToneBurstOptions fo;
  SimulationOptions sim;
  LinearModesOptions mo;
  PetscFunctionBeginUser;
  PetscCall(RejectGivenOptions(comm, {"-sim_progress", "-sim_sample_dt"}, "-study sweep (progress: -sweep_progress; no samples are stored)"));
  PetscCall(LatticeParamsFromOptions(comm, &lp));
  PetscCall(SweepOptionsFromOptions(comm, &so));
  PetscCall(ToneBurstOptionsFromOptions(comm, lp, &fo));
  PetscCall(SimulationOptionsFromOptions(comm, &sim));
  PetscCall(LinearModesOptionsFromOptions(comm, &mo));
  PetscCall(DeclareEPS(comm, "linear_"));
  PetscCall(DeclareTS(comm, "sim_"));
  PetscCall(DeclareOutputOptions(comm, "sweep"));
  PetscFunctionReturn(0);
}

PetscErrorCode SweepStudy(MPI_Comm comm)
{
  LatticeParams lp;
  ToneBurstOptions fo;
  SimulationOptions sim;
  LinearModesOptions mo;
  SweepOptions so;
  std::string path;
  Lattice lat;
  LinearModes modes;
  SweepGrid grid;
  Journal journal;
  WorkQueue queue;
  PetscMPIInt rank, size;
  PetscLogDouble t_start, t_last_ck, t_last_pr, now = 0;
  PetscFunctionBeginUser;
  PetscCall(PetscTime(&t_start));
  PetscCall(LogRegister());
  PetscCall(PetscLogStagePush(Log().setup));
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCallMPI(MPI_Comm_size(comm, &size));
  PetscCall(LatticeParamsFromOptions(comm, &lp));
  PetscCall(SweepOptionsFromOptions(comm, &so));
  PetscCall(ToneBurstOptionsFromOptions(comm, lp, &fo));
  PetscCheck(fo.profile != ForceProfile::None, comm, PETSC_ERR_USER, "-force_profile none: a sweep needs a forcing");
  PetscCall(SimulationOptionsFromOptions(comm, &sim));
  PetscCall(CheckMcrAccuracyIntegrator(comm, so.mcr));
  PetscCall(LinearModesOptionsFromOptions(comm, &mo));
  PetscCall(OutputPathFromOptions(comm, "sweep", &path, [&](const std::string &) { return (bool)so.resume; }));
  if (so.resume) PetscCall(CheckResumeOptions(comm, path, "sweep", "-sweep_resume")); // the same physics and numerics, or one line naming the first difference
  // Every rank integrates whole runs on its own copy of the lattice.
  PetscCall(lat.Setup(PETSC_COMM_SELF, lp));
  PetscCall(modes.Compute(lat, mo));
  // The lattice's frequencies (linear 1.0..2.24 at the defaults, higher when
  // hardened) then map to c = omega dt inside the test's range (pi/5, 4 pi/5).
  if (so.kcorr_sample_dt == 0) so.kcorr_sample_dt = PETSC_PI / (2 * std::sqrt(lp.KHat()));
  so.bands = InfiniteBandEdges(lp);
  const ZeroOneTest zero_one(so.kcorr_nc, (unsigned long)so.kcorr_seed, so.kcorr_lags);

  // Rank 0 builds the starting grid (fresh, or the stored one plus journals).
  grid.Reset(so.omega, so.energy);
  int err = 0;
  char msg[512] = "";
  if (!rank) {
    PetscCall(PetscPushErrorHandler(PetscReturnErrorHandler, NULL));
    PetscErrorCode ierr = 0;
    PetscInt merged = 0;
    if (so.resume) {
      if (access(path.c_str(), F_OK)) ierr = PetscError(PETSC_COMM_SELF, __LINE__, PETSC_FUNCTION_NAME, __FILE__, PETSC_ERR_FILE_OPEN, PETSC_ERROR_INITIAL,
                                                        "-sweep_resume: no sweep file %s to resume", path.c_str());
      if (!ierr) ierr = grid.Load(path);
      if (!ierr) ierr = grid.MergeJournals(path, &merged);
    }
    if (!ierr) ierr = WriteSweep(path, grid, so, 0, 0, false); // the file exists (and is valid) from the start
    PetscCall(PetscPopErrorHandler());
    if (ierr) {
      const char *text;
      char *specific = NULL;
      PetscCall(PetscErrorMessage(ierr, &text, &specific));
      err = 1;
      PetscCall(PetscStrncpy(msg, specific ? specific : text, sizeof(msg)));
    } else {
      for (const std::string &f : JournalFiles(path)) std::remove(f.c_str()); // merged (resume) or stale (fresh start)
      if (so.resume)
        PetscCall(PetscPrintf(PETSC_COMM_SELF, "nltopo sweep: resuming %s: %" PetscInt_FMT " of %zu points done (%" PetscInt_FMT " from journals)\n", path.c_str(),
                              grid.Done(), grid.Size(), merged));
    }
  }
  PetscCallMPI(MPI_Bcast(&err, 1, MPI_INT, 0, comm));
  PetscCallMPI(MPI_Bcast(msg, sizeof(msg), MPI_CHAR, 0, comm));
  PetscCheck(!err, comm, PETSC_ERR_USER, "%s", msg);
  PetscCallMPI(MPI_Bcast(grid.done.data(), (PetscMPIInt)grid.Size(), MPIU_INT, 0, comm));

  // The missing points, most expensive (highest E*, then highest omega) first.
  const size_t no = so.omega.size(), ne = so.energy.size();
  std::vector<size_t> todo;
  for (size_t i = 0; i < grid.Size(); i++)
    if (!grid.done[i]) todo.push_back(i);
  std::stable_sort(todo.begin(), todo.end(), [&](size_t a, size_t b) { return a / no != b / no ? a / no > b / no : a % no > b % no; });
  PetscCall(PetscPrintf(comm, "nltopo sweep: %zu omega x %zu E* = %zu points, %zu to compute on %d rank(s)%s, N = %" PetscInt_FMT ", t_final = %g\n", no, ne,
                        grid.Size(), todo.size(), size, so.kcorr ? ", with the 0-1 test" : "", lat.N(), (double)sim.t_final));
  {
    PetscErrorCode jerr = 0;
    char jmsg[1024];
    PetscCall(CaptureError([&]() { return journal.Open(path, rank); }, &jerr, jmsg, sizeof(jmsg)));
    PetscCall(FailTogether(comm, jerr, jmsg)); // one rank's journal: every rank stops
  }
  PetscCall(queue.Create(comm, (PetscInt)todo.size()));
  PetscCall(PetscLogStagePop());

  PetscCall(PetscLogStagePush(Log().solve));
  sim.progress = 0;
  sim.sample_dt = 0;
  // One updating line on a terminal; periodic lines otherwise. Under mpiexec
  // (OpenMPI gives ranks a pty even when the output goes to a file) lines.
  const bool tty = !rank && isatty(fileno(stdout)) && !getenv("OMPI_COMM_WORLD_SIZE") && !getenv("PMI_RANK");
  PetscInt computed = 0, item;
  t_last_ck = t_last_pr = t_start;
  PetscLogDouble t_loop;
  PetscCall(PetscTime(&t_loop));
  // A rank stops drawing points at a stop signal (the point it is integrating
  // ends at its next time step and is dropped: a resume recomputes it) or when
  // its journal or rank 0's checkpoint cannot be written; WorkQueue::Stop makes
  // the others stop after their current point. Then all ranks meet below.
  PetscErrorCode failed = 0;
  char fail_msg[1024] = "";
  for (;;) {
    if (StopSignalLocal()) {
      PetscCall(queue.Stop());
      break;
    }
    PetscCallAbort(PETSC_COMM_WORLD, queue.Next(&item)); // MPI itself failing: nothing to save
    if (item < 0) break;
    const size_t idx = todo[item];
    SweepPoint pt;
    PetscErrorCode ierr = 0;
    char msg[1024];
    PetscCall(CaptureError([&]() { return ComputePoint(lat, modes, fo, sim, so, zero_one, so.omega[idx % no], so.energy[idx / no], &pt); }, &ierr, msg,
                           sizeof(msg)));
    if (IsInterrupt(ierr)) {
      PetscCall(queue.Stop());
      break;
    }
    if (ierr) { // one failed run (e.g. a diverging integration) is flagged; the sweep goes on
      std::fprintf(stderr, "nltopo: warning: sweep point E* = %g, omega = %g failed (flagged failed = 1): %s\n", (double)so.energy[idx / no],
                   (double)so.omega[idx % no], msg);
      const PetscReal nan = std::numeric_limits<PetscReal>::quiet_NaN();
      pt = SweepPoint();
      pt.mcr = pt.t_off = pt.kcorr = pt.nl_ratio = pt.amplitude = pt.energy_final = nan;
      pt.failed = 1;
    }
    PetscCall(CaptureError([&]() { return journal.Append(idx, pt); }, &failed, fail_msg, sizeof(fail_msg)));
    if (failed) { // a rank that cannot journal stops every rank
      PetscCall(queue.Stop());
      break;
    }
    computed++;
    if (!rank) { // rank 0 merges what every rank journaled: checkpoint file and progress
      PetscCall(PetscTime(&now));
      const bool ck = now - t_last_ck >= so.checkpoint, pr = so.progress > 0 && (tty || now - t_last_pr >= so.progress);
      if (ck || pr) {
        PetscCall(CaptureError(
          [&]() -> PetscErrorCode {
            PetscInt lines;
            PetscFunctionBeginUser;
            PetscCall(grid.MergeJournals(path, &lines));
            if (ck) PetscCall(WriteSweep(path, grid, so, computed, now - t_start, false));
            PetscFunctionReturn(0);
          },
          &failed, fail_msg, sizeof(fail_msg)));
        if (failed) {
          PetscCall(queue.Stop());
          break;
        }
        if (ck) t_last_ck = now;
        if (pr && (tty ? now - t_last_pr >= 0.5 : true)) {
          const PetscInt d = grid.Done();
          const double rate = (d - (PetscInt)(grid.Size() - todo.size())) / (now - t_loop);
          const double eta = rate > 0 ? (grid.Size() - d) / rate : 0;
          PetscCall(PetscPrintf(PETSC_COMM_SELF, "%s  [sweep] %" PetscInt_FMT " / %zu points (%.1f %%), %.2f points/s, ETA %.0f s%s", tty ? "\r" : "", d,
                                grid.Size(), 100.0 * d / grid.Size(), rate, eta, tty ? "   " : "\n"));
          if (tty) fflush(stdout);
          t_last_pr = now;
        }
      }
    }
  }
  journal.Close();
  PetscCallMPI(MPI_Barrier(comm)); // every journal is complete
  PetscCall(PetscLogStagePop());
  // A journal or checkpoint failure: every rank fails with its message; the
  // last checkpoint and the journals stay for -sweep_resume.
  PetscCall(FailTogether(comm, failed, fail_msg));
  PetscCall(AuditOptionsBeforeCommit(comm)); // collective; rank 0 alone commits the file below

  PetscCall(PetscLogStagePush(Log().write));
  PetscInt total_computed = 0;
  int sig;
  PetscCall(InterruptRequested(comm, &sig));
  PetscCallMPI(MPI_Reduce(&computed, &total_computed, 1, MPIU_INT, MPI_SUM, 0, comm));
  PetscCall(CostReduceWorld()); // rank 0 writes the card of every rank's integrations
  PetscInt done_now = 0;
  if (!rank) {
    // The journals hold every point done; merged into -output they are no
    // longer needed, also when the sweep was interrupted (the file is then
    // complete = 0 and -sweep_resume continues from it alone).
    PetscCall(CaptureError(
      [&]() -> PetscErrorCode {
        PetscInt lines;
        PetscFunctionBeginUser;
        PetscCall(grid.MergeJournals(path, &lines));
        if (so.mcr.tol > 0) {
          PetscReal worst = 0;
          for (size_t i = 0; i < grid.Size(); i++)
            if (grid.done[i] && grid.pts[i].predictable == 1 && grid.pts[i].mcr_error <= so.mcr.tol) worst = std::max(worst, grid.pts[i].mcr_error);
          CostSetErrorEstimate(worst, "the largest mcr_error of the points converged to -sweep_mcr_tol (relative)");
        }
        PetscCall(PetscTime(&now));
        done_now = grid.Done();
        PetscCall(WriteSweep(path, grid, so, total_computed, now - t_start, done_now == (PetscInt)grid.Size()));
        PetscFunctionReturn(0);
      },
      &failed, fail_msg, sizeof(fail_msg)));
    if (!failed) {
      for (const std::string &f : JournalFiles(path)) std::remove(f.c_str());
      PetscInt missed = 0, nfailed = 0;
      for (size_t i = 0; i < grid.Size(); i++) {
        missed += grid.done[i] && !grid.pts[i].reached && !grid.pts[i].failed;
        nfailed += grid.done[i] && grid.pts[i].failed;
      }
      if (tty) PetscCall(PetscPrintf(PETSC_COMM_SELF, "\n")); // end the updating progress line
      if (so.mcr.tol > 0) {
        PetscInt unpredictable = 0, short_of_tol = 0, runs = 0;
        for (size_t i = 0; i < grid.Size(); i++) {
          if (!grid.done[i] || grid.pts[i].failed) continue;
          unpredictable += grid.pts[i].predictable == 0;
          short_of_tol += grid.pts[i].predictable == 1 && !(grid.pts[i].mcr_error <= so.mcr.tol);
          runs += grid.pts[i].runs;
        }
        PetscCall(PetscPrintf(PETSC_COMM_SELF,
                              "  -sweep_mcr_tol %g: %" PetscInt_FMT " integrations; %" PetscInt_FMT " point(s) unpredictable (predictable = 0: mcr is the twins' mean, mcr_spread their spread), %" PetscInt_FMT
                              " predictable but short of the tolerance after %" PetscInt_FMT " halvings (mcr_error > tol)\n",
                              (double)so.mcr.tol, runs, unpredictable, short_of_tol, so.mcr.levels));
      }
      PetscCall(PetscPrintf(PETSC_COMM_SELF, "  computed %" PetscInt_FMT " points in %.2f s (%.2f points/s on %d ranks); %" PetscInt_FMT
                                             " point(s) never reached E* (reached = 0), %" PetscInt_FMT " failed (failed = 1)\n  wrote %s\n",
                            total_computed, (double)(now - t_loop), total_computed / std::max(1e-9, (double)(now - t_loop)), size, missed,
                            nfailed, path.c_str()));
    }
  }
  PetscCall(FailTogether(comm, failed, fail_msg));
  PetscCallMPI(MPI_Bcast(&done_now, 1, MPIU_INT, 0, comm));
  PetscCall(PetscLogStagePop());
  PetscCheck(!sig || done_now == (PetscInt)grid.Size(), comm, PETSC_ERR_SIG,
             "interrupted by %s between sweep points (%" PetscInt_FMT " of %zu done, %" PetscInt_FMT " by this run); partial output %s (complete = 0); -sweep_resume continues it",
             SignalName(sig), done_now, grid.Size(), total_computed, path.c_str());
  PetscFunctionReturn(0);
}

} // namespace nltopo
