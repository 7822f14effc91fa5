// -study simulate: one forced tone-burst run with energy cut-off; /simulate of outputs.md.
#include "bands/linear_modes.hpp"
#include "core/memory_guard.hpp"
#include "core/log.hpp"
#include "core/options_audit.hpp"
#include "core/signals.hpp"
#include "io/output.hpp"
#include "studies/registry.hpp"
#include "timeint/simulation.hpp"

namespace nltopo {

namespace {

// Keeps the sub-sampled displacement u(t) (every stride-th site, 0-based
// index divisible by stride, of this rank's block, at every sample) and E(t);
// written once at the end as /simulate/u (nt x ceil(N / stride)).
class Samples : public SampleSink {
public:
  Samples(const Lattice &lat, bool store_u, PetscInt stride) : store_u_(store_u)
  {
    for (PetscInt i = lat.OwnedStart(); i < lat.OwnedStart() + lat.OwnedCount(); i++)
      if (i % stride == 0) local_.push_back(i - lat.OwnedStart());
    col0_ = (lat.OwnedStart() + stride - 1) / stride; // strided sites before this block
    ncols_ = (lat.N() + stride - 1) / stride;
  }
  PetscInt Col0() const { return col0_; }
  PetscInt Cols() const { return ncols_; }
  PetscInt LocalCols() const { return (PetscInt)local_.size(); }
  PetscErrorCode Sample(PetscReal t, Vec z, const EnergyParts &e) override
  {
    PetscFunctionBeginUser;
    t_.push_back(t);
    energy_.push_back(e.Total());
    if (store_u_) {
      const PetscScalar *a;
      PetscCall(VecGetArrayRead(z, &a));
      for (PetscInt k : local_) u_.push_back(a[k]); // the u half of this rank's block
      PetscCall(VecRestoreArrayRead(z, &a));
    }
    PetscFunctionReturn(0);
  }
  void Restart() override
  {
    t_.clear();
    energy_.clear();
    u_.clear();
  }
  std::vector<PetscReal> t_, energy_, u_;

private:
  bool store_u_;
  std::vector<PetscInt> local_; // owned positions of the stored sites
  PetscInt col0_ = 0, ncols_ = 0;
};

PetscErrorCode StoreOptionsFromOptions(MPI_Comm comm, const LatticeParams &lp, const SimulationOptions &so, PetscBool *store_u, PetscInt *stride)
{
  PetscFunctionBeginUser;
  PetscOptionsBegin(comm, "sim_", "Simulate study output", NULL);
  PetscCall(PetscOptionsBool("-store_u", "Store the sub-sampled displacement u(t) (/simulate/u)", NULL, *store_u, store_u, NULL));
  PetscCall(PetscOptionsInt("-store_u_stride", "Store u at every this many sites (0-based index divisible by it; long lattices)", NULL, *stride, stride, NULL));
  PetscOptionsEnd();
  PetscCheck(*stride >= 1, comm, PETSC_ERR_USER, "-sim_store_u_stride must be >= 1, got %" PetscInt_FMT, *stride);
  // /simulate/u is held in memory and written at the end: at most 2.5e8 values (2 GB)
  const double samples = so.sample_dt > 0 ? std::floor(so.t_final / so.sample_dt) + 1 : 0, cols = std::ceil((double)lp.N() / (double)*stride);
  PetscCheck(!*store_u || samples * cols <= 2.5e8, comm, PETSC_ERR_USER,
             "-sim_store_u: %g samples x %g sites is more than 2.5e8 values; raise -sim_sample_dt or -sim_store_u_stride, or give -sim_store_u 0", samples, cols);
  PetscFunctionReturn(0);
}

} // namespace

PetscErrorCode SimulateStudyOptions(MPI_Comm comm)
{
  LatticeParams lp;
  ToneBurstOptions fo;
  SimulationOptions so;
  LinearModesOptions mo;
  PetscBool store_u = PETSC_TRUE;
  PetscInt stride = 1;
  PetscFunctionBeginUser;
  PetscCall(LatticeParamsFromOptions(comm, &lp));
  PetscCall(ToneBurstOptionsFromOptions(comm, lp, &fo));
  PetscCall(SimulationOptionsFromOptions(comm, &so));
  PetscCall(StoreOptionsFromOptions(comm, lp, so, &store_u, &stride));
  PetscCall(LinearModesOptionsFromOptions(comm, &mo)); // the mode profiles and the amplitude rule
  PetscCall(DeclareEPS(comm, "linear_"));
  PetscCall(DeclareTS(comm, "sim_"));
  PetscCall(DeclareOutputOptions(comm, "simulate"));
  PetscFunctionReturn(0);
}

PetscErrorCode SimulateStudy(MPI_Comm comm)
{
  LatticeParams lp;
  ToneBurstOptions fo;
  SimulationOptions so;
  LinearModesOptions mo;
  PetscBool store_u = PETSC_TRUE;
  PetscInt stride = 1;
  std::string path;
  OutputFile out;
  Lattice lat;
  LinearModes modes;
  ToneBurst burst;
  SimulationResult r;
  PetscLogDouble t_start, t_solve0, t_solve1, t_end;
  PetscFunctionBeginUser;
  PetscCall(PetscTime(&t_start));
  PetscCall(LogRegister());
  PetscCall(PetscLogStagePush(Log().setup));
  PetscCall(LatticeParamsFromOptions(comm, &lp));
  PetscCall(ToneBurstOptionsFromOptions(comm, lp, &fo));
  PetscCall(SimulationOptionsFromOptions(comm, &so));
  PetscCall(StoreOptionsFromOptions(comm, lp, so, &store_u, &stride));
  const bool need_modes = fo.profile == ForceProfile::Mode || fo.profile == ForceProfile::Exponential || (fo.profile != ForceProfile::None && fo.amplitude < 0);
  if (need_modes) PetscCall(LinearModesOptionsFromOptions(comm, &mo));
  PetscCall(OutputPathFromOptions(comm, "simulate", &path));
  double u_bytes = 0;
  if (store_u && so.sample_dt > 0) {
    PetscMPIInt nranks;
    PetscCallMPI(MPI_Comm_size(comm, &nranks));
    const double samples = (so.t_final - so.t_start) / so.sample_dt + 2, sites = std::ceil((double)lp.N() / stride) / nranks;
    PetscCall(CheckMemory(comm, 8.0 * samples * sites, "/simulate/u (-lattice_cells x -sim_t_final / -sim_sample_dt; -sim_store_u_stride or -sim_store_u 0 shrink it)"));
    u_bytes = 8.0 * samples * sites * nranks;
  }
  PetscCall(out.Open(comm, path, "", u_bytes + 16.0 * lp.N()));
  PetscCall(lat.Setup(comm, lp));
  if (need_modes) PetscCall(modes.Compute(lat, mo));
  PetscCall(burst.Setup(lat, fo, need_modes ? &modes : NULL));
  PetscCall(PetscLogStagePop());
  PetscInt rescalings = 0;

  Samples sink(lat, store_u, stride);
  PetscCall(PetscLogStagePush(Log().solve));
  PetscCall(PetscTime(&t_solve0));
  {
    EffectList fx(lat);
    PetscCall(BuildEffects(lat, &burst, &fx));
    const PetscErrorCode ierr = SimulateForced(fx, so, &sink, &r, &rescalings);
    // One run has nothing partial worth keeping: a stop signal ends it without output.
    PetscCheck(!IsInterrupt(ierr), comm, PETSC_ERR_SIG, "interrupted by %s during the forced run; no output written (one run has no partial result)",
               SignalName(StopSignalSeen()));
    PetscCall(ierr);
  }
  PetscCall(PetscTime(&t_solve1));
  PetscCall(PetscLogStagePop());

  PetscCall(PetscPrintf(comm, "nltopo simulate: N = %" PetscInt_FMT ", omega_ext = %.6f, E* = %g, S = %.6g (%s, %" PetscInt_FMT " rescalings), t_final = %g\n",
                        lat.N(), (double)burst.Omega(), (double)burst.EnergyStar(), (double)burst.Amplitude(),
                        burst.AmplitudeFromRule() ? "amplitude rule" : "-force_amplitude", rescalings, (double)so.t_final));
  if (r.reached) PetscCall(PetscPrintf(comm, "  cut-off at t_off = %.6f, E_final = %.10g\n", (double)r.t_off, (double)r.energy_final));
  else if (burst.Present())
    PetscCall(PetscPrintf(comm, "  WARNING: E* = %g was NOT reached (E_final = %.6g); RMS window from t = %g\n", (double)burst.EnergyStar(),
                          (double)r.energy_final, (double)r.window_start));
  PetscCall(PetscPrintf(comm, "  MCR = %.10f, nl_ratio = %.6g, steps = %" PetscInt_FMT " (%" PetscInt_FMT " rejected), RHS evaluations = %" PetscInt_FMT
                              ", solve %.3f s\n",
                        (double)r.mcr, (double)r.nl_ratio, r.steps, r.rejected, r.counters.rhs, (double)(t_solve1 - t_solve0)));

  PetscCall(PetscLogStagePush(Log().write));
  PetscViewer v = out.Viewer();
  const char *g = "/simulate";
  PetscCall(WriteArray(v, g, "t", sink.t_));
  PetscCall(WriteArray(v, g, "energy", sink.energy_));
  if (store_u && !sink.t_.empty()) {
    PetscCall(WriteColumnBlock(v, g, "u", (PetscInt)sink.t_.size(), sink.Cols(), sink.Col0(), sink.LocalCols(), sink.u_));
    PetscCall(WriteAttr(v, g, "u_stride", stride));
  }
  PetscCall(WriteDistributed(v, g, "rms", r.rms));
  PetscCall(WriteAttr(v, g, "mcr", r.mcr));
  PetscCall(WriteAttr(v, g, "t_off", r.t_off));
  PetscCall(WriteAttr(v, g, "energy_final", r.energy_final));
  PetscCall(WriteAttr(v, g, "nl_ratio", r.nl_ratio));
  PetscCall(WriteAttr(v, g, "rhs_evals", r.counters.rhs));
  PetscCall(WriteAttr(v, g, "rhs_evals_all_attempts", r.rhs_all_attempts));
  PetscCall(WriteAttr(v, g, "steps", r.steps));
  PetscCall(WriteAttr(v, g, "rejected_steps", r.rejected));
  PetscCall(WriteAttr(v, g, "energy_reached", (PetscInt)r.reached));
  PetscCall(WriteAttr(v, g, "window_start", r.window_start));
  PetscCall(WriteAttr(v, g, "omega_ext", burst.Omega()));
  PetscCall(WriteAttr(v, g, "energy_star", burst.EnergyStar()));
  PetscCall(WriteAttr(v, g, "amplitude", burst.Amplitude()));
  PetscCall(WriteAttr(v, g, "amplitude_rule",
                      !burst.Present() ? "none (no forcing)"
                      : burst.AmplitudeFromRule() ? "linear Gaussian-burst energy = amplitude_safety * E*; a run whose burst ends before E* is repeated with a larger S (x (1.2 E*/E_peak)^(1/p), p the log-log slope of the misses) (README.md, Amplitude rule)"
                                                  : "user (-force_amplitude)"));
  PetscCall(WriteAttr(v, g, "amplitude_safety", fo.safety));
  PetscCall(WriteAttr(v, g, "amplitude_rescalings", rescalings)); // -1: E* missed after -force_amplitude_retries
  PetscCall(WriteAttr(v, g, "tau", burst.Tau()));
  PetscCall(WriteAttr(v, g, "t0", burst.T0()));
  PetscCall(WriteAttr(v, g, "solve_seconds", (PetscReal)(t_solve1 - t_solve0)));
  PetscCall(PetscTime(&t_end));
  PetscCall(out.Commit("simulate", t_end - t_start));
  PetscCall(PetscLogStagePop());
  PetscCall(PetscPrintf(comm, "  wrote %s\n", path.c_str()));
  PetscFunctionReturn(0);
}

} // namespace nltopo
