#include "studies/sweep_accuracy.hpp"
#include "core/option_table.hpp"
#include "core/ts_traits.hpp"
#include <algorithm>
#include <cmath>

namespace nltopo {

static const auto &kMcrAccuracyTable =
    DeclareOptionTable<McrAccuracyOptions>("sweep_", "Accuracy-aware sweep (-sweep_mcr_tol)", [](OptionTable<McrAccuracyOptions> &t) {
      t.Real("mcr_tol", &McrAccuracyOptions::tol, RightOpen(0, 1),
             "Target relative accuracy of each point's MCR: the step is halved until two runs agree to it; unpredictable points get twin-run statistics (0: "
             "off, the scene's own integration)")
          .Int("mcr_levels", &McrAccuracyOptions::levels, Closed(0, 8), "-sweep_mcr_tol: at most this many halvings of the step")
          .Int("mcr_twins", &McrAccuracyOptions::twins, Closed(1, 100), "-sweep_mcr_tol: twin runs (amplitude x (1 + k eps)) of a point that does not converge")
          .Real("mcr_twin_eps", &McrAccuracyOptions::twin_eps, Closed(1e-15, 1e-2), "-sweep_mcr_tol: relative change of the amplitude of the twins")
          .Real("mcr_dt_phase", &McrAccuracyOptions::dt_phase, Closed(0, 1),
                "-sweep_mcr_tol: the step rule, the forcing's phase per step (rad) at tolerance 1e-3 (0: the scene's -sim_ts_dt and "
                "-sim_dt_quartic_energy)")
          .Real("mcr_dt_energy", &McrAccuracyOptions::dt_energy, Closed(0, 1e12),
                "-sweep_mcr_dt_phase: the E* at which the hardened bonds' frequency reaches the linear lattice's top (0: the scene's "
                "-sim_dt_quartic_energy)");
    });

PetscErrorCode McrAccuracyOptionsFromOptions(MPI_Comm comm, McrAccuracyOptions *o) { return kMcrAccuracyTable.Read(comm, o); }

PetscErrorCode CheckMcrAccuracyIntegrator(MPI_Comm comm, const McrAccuracyOptions &o)
{
  char type[64];
  PetscFunctionBeginUser;
  if (o.tol == 0) PetscFunctionReturn(0);
  PetscCall(PetscStrncpy(type, TSDefaultType("sim_"), sizeof(type)));
  PetscCall(PetscOptionsGetString(NULL, NULL, "-sim_ts_type", type, sizeof(type), NULL));
  const TSTraits *tr = TSTraitsFind(type);
  PetscCheck(tr && tr->fixed_step, comm, PETSC_ERR_USER,
             "-sweep_mcr_tol needs a fixed-step integrator (-sim_ts_type symsplit: the ladder halves its step), got -sim_ts_type %s", type);
  PetscFunctionReturn(0);
}

SimulationOptions McrFirstRunOptions(const McrAccuracyOptions &o, const SimulationOptions &sim, PetscReal omega_ext, PetscReal energy, PetscReal omega_top)
{
  SimulationOptions first = sim;
  if (o.tol > 0 && o.dt_phase > 0) {
    // bm4's MCR error grows as h^4 where the step is not yet coarse
    // (benchmarks/README.md "Issue 36 item 5"): the tolerance sets the step as tol^(1/4).
    const PetscReal E_q = o.dt_energy > 0 ? o.dt_energy : sim.dt_quartic_energy;
    const PetscReal omega_hard = E_q > 0 ? omega_top * std::pow(energy / E_q, 0.25) : 0;
    PetscReal h = o.dt_phase / omega_ext;
    if (omega_hard > 0) h = std::min(h, o.dt_phase / omega_hard);
    first.dt_base = std::min(h * std::pow(o.tol / 1e-3, 0.25), 1 / omega_top);
    first.dt_quartic_energy = 0; // in the rule
  }
  return first;
}

PetscReal McrFirstStep(const SimulationOptions &first, PetscReal scene_dt, PetscReal energy)
{
  return (first.dt_base > 0 ? first.dt_base : scene_dt) * first.dt_scale * QuarticStepFactor(first, energy);
}

namespace {

PetscReal RelDiff(PetscReal a, PetscReal b) { return std::abs(a - b) / std::max(std::abs(a), std::abs(b)); }

// One more run of the point with the step times scale and the amplitude times (1 + da).
PetscErrorCode Rerun(const Lattice &lat, const ToneBurst &burst, const SimulationOptions &sim, PetscReal scale, PetscReal da, SimulationResult *r,
                     SweepPoint *pt)
{
  PetscFunctionBeginUser;
  SimulationOptions o = sim;
  o.dt_scale = scale;
  o.sample_dt = 0;
  ToneBurst b = burst;
  if (da != 0) b.ScaleAmplitude(1 + da);
  EffectList fx(lat);
  PetscCall(BuildEffects(lat, &b, &fx));
  PetscCall(Simulate(fx, o, NULL, NULL, r));
  pt->rhs += r->counters.rhs;
  pt->runs++;
  PetscFunctionReturn(0);
}

void Accept(const SimulationResult &r, SweepPoint *pt)
{
  pt->mcr = r.mcr, pt->t_off = r.t_off, pt->nl_ratio = r.nl_ratio, pt->energy_final = r.energy_final, pt->reached = r.reached, pt->steps = r.steps;
}

// Halves the step from h (the first run r0) until two successive runs agree to
// tol: |m(h) - m(2h)| = est was the first difference. Stops early when a halving
// does not halve the difference (a step ladder that does not converge).
PetscErrorCode HalveStep(const Lattice &lat, const ToneBurst &burst, const SimulationOptions &first, PetscReal h, const McrAccuracyOptions &o,
                         const SimulationResult &r0, PetscReal est, SweepPoint *pt)
{
  PetscReal finest = r0.mcr, prev_diff = est, diff = est, scale = 1;
  bool converged = false;
  PetscFunctionBeginUser;
  for (PetscInt l = 1; !converged && l <= o.levels; l++) {
    SimulationResult r;
    scale *= 0.5;
    PetscCall(Rerun(lat, burst, first, scale, 0, &r, pt));
    diff = RelDiff(r.mcr, finest);
    finest = r.mcr;
    Accept(r, pt);
    // two successive differences below tol (one alone has agreed by chance at sensitive points)
    converged = diff <= o.tol && prev_diff <= o.tol;
    if (!converged && diff > o.tol && !(diff < 0.5 * prev_diff)) break;
    prev_diff = diff;
  }
  pt->mcr = finest;
  pt->mcr_dt = h * scale;
  pt->mcr_spread = 0;
  pt->mcr_error = converged ? diff : std::max(diff, std::nextafter(o.tol, PETSC_MAX_REAL)); // > tol: not converged
  pt->predictable = 1;
  PetscFunctionReturn(0);
}

} // namespace

PetscErrorCode RefineMcr(const Lattice &lat, const ToneBurst &burst, const SimulationOptions &first, PetscReal h, const McrAccuracyOptions &o,
                         const SimulationResult &r0, SweepPoint *pt)
{
  SimulationResult r2;
  PetscFunctionBeginUser;
  pt->runs = 1;
  // The check: the run at twice the step. |m(h) - m(2h)| is (2^p - 1) times
  // m(h)'s error for a method of order p in its asymptotic range, so
  // |m(h) - m(2h)| <= tol / 4 accepts m(h).
  PetscCall(Rerun(lat, burst, first, 2, 0, &r2, pt));
  const PetscReal est = RelDiff(r0.mcr, r2.mcr);
  // The probe of predictability: runs at one step with the amplitude times
  // 1 + k eps (k = 0, 1, -1, 2, ...). At 2h where the 2h run is sound (it ends
  // with the energy of the first run to 10 tol, reached or not alike: the
  // motion of a nearby energy, where a step beyond stability would blow up):
  // the spread measures the motion's sensitivity, which a stable step does not
  // change, at half the cost. Otherwise at h.
  const bool sound = r2.reached == r0.reached && RelDiff(r2.energy_final, r0.energy_final) <= 10 * o.tol;
  const PetscReal probe = sound ? 2 : 1;
  std::vector<PetscReal> m = {sound ? r2.mcr : r0.mcr};
  auto twin = [&](PetscInt j) -> PetscErrorCode {
    const PetscReal k = (j % 2 ? -1.0 : 1.0) * (PetscReal)(j / 2 + 1);
    SimulationResult r;
    PetscFunctionBeginUser;
    PetscCall(Rerun(lat, burst, first, probe, k * o.twin_eps, &r, pt));
    m.push_back(r.mcr);
    PetscFunctionReturn(0);
  };
  PetscCall(twin(0));
  // A 1e-10 change of S moves the MCR by at most tol / 100: the check's agreement
  // is not by chance. (At tol / 10 one sensitive point of the paper grid, whose
  // twins spread by 5 tol, passed check and twin together.)
  const bool steady = RelDiff(m[0], m[1]) <= 0.01 * o.tol;
  if (steady && est <= 0.25 * o.tol) {
    pt->mcr_error = est;
    pt->mcr_spread = 0;
    pt->mcr_dt = h;
    pt->predictable = 1;
    PetscFunctionReturn(0);
  }
  if (!steady) {
    for (PetscInt j = 1; j < o.twins; j++) PetscCall(twin(j));
    const auto [lo, hi] = std::minmax_element(m.begin(), m.end());
    PetscReal mean = 0;
    for (PetscReal x : m) mean += x;
    mean /= (PetscReal)m.size();
    if ((*hi - *lo) / std::abs(mean) > o.tol) {
      pt->mcr = mean; // one sample would pretend to a precision the point does not have
      pt->mcr_spread = *hi - *lo;
      pt->mcr_error = std::numeric_limits<PetscReal>::quiet_NaN();
      pt->mcr_dt = h * probe;
      pt->predictable = 0;
      PetscFunctionReturn(0);
    }
  }
  // Predictable at this tolerance, the step too coarse for it: halve it.
  PetscCall(HalveStep(lat, burst, first, h, o, r0, est, pt));
  PetscFunctionReturn(0);
}

} // namespace nltopo
