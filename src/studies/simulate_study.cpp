// -study simulate: one forced tone-burst run with energy cut-off; /simulate of outputs.md.
#include "bands/linear_modes.hpp"
#include "core/memory_guard.hpp"
#include "core/log.hpp"
#include "core/option_table.hpp"
#include "core/options_audit.hpp"
#include "core/signals.hpp"
#include "io/output.hpp"
#include "studies/forced_scene.hpp"
#include "studies/registry.hpp"
#include "studies/simulate_store.hpp"
#include "studies/study.hpp"
#include "timeint/simulation.hpp"

namespace nltopo {

// Extent: how much of the run the output keeps (a resume or an overwrite may change it).
static const auto &kStoreTable = DeclareOptionTable<SimulateStoreOptions>("sim_", "Simulate study output", [](OptionTable<SimulateStoreOptions> &t) {
  t.Bool("store_u", &SimulateStoreOptions::store_u, "Store the sub-sampled displacement u(t) (/simulate/u)", OptionClass::Extent)
      .Int("store_u_stride", &SimulateStoreOptions::stride, Closed(1, PETSC_MAX_INT),
           "Store u at every this many sites (0-based index divisible by it; long lattices)", OptionClass::Extent);
});

PetscErrorCode SimulateStoreOptionsFromOptions(MPI_Comm comm, SimulateStoreOptions *o) { return kStoreTable.Read(comm, o); }

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
  void Reserve(PetscInt samples) override
  {
    t_.reserve(samples);
    energy_.reserve(samples);
    if (store_u_) u_.reserve(samples * local_.size());
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

PetscErrorCode StoreOptionsFromOptions(MPI_Comm comm, const LatticeParams &lp, const SimulationOptions &so, SimulateStoreOptions *o)
{
  PetscFunctionBeginUser;
  PetscCall(SimulateStoreOptionsFromOptions(comm, o));
  // /simulate/u is held in memory and written at the end: at most 2.5e8 values (2 GB)
  const double samples = so.sample_dt > 0 ? std::floor(so.t_final / so.sample_dt) + 1 : 0, cols = std::ceil((double)lp.N() / (double)o->stride);
  PetscCheck(!o->store_u || samples * cols <= 2.5e8, comm, PETSC_ERR_USER,
             "-sim_store_u: %g samples x %g sites is more than 2.5e8 values; raise -sim_sample_dt or -sim_store_u_stride, or give -sim_store_u 0", samples,
             cols);
  PetscFunctionReturn(0);
}

class SimulateStudy : public Study {
protected:
  PetscErrorCode ReadOptions() override
  {
    PetscFunctionBeginUser;
    PetscCall(sc_.ReadOptions(comm_, declaring_, true, ForcedScene::Modes::Needed, NULL)); // -force_profile none: a free run
    PetscCall(StoreOptionsFromOptions(comm_, sc_.lp, sc_.sim, &store_));
    PetscCall(sc_.ReadModeOptions(comm_, declaring_));
    PetscFunctionReturn(0);
  }
  PetscErrorCode CheckResources() override
  {
    PetscFunctionBeginUser;
    PetscCall(sc_.CheckResources(comm_));
    if (store_.store_u && sc_.sim.sample_dt > 0) {
      PetscMPIInt nranks;
      PetscCallMPI(MPI_Comm_size(comm_, &nranks));
      const double samples = (sc_.sim.t_final - sc_.sim.t_start) / sc_.sim.sample_dt + 2, sites = std::ceil((double)sc_.lp.N() / store_.stride) / nranks;
      PetscCall(CheckMemory(comm_, 8.0 * samples * sites,
                            "/simulate/u (-lattice_cells x -sim_t_final / -sim_sample_dt; -sim_store_u_stride or -sim_store_u 0 shrink it)"));
      u_bytes_ = 8.0 * samples * sites * nranks;
    }
    PetscFunctionReturn(0);
  }
  PetscErrorCode DeclareSolvers(MPI_Comm comm) override { return ForcedScene::DeclareSolvers(comm); }
  double OutputBytes() const override { return u_bytes_ + 16.0 * sc_.lp.N(); }
  PetscErrorCode Build() override
  {
    PetscFunctionBeginUser;
    PetscCall(sc_.Build(comm_, ForcedScene::Upto::Effects));
    sink_ = std::make_unique<Samples>(sc_.lat, store_.store_u, store_.stride);
    PetscFunctionReturn(0);
  }
  PetscErrorCode Solve() override
  {
    PetscLogDouble t0, t1;
    PetscFunctionBeginUser;
    PetscCall(PetscTime(&t0));
    {
      const PetscErrorCode ierr = SimulateForced(sc_.fx, sc_.sim, sink_.get(), &r_, &rescalings_);
      if (IsInterrupt(ierr)) PetscFunctionReturn(ierr); // Interrupted: no output
      PetscCall(ierr);
    }
    PetscCall(PetscTime(&t1));
    solve_seconds_ = t1 - t0;
    PetscCall(PetscPrintf(comm_,
                          "nltopo simulate: N = %" PetscInt_FMT ", omega_ext = %.6f, E* = %g, S = %.6g (%s, %" PetscInt_FMT " rescalings), t_final = %g\n",
                          sc_.lat.N(), (double)sc_.burst.Omega(), (double)sc_.burst.EnergyStar(), (double)sc_.burst.Amplitude(),
                          sc_.burst.AmplitudeFromRule() ? "amplitude rule" : "-force_amplitude", rescalings_, (double)sc_.sim.t_final));
    if (r_.reached) PetscCall(PetscPrintf(comm_, "  cut-off at t_off = %.6f, E_final = %.10g\n", (double)r_.t_off, (double)r_.energy_final));
    else if (sc_.burst.Present())
      PetscCall(PetscPrintf(comm_, "  WARNING: E* = %g was NOT reached (E_final = %.6g); RMS window from t = %g\n", (double)sc_.burst.EnergyStar(),
                            (double)r_.energy_final, (double)r_.window_start));
    PetscCall(PetscPrintf(
        comm_, "  MCR = %.10f, nl_ratio = %.6g, steps = %" PetscInt_FMT " (%" PetscInt_FMT " rejected), RHS evaluations = %" PetscInt_FMT ", solve %.3f s\n",
        (double)r_.mcr, (double)r_.nl_ratio, r_.steps, r_.rejected, r_.counters.rhs, solve_seconds_));
    PetscFunctionReturn(0);
  }
  // One run has nothing partial worth keeping: a stop signal ends it without output.
  bool Interrupted(Interruption *it) const override
  {
    *it = {false, "during the forced run", " (one run has no partial result)"};
    return true;
  }
  PetscErrorCode Write(PetscViewer v) override
  {
    const SimulationResult &r = r_;
    const Samples &sink = *sink_;
    const char *g = "/simulate";
    PetscFunctionBeginUser;
    PetscCall(WriteArray(v, g, "t", sink.t_));
    PetscCall(WriteArray(v, g, "energy", sink.energy_));
    if (store_.store_u && !sink.t_.empty()) {
      PetscCall(WriteColumnBlock(v, g, "u", (PetscInt)sink.t_.size(), sink.Cols(), sink.Col0(), sink.LocalCols(), sink.u_));
      PetscCall(WriteAttr(v, g, "u_stride", store_.stride));
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
    PetscCall(WriteAttr(v, g, "omega_ext", sc_.burst.Omega()));
    PetscCall(WriteAttr(v, g, "energy_star", sc_.burst.EnergyStar()));
    PetscCall(WriteAttr(v, g, "amplitude", sc_.burst.Amplitude()));
    PetscCall(WriteAttr(
        v, g, "amplitude_rule",
        !sc_.burst.Present() ? "none (no forcing)"
        : sc_.burst.AmplitudeFromRule()
            ? "linear Gaussian-burst energy = amplitude_safety * E*; a run whose burst ends before E* is repeated with a larger S (x (1.2 E*/E_peak)^(1/p), p the log-log slope of the misses) (docs/model.md, the amplitude rule)"
            : "user (-force_amplitude)"));
    PetscCall(WriteAttr(v, g, "amplitude_safety", sc_.fo.safety));
    PetscCall(WriteAttr(v, g, "amplitude_rescalings", rescalings_)); // -1: E* missed after -force_amplitude_retries
    PetscCall(WriteAttr(v, g, "tau", sc_.burst.Tau()));
    PetscCall(WriteAttr(v, g, "t0", sc_.burst.T0()));
    PetscCall(WriteAttr(v, g, "solve_seconds", solve_seconds_));
    PetscFunctionReturn(0);
  }

private:
  ForcedScene sc_;
  SimulateStoreOptions store_;
  PetscInt rescalings_ = 0;
  double u_bytes_ = 0;
  PetscReal solve_seconds_ = 0;
  std::unique_ptr<Samples> sink_;
  SimulationResult r_;
};

} // namespace

StudyContract SimulateStudyContract()
{
  using namespace schema_names;
  return {ForcedScene::OptionPrefixes(),
          {{"/simulate",
            "",
            {{"t", D, R, "nt", "time", "sample times"},
             {"energy", D, R, "nt", "energy", "total energy"},
             {"u", D, R, "nt x N", "displacement", "displacements, sub-sampled (with u_stride)"},
             {"rms", D, R, "N", "displacement", "RMS per site after the cut-off"},
             {"u_stride", A, I, "scalar", "1", "-sim_store_u_stride"},
             {"mcr", A, R, "scalar", "1", "mode confinement ratio"},
             {"t_off", A, R, "scalar", "time", "cut-off time (-1: never)"},
             {"energy_final", A, R, "scalar", "energy", "energy at the end"},
             {"nl_ratio", A, R, "scalar", "1", "nonlinear / linear energy"},
             {"rhs_evals", A, I, "scalar", "1", "RHS evaluations of the run"},
             {"rhs_evals_all_attempts", A, I, "scalar", "1", "RHS evaluations of every amplitude attempt"},
             {"steps", A, I, "scalar", "1", "accepted steps"},
             {"rejected_steps", A, I, "scalar", "1", "rejected steps"},
             {"energy_reached", A, I, "scalar", "1", "1 if E* was reached", codes::kYesNo},
             {"window_start", A, R, "scalar", "time", "start of the RMS window"},
             {"omega_ext", A, R, "scalar", "rad/time", "forcing frequency"},
             {"energy_star", A, R, "scalar", "energy", "target energy E*"},
             {"amplitude", A, R, "scalar", "force", "forcing amplitude S"},
             {"amplitude_rule", A, S, "scalar", "1", "how S was chosen"},
             {"amplitude_safety", A, R, "scalar", "1", "-force_amplitude_safety"},
             {"amplitude_rescalings", A, I, "scalar", "1", "repeats with a larger S (-1: E* missed)"},
             {"tau", A, R, "scalar", "time", "burst width"},
             {"t0", A, R, "scalar", "time", "burst centre"},
             {"solve_seconds", A, R, "scalar", "s", "wall time of the solve"}}}}};
}

std::unique_ptr<Study> CreateSimulateStudy() { return std::make_unique<SimulateStudy>(); }

} // namespace nltopo
