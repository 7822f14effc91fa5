// -study stability: does an NNM persist? The orbit of a branch at each given
// frequency (continuation to it, then Newton at fixed period), its Floquet
// multipliers, then a long free run from the orbit plus a seeded perturbation,
// recording the shape correlation with the orbit and the MCR every few periods.
#include "studies/nnm_setup.hpp"
#include "core/gather.hpp"
#include "core/errors.hpp"
#include "core/log.hpp"
#include "core/options_audit.hpp"
#include "core/signals.hpp"
#include "io/output.hpp"
#include "orbits/continuation.hpp"
#include "stability/floquet.hpp"
#include "studies/registry.hpp"
#include "timeint/simulation.hpp"
#include <cmath>
#include <cstring>
#include <algorithm>
#include <random>

namespace nltopo {

namespace {

// Shape correlation |u(t) . u0| / (|u(t)| |u0|) of the displacement with the
// orbit's, sampled 8 times per period; per window of `per_window` samples the
// best-aligned snapshot is kept (with its MCR), so neither the phase drift of
// the perturbed orbit nor the zero crossings of a standing wave read as loss.
class Persistence : public SampleSink {
public:
  Persistence(const Lattice &lat, Vec z0, PetscInt per_window) : lat_(lat), z0_(z0), per_window_(per_window) {}
  PetscErrorCode Sample(PetscReal t, Vec z, const EnergyParts &e) override
  {
    const PetscScalar *a, *b;
    const PetscInt m = lat_.OwnedCount();
    PetscReal loc[4] = {0, 0, 0, 0}, g[4];
    PetscFunctionBeginUser;
    PetscCall(VecGetArrayRead(z, &a));
    PetscCall(VecGetArrayRead(z0_, &b));
    for (PetscInt k = 0; k < m; k++) {
      loc[0] += a[k] * b[k];
      loc[1] += a[k] * a[k];
      loc[2] += b[k] * b[k];
      loc[3] += a[k] * a[k] * a[k] * a[k];
    }
    PetscCall(VecRestoreArrayRead(z0_, &b));
    PetscCall(VecRestoreArrayRead(z, &a));
    PetscCall(MPIU_Allreduce(loc, g, 4, MPIU_REAL, MPIU_SUM, lat_.Comm()));
    const PetscReal c = g[1] > 0 && g[2] > 0 ? std::abs(g[0]) / std::sqrt(g[1] * g[2]) : 0;
    if (n_ == 0 || c > best_) {
      best_ = c;
      best_mcr_ = g[1] > 0 ? g[3] / (g[1] * g[1]) : 0;
    }
    if (++n_ == per_window_ || t == 0) { // the initial state is its own window
      t_.push_back(t);
      energy_.push_back(e.Total());
      corr_.push_back(best_);
      mcr_.push_back(best_mcr_);
      n_ = 0;
    }
    PetscFunctionReturn(0);
  }
  std::vector<PetscReal> t_, corr_, mcr_, energy_;

private:
  const Lattice &lat_;
  Vec z0_;
  PetscInt per_window_, n_ = 0;
  PetscReal best_ = 0, best_mcr_ = 0;
};

// State from a row [u_1..u_N, v_1..v_N] held by rank 0.
PetscErrorCode RowToState(const Lattice &lat, const std::vector<PetscReal> &rows, size_t row, Vec z)
{
  const PetscInt N = lat.N();
  std::vector<PetscReal> r(2 * N);
  PetscMPIInt rank;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(lat.Comm(), &rank));
  if (!rank) std::copy(rows.begin() + row * 2 * N, rows.begin() + (row + 1) * 2 * N, r.begin());
  PetscCallMPI(MPI_Bcast(r.data(), (int)(2 * N), MPIU_REAL, 0, lat.Comm()));
  PetscScalar *a;
  const PetscInt xs = lat.OwnedStart(), xm = lat.OwnedCount();
  PetscCall(VecGetArray(z, &a));
  for (PetscInt k = 0; k < xm; k++) {
    a[k] = r[xs + k];
    a[xm + k] = r[N + xs + k];
  }
  PetscCall(VecRestoreArray(z, &a));
  PetscFunctionReturn(0);
}

} // namespace

struct StabilityOptions {
  PetscReal omegas[16] = {std::sqrt(3.0), 1.8245, 2.1876, 2.2654}, eps = 0.01, corr_min = 0.9;
  PetscInt nw = 4, periods = 30000, sample_periods = 10, seed = 1;
};

