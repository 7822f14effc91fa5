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
          .Real("mcr_twin_eps", &McrAccuracyOptions::twin_eps, Closed(1e-15, 1e-2), "-sweep_mcr_tol: relative change of the amplitude of the twins");
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

} // namespace

PetscErrorCode RefineMcr(const Lattice &lat, const ToneBurst &burst, const SimulationOptions &sim, const McrAccuracyOptions &o, const SimulationResult &r0,
                         SweepPoint *pt)
{
  PetscReal finest = r0.mcr, est = std::numeric_limits<PetscReal>::infinity();
  bool ladder_done = false;
  // The run at twice the step bounds the first run's error: |m(h) - m(2h)| is
  // (2^p - 1) times the error of m(h) for a method of order p in its
  // asymptotic range, so |m(h) - m(2h)| <= tol / 4 accepts m(h). Otherwise
  // halve the step until two successive differences d_l = |m_l - m_(l-1)| are
  // both below tol (one alone has agreed by chance at sensitive points, where
  // the differences do not shrink steadily), and stop early when a halving
  // does not halve the difference (not converging: the twins decide).
  bool converged = false;
  auto ladder = [&]() -> PetscErrorCode {
    SimulationResult r;
    PetscFunctionBeginUser;
    ladder_done = true;
    PetscCall(Rerun(lat, burst, sim, 2, 0, &r, pt));
    PetscReal prev_diff = RelDiff(r0.mcr, r.mcr), scale = 1;
    est = prev_diff;
    converged = est <= 0.25 * o.tol;
    for (PetscInt l = 1; !converged && l <= o.levels; l++) {
      scale *= 0.5;
      PetscCall(Rerun(lat, burst, sim, scale, 0, &r, pt));
      const PetscReal diff = RelDiff(r.mcr, finest);
      finest = r.mcr;
      Accept(r, pt);
      est = diff;
      converged = diff <= o.tol && prev_diff <= o.tol;
      if (!converged && diff > o.tol && !(diff < 0.5 * prev_diff)) break;
      prev_diff = diff;
    }
    PetscFunctionReturn(0);
  };
  PetscFunctionBeginUser;
  pt->runs = 1;
  const bool chaotic = std::isfinite(pt->kcorr) && pt->kcorr > o.kcorr_chaotic;
  std::vector<PetscReal> m = {r0.mcr}; // the first run and its twins (S x (1 + k eps), k = 1, -1, 2, -2, ...)
  auto twin = [&](PetscInt j) -> PetscErrorCode {
    const PetscReal k = (j % 2 ? -1.0 : 1.0) * (PetscReal)(j / 2 + 1);
    SimulationResult r;
    PetscFunctionBeginUser;
    PetscCall(Rerun(lat, burst, sim, 1, k * o.twin_eps, &r, pt));
    m.push_back(r.mcr);
    PetscFunctionReturn(0);
  };
  if (!chaotic) {
    PetscCall(ladder());
    if (converged) {
      // One twin guards against a ladder that agreed by chance at a point that
      // a 1e-10 change moves by more than tol / 10.
      PetscCall(twin(0));
      if (RelDiff(m[0], m[1]) <= 0.1 * o.tol) {
        pt->mcr_error = est;
        pt->mcr_spread = 0;
        pt->predictable = 1;
        PetscFunctionReturn(0);
      }
    }
  }
  // The twins at the scene's step
  for (PetscInt j = (PetscInt)m.size() - 1; j < o.twins; j++) { PetscCall(twin(j)); }
  const auto [lo, hi] = std::minmax_element(m.begin(), m.end());
  PetscReal mean = 0;
  for (PetscReal x : m) mean += x;
  mean /= (PetscReal)m.size();
  if ((*hi - *lo) / std::abs(mean) > o.tol) {
    pt->mcr = mean; // one sample would pretend to a precision the point does not have
    pt->mcr_spread = *hi - *lo;
    pt->mcr_error = std::numeric_limits<PetscReal>::quiet_NaN();
    pt->predictable = 0;
    PetscFunctionReturn(0);
  }
  // Predictable at this tolerance after all (a 0-1 test false alarm, or a slow
  // convergence): the ladder's finest run and its estimate (mcr_error > tol
  // flags a point the halvings did not bring to the tolerance).
  if (!ladder_done) PetscCall(ladder());
  pt->mcr = finest;
  pt->mcr_spread = 0;
  pt->mcr_error = converged ? est : std::max(est, std::nextafter(o.tol, PETSC_MAX_REAL)); // > tol: not converged
  pt->predictable = 1;
  PetscFunctionReturn(0);
}

} // namespace nltopo