static PetscErrorCode StabilityOptionsFromOptions(MPI_Comm comm, StabilityOptions *o)
{
  PetscInt nw = 16;
  PetscBool set;
  PetscFunctionBeginUser;
  PetscCall(RejectGivenOptions(comm, {"-sim_t_final", "-sim_sample_dt"}, "-study stability (-stability_periods, 8 samples per period)"));
  PetscOptionsBegin(comm, "stability_", "NNM persistence under perturbation (insulated branch)", NULL);
  PetscCall(PetscOptionsRealArray("-omega", "Frequencies of the insulated-branch orbits to test (paper: sqrt(3),1.8245,2.1876,2.2654)", NULL, o->omegas, &nw, &set));
  PetscCall(PetscOptionsInt("-periods", "Periods to integrate each perturbed orbit", NULL, o->periods, &o->periods, NULL));
  PetscCall(PetscOptionsInt("-sample_periods", "Record the best shape correlation (8 snapshots per period) and its MCR per window of this many periods", NULL,
                            o->sample_periods, &o->sample_periods, NULL));
  PetscCall(PetscOptionsReal("-perturbation", "Perturbation size relative to the orbit's norm (uniform random per entry)", NULL, o->eps, &o->eps, NULL));
  PetscCall(PetscOptionsInt("-seed", "Seed of the perturbation", NULL, o->seed, &o->seed, NULL));
  PetscCall(PetscOptionsReal("-corr_min", "The standing wave persisted if its shape correlation stays above this over the last 10 % of the run", NULL,
                             o->corr_min, &o->corr_min, NULL));
  PetscOptionsEnd();
  if (set) o->nw = nw;
  PetscCheck(o->nw >= 1, comm, PETSC_ERR_USER, "-stability_omega needs at least one frequency");
  for (PetscInt c = 0; c < o->nw; c++)
    PetscCheck(o->omegas[c] > 0 && o->omegas[c] <= 1e3, comm, PETSC_ERR_USER, "-stability_omega: frequencies must lie in (0, 1e3], got %g", (double)o->omegas[c]);
  PetscCheck(o->periods >= 1 && o->periods <= 100000000 && o->sample_periods >= 1 && o->sample_periods <= o->periods, comm, PETSC_ERR_USER,
             "-stability_periods must lie in [1, 1e8] and -stability_sample_periods in [1, -stability_periods], got %" PetscInt_FMT " and %" PetscInt_FMT,
             o->periods, o->sample_periods);
  PetscCheck(o->eps >= 0 && o->eps < 1, comm, PETSC_ERR_USER, "-stability_perturbation must lie in [0, 1), got %g", (double)o->eps);
  PetscCheck(o->corr_min > 0 && o->corr_min <= 1, comm, PETSC_ERR_USER, "-stability_corr_min must lie in (0, 1], got %g", (double)o->corr_min);
  PetscFunctionReturn(0);
}

PetscErrorCode StabilityStudyOptions(MPI_Comm comm)
{
  NnmSetup nnm;
  FloquetOptions flo;
  SimulationOptions sim;
  StabilityOptions st;
  PetscFunctionBeginUser;
  PetscCall(nnm.DeclareOptions(comm));
  PetscCall(FloquetOptionsFromOptions(comm, &flo));
  PetscCall(DeclareEPS(comm, "floquet_"));
  PetscCall(SimulationOptionsFromOptions(comm, &sim));
  PetscCall(StabilityOptionsFromOptions(comm, &st));
  PetscCall(DeclareTS(comm, "sim_"));
  PetscCall(DeclareOutputOptions(comm, "stability"));
  PetscFunctionReturn(0);
}

PetscErrorCode StabilityStudy(MPI_Comm comm)
{
  NnmSetup nnm;
  FloquetOptions flo;
  SimulationOptions sim;
  StabilityOptions st;
  std::string path;
  OutputFile out;
  PetscLogDouble t_start, t_end;
  PetscFunctionBeginUser;
  PetscCall(PetscTime(&t_start));
  PetscCall(LogRegister());
  PetscCall(nnm.ReadOptions(comm));
  PetscCall(FloquetOptionsFromOptions(comm, &flo));
  PetscCall(SimulationOptionsFromOptions(comm, &sim));
  PetscCall(StabilityOptionsFromOptions(comm, &st));
  const PetscReal *omegas = st.omegas, eps = st.eps, corr_min = st.corr_min;
  const PetscInt nw = st.nw, periods = st.periods, sample_periods = st.sample_periods, seed = st.seed;
  PetscCall(OutputPathFromOptions(comm, "stability", &path));
  PetscCall(out.Open(comm, path));
  PetscCall(nnm.Build(comm, "-study stability"));
  Lattice &lat = nnm.lat;
  LinearModes &modes = nnm.modes;
  PeriodicFlow &flow = nnm.flow;
  Shooting &shoot = nnm.shoot;
  ContinuationOptions &co = nnm.co;
  PetscCheck(modes.Insulated(), comm, PETSC_ERR_USER, "-study stability follows the insulated branch: use -lattice_layout interface");
  co.verbose = PETSC_FALSE;

  OwnedVec z, zT, X;
  OwnedMat S;
  PetscCall(lat.CreateStateVector(z.out()));
  PetscCall(VecDuplicate(z, zT.out()));
  PetscCall(shoot.CreateUnknowns(X.out()));
  PetscCall(flow.CreateSensitivityMatrix(S.out()));
  // One continuation of the insulated branch up to the highest frequency asked for.
  const PetscReal w0 = modes.Named().insulated_omega;
  Branch b;
  co.omega_max = *std::max_element(omegas, omegas + nw);
  // A stop signal (core/signals.hpp) ends the branch continuation or a case
  // (its Newton solve or free run) at once; the cases done are kept.
  PetscInt cases_done = 0;
  const PetscErrorCode irun = [&]() -> PetscErrorCode {
    PetscFunctionBeginUser;
    PetscCall(ContinueBranch(shoot, modes.Insulated(), 2 * PETSC_PI / w0, co, "insulated", &b));
    for (PetscInt c = 0; c < nw; c++) {
      const PetscReal wt = omegas[c];
      PetscCheck(b.omega.back() >= wt, comm, PETSC_ERR_USER, "-stability_omega %g: the insulated branch ends at omega %g (%s)", (double)wt,
                 (double)b.omega.back(), b.stop_reason.c_str());
      // The orbit at omega = wt: Newton at fixed period from the first stored orbit
      // at or above wt (the low-energy orbit itself when wt is at or below its frequency).
      size_t k = 0;
      while (b.omega[k] < wt) k++;
      PetscCall(RowToState(lat, b.z0, k, z));
      PetscReal T = b.period[k], beta = 0;
      if (k > 0) {
        bool ok;
        PetscInt its;
        PetscCall(shoot.Pack(z, 2 * PETSC_PI / wt, 0.0, X));
        PetscCall(shoot.SetPeriodConstraint(z, 2 * PETSC_PI / wt));
        PetscCall(shoot.Solve(X, &ok, &its));
        PetscCheck(ok, comm, PETSC_ERR_NOT_CONVERGED, "-stability_omega %g: no insulated-branch orbit found at this frequency", (double)wt);
        PetscCall(shoot.Unpack(X, z, &T, &beta));
      }
      EnergyParts e;
      FloquetResult fr;
      PetscCall(nnm.fx.Energy(z, &e));
      PetscCall(flow.IntegrateWithMonodromy(z, T, flow.FloquetBeta(beta), zT, S));
      PetscCall(FloquetAnalysis(lat, S, flo, &fr));
      // Perturbation: z0 + eps ||z0|| / sqrt(2N) xi, xi uniform in (-1, 1) per entry,
      // drawn by global index from the seed (the same on any number of ranks).
      OwnedVec zp;
      PetscReal nz;
      PetscCall(VecDuplicate(z, zp.out()));
      PetscCall(VecNorm(z, NORM_2, &nz));
      {
        std::mt19937_64 rng((unsigned long)seed * 7919 + c);
        std::uniform_real_distribution<PetscReal> xi(-1, 1);
        std::vector<PetscReal> noise(2 * lat.N());
        for (auto &x : noise) x = xi(rng);
        const PetscScalar *a;
        PetscScalar *p;
        const PetscInt xs = lat.OwnedStart(), xm = lat.OwnedCount(), N = lat.N();
        const PetscReal scale = eps * nz / std::sqrt(2.0 * N);
        PetscCall(VecGetArrayRead(z, &a));
        PetscCall(VecGetArray(zp, &p));
        for (PetscInt k = 0; k < xm; k++) {
          p[k] = a[k] + scale * noise[xs + k];
          p[xm + k] = a[xm + k] + scale * noise[N + xs + k];
        }
        PetscCall(VecRestoreArray(zp, &p));
        PetscCall(VecRestoreArrayRead(z, &a));
      }
      EnergyParts ep;
      PetscCall(nnm.fx.Energy(zp, &ep)); // the perturbed start: the free run conserves this
      SimulationOptions run = sim;
      run.t_final = periods * T;
      run.sample_dt = T / 8;
      Persistence sink(lat, z, 8 * sample_periods);
      SimulationResult r;
      PetscCall(Simulate(nnm.fx, run, zp, &sink, &r));
      const size_t ns = sink.corr_.size(), tail = std::max<size_t>(1, ns / 10);
      PetscReal tail_min = 1;
      for (size_t k = ns - tail; k < ns; k++) tail_min = std::min(tail_min, sink.corr_[k]);
      const bool persisted = tail_min >= corr_min;
      PetscCall(PetscPrintf(comm, "nltopo stability: omega %.4f (E = %.4g): Floquet max |mu| = %.6f (%s), %" PetscInt_FMT " periods: shape correlation %.3f at the end (min %.3f over the last 10 %%), MCR %.3f -> %.3f: %s\n",
                            (double)(2 * PETSC_PI / T), (double)e.Total(), (double)fr.max_modulus, fr.stable ? "stable" : "unstable", periods,
                            (double)sink.corr_.back(), (double)tail_min, (double)sink.mcr_.front(), (double)sink.mcr_.back(),
                            persisted ? "the standing wave persisted" : "the standing wave did NOT persist"));
      const std::string g = "/stability/case" + std::to_string(c);
      PetscViewer v = out.Viewer();
      PetscCall(WriteArray(v, g.c_str(), "t", sink.t_));
      PetscCall(WriteArray(v, g.c_str(), "corr", sink.corr_));
      PetscCall(WriteArray(v, g.c_str(), "mcr", sink.mcr_));
      PetscCall(WriteArray(v, g.c_str(), "energy", sink.energy_));
      PetscCall(WriteArray(v, g.c_str(), "multipliers_re", fr.re));
      PetscCall(WriteArray(v, g.c_str(), "multipliers_im", fr.im));
      PetscCall(WriteAttr(v, g.c_str(), "omega_target", wt));
      PetscCall(WriteAttr(v, g.c_str(), "omega", (PetscReal)(2 * PETSC_PI / T)));
      PetscCall(WriteAttr(v, g.c_str(), "energy", e.Total()));
      PetscCall(WriteAttr(v, g.c_str(), "period", T));
      PetscCall(WriteAttr(v, g.c_str(), "max_modulus", fr.max_modulus));
      PetscCall(WriteAttr(v, g.c_str(), "floquet_stable", (PetscInt)fr.stable));
      PetscCall(WriteAttr(v, g.c_str(), "instability", fr.instability));
      PetscCall(WriteAttr(v, g.c_str(), "persisted", (PetscInt)persisted));
      PetscCall(WriteAttr(v, g.c_str(), "corr_tail_min", tail_min));
      PetscCall(WriteAttr(v, g.c_str(), "energy_drift", (r.energy_final - ep.Total()) / ep.Total()));
      cases_done++;
    }
    PetscFunctionReturn(0);
  }();
  if (!IsInterrupt(irun)) PetscCall(irun);
  const bool interrupted = IsInterrupt(irun);
  PetscCheck(!interrupted || cases_done > 0, comm, PETSC_ERR_SIG, "interrupted by %s before the first stability case ended; no output written",
             SignalName(StopSignalSeen()));
  PetscCall(WriteAttr(out.Viewer(), "/stability", "cases_done", cases_done)); // of -stability_omega's; fewer only when interrupted
  PetscCall(PetscTime(&t_end));
  PetscCall(out.Commit("stability", t_end - t_start, !interrupted));
  PetscCheck(!interrupted, comm, PETSC_ERR_SIG, "interrupted by %s during stability case %" PetscInt_FMT " (omega %g); partial output %s (complete = 0) with the %" PetscInt_FMT " case(s) before it",
             SignalName(StopSignalSeen()), cases_done, (double)omegas[cases_done], path.c_str(), cases_done);
  PetscCall(PetscPrintf(comm, "  wrote %s\n", path.c_str()));
  PetscFunctionReturn(0);
}

} // namespace nltopo
