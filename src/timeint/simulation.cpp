#include "timeint/simulation.hpp"
#include "core/cost.hpp"
#include "core/errors.hpp"
#include "core/log.hpp"
#include "core/option_table.hpp"
#include "core/signals.hpp"
#include "core/ts_traits.hpp"
#include "diagnostics/mcr.hpp"
#include "diagnostics/rms_window.hpp"
#include "timeint/ts_rkn.hpp"
#include "timeint/ts_symsplit.hpp"
#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>

namespace nltopo {

// The -sim_* block; the TS itself reads -sim_ts_*.
static const auto &kSimulationTable =
    DeclareOptionTable<SimulationOptions>("sim_", "Forced simulation (TS options: -sim_ts_*)", [](OptionTable<SimulationOptions> &t) {
      t.Real("t_final", &SimulationOptions::t_final, Closed(1e-6, 1e9), "Simulated time")
          .Real("sample_dt", &SimulationOptions::sample_dt, Closed(0, 1e9), "Spacing of stored samples of u and E (0: none)", OptionClass::Extent)
          .Real("progress", &SimulationOptions::progress, Closed(0, 1e7), "Print a progress line every this many wall seconds (0: never)",
                OptionClass::Bookkeeping)
          .Real("dt_quartic_energy", &SimulationOptions::dt_quartic_energy, Closed(0, 1e12),
                "Fixed-step types (symsplit, basicsymplectic): at a run energy E above this, -sim_ts_dt is scaled by (this / E)^(1/4), "
                "as the hardened bonds' frequencies grow (E: E* of a forced run, else the initial energy; 0: off)");
    });

PetscErrorCode SimulationOptionsFromOptions(MPI_Comm comm, SimulationOptions *o)
{
  PetscFunctionBeginUser;
  PetscCall(kSimulationTable.Read(comm, o));
  // every sample is kept in memory (E, and u in the simulate study)
  PetscCheck(o->sample_dt == 0 || o->t_final / o->sample_dt <= 1e7, comm, PETSC_ERR_USER,
             "-sim_t_final / -sim_sample_dt must be at most 1e7 samples, got %g / %g", (double)o->t_final, (double)o->sample_dt);
  PetscFunctionReturn(0);
}

// The initial step of every run (-sim_ts_dt overrides it).
static const PetscReal kInitialStep = 0.01;

PetscReal QuarticStepFactor(const SimulationOptions &o, PetscReal energy)
{
  return o.dt_quartic_energy > 0 && energy > o.dt_quartic_energy ? std::pow(o.dt_quartic_energy / energy, 0.25) : 1;
}

PetscErrorCode SimulationGivenStep(PetscReal *dt)
{
  PetscFunctionBeginUser;
  *dt = kInitialStep;
  PetscCall(PetscOptionsGetReal(NULL, NULL, "-sim_ts_dt", dt, NULL));
  PetscFunctionReturn(0);
}

namespace {

// The energy of the TS solution z at (t, step), computed once: the event
// indicator and the post-step see the same state (the code that changes z in
// place at the same t, the cut-off inside a step, sets t anew).
class EnergyCache {
public:
  PetscErrorCode At(const EffectList &fx, TS ts, PetscReal t, Vec z, EnergyParts *e)
  {
    PetscObjectId id;
    PetscInt step;
    PetscFunctionBeginUser;
    PetscCall(PetscObjectGetId((PetscObject)z, &id));
    PetscCall(TSGetStepNumber(ts, &step));
    if (id != id_ || step != step_ || t != t_) {
      PetscCall(fx.Energy(z, &e_));
      id_ = id;
      step_ = step;
      t_ = t;
    }
    *e = e_;
    PetscFunctionReturn(0);
  }

private:
  PetscObjectId id_ = 0;
  PetscInt step_ = -1;
  PetscReal t_ = -1;
  EnergyParts e_;
};

// The sink's samples at t = k sample_dt: at each step end, those the step
// passed, on the step's interpolant (or the step end itself, for a type
// without one), with their energy.
class Sampler {
public:
  Sampler(const EffectList &fx, SampleSink *sink, const SimulationOptions &o) : fx_(fx), sink_(sink), dt_(o.sample_dt), t_final_(o.t_final)
  {
    // a continued run's samples follow the earlier run's (which took t = t_start)
    if (o.t_start > 0 && o.sample_dt > 0) next_ = (PetscInt)std::floor(o.t_start / o.sample_dt + 1e-9) + 1;
    if (sink_ && dt_ > 0) sink_->Reserve(std::max<PetscInt>(0, (PetscInt)std::floor(t_final_ / dt_ * (1 + 1e-12)) + 1 - next_));
  }
  void WithoutInterpolant() { interpolate_ = false; }
  // The samples up to the state z (energy parts e) at time t; t_off < 0
  // while the forcing is on.
  PetscErrorCode Through(TS ts, PetscReal t, Vec z, const EnergyParts &e, PetscReal t_off)
  {
    PetscFunctionBeginUser;
    if (!sink_ || dt_ <= 0) PetscFunctionReturn(0);
    for (;; next_++) {
      const PetscReal tk = next_ * dt_;
      if (tk > t_final_ * (1 + 1e-12) || tk > t + 1e-9 * dt_) break;
      if (!sink_->Wants(tk, t_off)) continue;
      if (interpolate_ && std::abs(tk - t) > 1e-12 * (1 + t)) {
        EnergyParts es;
        if (!zs_) PetscCall(VecDuplicate(z, zs_.out()));
        PetscCall(TSInterpolate(ts, tk, zs_));
        PetscCall(fx_.Energy(zs_, &es));
        PetscCall(sink_->Sample(tk, zs_, es));
      } else {
        PetscCall(sink_->Sample(interpolate_ ? tk : t, z, e));
      }
    }
    PetscFunctionReturn(0);
  }

private:
  const EffectList &fx_;
  SampleSink *sink_;
  PetscReal dt_, t_final_;
  PetscInt next_ = 0;
  bool interpolate_ = true;
  OwnedVec zs_; // the interpolated sample state
};

// A progress line on rank 0 every interval wall seconds (long runs say where they are).
class ProgressLine {
public:
  ProgressLine(MPI_Comm comm, PetscReal interval, PetscReal t_final) : comm_(comm), interval_(interval), t_final_(t_final) {}
  PetscErrorCode Start()
  {
    PetscFunctionBeginUser;
    PetscCall(PetscTime(&wall0_));
    wall_last_ = wall0_;
    PetscFunctionReturn(0);
  }
  PetscErrorCode Step(TS ts, PetscReal t, const EnergyParts &e, bool forcing)
  {
    PetscLogDouble now;
    PetscInt step;
    PetscFunctionBeginUser;
    if (interval_ <= 0) PetscFunctionReturn(0);
    PetscCall(PetscTime(&now));
    if (now - wall_last_ < interval_) PetscFunctionReturn(0);
    PetscCall(TSGetStepNumber(ts, &step));
    wall_last_ = now;
    const double frac = t / t_final_, el = now - wall0_;
    PetscCall(PetscPrintf(comm_, "  [simulate] t = %.6g / %g (%.1f %%), %" PetscInt_FMT " steps, E = %.6g, %s, %.0f s elapsed, ETA %.0f s\n", (double)t,
                          (double)t_final_, 100 * frac, step, (double)e.Total(), forcing ? "forcing on" : "forcing off", el,
                          frac > 0 ? el * (1 - frac) / frac : 0.0));
    PetscFunctionReturn(0);
  }

private:
  MPI_Comm comm_;
  PetscReal interval_, t_final_;
  PetscLogDouble wall0_ = 0, wall_last_ = 0;
};

// Finding where E reaches E* inside a step, on the step's interpolant.
class CrossingFinder {
public:
  CrossingFinder(const EffectList &fx, PetscReal estar) : fx_(fx), estar_(estar) {}
  // E crossed E* during the last step [t_prev, t]: the crossing time on the
  // step's interpolant, by bisection to a relative energy tolerance of 1e-10
  // (that of the event). A fixed-step method cannot use a TS event here: a
  // shortened step is another discretisation, whose energy need not cross E*
  // in the same interval (the event then shrinks the step forever).
  PetscErrorCode Locate(TS ts, PetscReal lo, PetscReal hi, PetscReal *t_off, EnergyParts *e_off)
  {
    PetscFunctionBeginUser;
    PetscCall(Scratch(ts));
    for (int it = 0; it < 200 && hi - lo > 1e-14 * (1 + hi); it++) {
      const PetscReal mid = 0.5 * (lo + hi);
      PetscCall(TSInterpolate(ts, mid, zs_));
      PetscCall(fx_.Energy(zs_, e_off));
      const PetscReal g = e_off->Total() / estar_ - 1;
      if (std::abs(g) <= 1e-10) {
        lo = hi = mid;
        break;
      }
      (g < 0 ? lo : hi) = mid;
    }
    *t_off = hi;
    PetscCall(TSInterpolate(ts, hi, zs_));
    PetscCall(fx_.Energy(zs_, e_off));
    PetscFunctionReturn(0);
  }

  // The first time in the last step [t_prev, t] at which E reaches E*, looking
  // also inside the step: the driven energy oscillates at 2 omega_ext, so a
  // step longer than a fraction of pi / omega_ext (rkn's, at low E*) can hold a
  // whole excursion above E* while E < E* at both ends, which a test at step
  // ends (the TS event, the post-step check) misses. E is sampled on the
  // step's interpolant every (pi / omega_ext) / 8 at most, so a peak is seen
  // to within 1 - cos(pi / 8) = 8 % of the oscillation's amplitude (steps
  // shorter than that get no inner samples); *found is false when no sample
  // reaches E*.
  PetscErrorCode Scan(TS ts, PetscReal t_prev_step, PetscReal t, bool *found, PetscReal *t_off, EnergyParts *e_off)
  {
    PetscFunctionBeginUser;
    *found = false;
    const PetscReal spacing = PETSC_PI / (8 * fx_.Burst()->Omega());
    const PetscInt k = (PetscInt)std::floor((t - t_prev_step) / spacing);
    PetscReal lo = t_prev_step;
    if (k > 0) PetscCall(Scratch(ts));
    for (PetscInt i = 1; i <= k; i++) {
      const PetscReal ti = t_prev_step + i * (t - t_prev_step) / (k + 1);
      PetscCall(TSInterpolate(ts, ti, zs_));
      PetscCall(fx_.Energy(zs_, e_off));
      if (e_off->Total() >= estar_) {
        PetscCall(Locate(ts, lo, ti, t_off, e_off));
        *found = true;
        break;
      }
      lo = ti;
    }
    PetscFunctionReturn(0);
  }

private:
  PetscErrorCode Scratch(TS ts)
  {
    Vec sol;
    PetscFunctionBeginUser;
    if (zs_) PetscFunctionReturn(0);
    PetscCall(TSGetSolution(ts, &sol));
    PetscCall(VecDuplicate(sol, zs_.out()));
    PetscFunctionReturn(0);
  }
  const EffectList &fx_;
  PetscReal estar_;
  OwnedVec zs_; // the interpolated state
};

struct Run {
  const Lattice *lat;
  const EffectList *fx;
  Rhs rhs;
  SimulationResult *r;
  bool keep_state; // keep the state at the cut-off (SimulationOptions::keep_cutoff_state)
  PetscReal estar;
  bool event_mode = false, interpolate = true;
  bool locate_in_step = false;          // find the cut-off on the step's interpolant (fixed-step symsplit)
  bool rk_stages = false;               // the window integrals on each step's stages (explicit Runge-Kutta tableau)
  PetscReal burst_end = PETSC_MAX_REAL; // abort_if_missed: stop here if E* was missed
  OwnedVec zcut;                        // the state at a cut-off located inside a step
  EnergyCache energy;
  CrossingFinder crossing;
  RmsWindow window; // the RMS / energy-ratio window after the cut-off
  Sampler sampler;
  ProgressLine progress;

  Run(const EffectList &e, const SimulationOptions &o, SampleSink *s, SimulationResult *res)
      : lat(&e.Lat()), fx(&e), rhs(e), r(res), keep_state(o.keep_cutoff_state), estar(e.Burst() ? e.Burst()->EnergyStar() : 0), crossing(e, estar), window(e),
        sampler(e, s, o), progress(e.Lat().Comm(), o.progress, o.t_final)
  {
  }

  PetscErrorCode CutOff(PetscReal t, Vec z)
  {
    PetscFunctionBeginUser;
    if (keep_state) {
      if (!r->z_off) PetscCall(VecDuplicate(z, r->z_off.out()));
      PetscCall(VecCopy(z, r->z_off));
    }
    rhs.DropForcing();
    r->t_off = t;
    r->reached = true;
    r->window_start = t;
    window.Restart(); // the window starts at t_off
    PetscFunctionReturn(0);
  }
};

// The cut-off at the end of a step with the forcing on (when no TS event
// locates it): E reached E* inside the step or at its end. A crossing inside
// the step moves the run back to it (*t, z, *e): the samples before it come
// from this step, forcing on; the run goes on from the crossing, free.
PetscErrorCode CutOffAtStepEnd(TS ts, Run *run, PetscReal *t, Vec z, EnergyParts *e)
{
  bool inside = false; // E reached E* inside the step, below it at the step's end
  PetscReal t_off = 0;
  EnergyParts e_off;
  PetscFunctionBeginUser;
  if (run->interpolate) {
    PetscReal tp;
    PetscCall(TSGetPrevTime(ts, &tp));
    PetscCall(run->crossing.Scan(ts, tp, *t, &inside, &t_off, &e_off));
    if (!inside && !run->event_mode && e->Total() >= run->estar && run->locate_in_step) PetscCall(run->crossing.Locate(ts, tp, *t, &t_off, &e_off));
  }
  if (!inside && (run->event_mode || e->Total() < run->estar)) PetscFunctionReturn(0);
  if (run->locate_in_step || inside) {
    if (!run->zcut) PetscCall(VecDuplicate(z, run->zcut.out()));
    PetscCall(TSInterpolate(ts, t_off, run->zcut));
    PetscCall(run->sampler.Through(ts, t_off, run->zcut, e_off, run->r->t_off));
    PetscCall(VecCopy(run->zcut, z));
    PetscCall(TSSetTime(ts, t_off));
    PetscCall(TSRestartStep(ts));
    *t = t_off;
    *e = e_off;
  }
  PetscCall(run->CutOff(*t, z));
  PetscFunctionReturn(0);
}

PetscErrorCode RhsFunction(TS ts, PetscReal t, Vec z, Vec f, void *ctx)
{
  PetscFunctionBeginUser;
  PetscCall(static_cast<Run *>(ctx)->rhs.Evaluate(t, z, f));
  PetscFunctionReturn(0);
}

PetscErrorCode RhsJacobian(TS ts, PetscReal t, Vec z, Mat A, Mat P, void *ctx)
{
  PetscFunctionBeginUser;
  PetscCall(static_cast<Run *>(ctx)->fx->AssembleStateJacobian(z, P));
  if (A != P) {
    PetscCall(MatAssemblyBegin(A, MAT_FINAL_ASSEMBLY));
    PetscCall(MatAssemblyEnd(A, MAT_FINAL_ASSEMBLY));
  }
  PetscFunctionReturn(0);
}

PetscErrorCode PositionRate(TS ts, PetscReal t, Vec p, Vec qdot, void *ctx)
{
  PetscFunctionBeginUser;
  PetscCall(VecCopy(p, qdot)); // unit masses: q' = p
  PetscFunctionReturn(0);
}

PetscErrorCode MomentumRate(TS ts, PetscReal t, Vec q, Vec pdot, void *ctx)
{
  PetscFunctionBeginUser;
  PetscCall(static_cast<Run *>(ctx)->rhs.Momentum(t, q, pdot));
  PetscFunctionReturn(0);
}

PetscErrorCode RunAcceleration(TS ts, PetscReal t, Vec z, PetscScalar *a, void *ctx)
{
  PetscFunctionBeginUser;
  PetscCall(static_cast<Run *>(ctx)->rhs.Acceleration(t, z, a));
  PetscFunctionReturn(0);
}

// The rate of the window's quadrature states (the TS's quadrature TS).
PetscErrorCode WindowRate(TS quad, PetscReal t, Vec z, Vec rate, void *ctx)
{
  PetscFunctionBeginUser;
  PetscCall(static_cast<RmsWindow *>(ctx)->Integrand(z, rate));
  PetscFunctionReturn(0);
}

PetscErrorCode CutOffIndicator(TS ts, PetscReal t, Vec z, PetscScalar *fv, void *ctx)
{
  Run *run = static_cast<Run *>(ctx);
  PetscFunctionBeginUser;
  if (run->rhs.Forcing()) {
    EnergyParts e;
    PetscCall(run->energy.At(*run->fx, ts, t, z, &e));
    fv[0] = e.Total() / run->estar - 1; // relative, so the event tolerance means the same at any E*
  } else {
    fv[0] =
        -1.0; // after the cut-off the event can never fire again (it fires on upward crossings only, and a cut-off found inside a step leaves a negative value behind)
  }
  PetscFunctionReturn(0);
}

PetscErrorCode CutOffEvent(TS ts, PetscInt nev, PetscInt list[], PetscReal t, Vec z, PetscBool forward, void *ctx)
{
  Run *run = static_cast<Run *>(ctx);
  PetscFunctionBeginUser;
  if (run->rhs.Forcing()) {
    PetscCall(run->CutOff(t, z));
    PetscCall(TSRestartStep(ts)); // FSAL schemes must not reuse a stage computed with the forcing on
  }
  PetscFunctionReturn(0);
}

// An explicit Runge-Kutta step inside the window: the window integrals on its
// stages with the tableau's weights b, to the order of the method. (PETSc's
// own quadrature TS for rk also subtracts the rejected attempts, which it
// never added.)
PetscErrorCode WindowOnStages(TS ts, Run *run, PetscReal t)
{
  PetscInt s, ns;
  const PetscReal *b;
  Vec *Y;
  PetscReal tp;
  PetscFunctionBeginUser;
  if (!run->rk_stages) PetscFunctionReturn(0);
  PetscCall(TSRKGetTableau(ts, &s, NULL, &b, NULL, NULL, NULL, NULL, NULL));
  PetscCall(TSGetStages(ts, &ns, &Y));
  PetscCall(TSGetPrevTime(ts, &tp));
  PetscCall(run->window.AddStages(t - tp, std::min(s, ns), b, Y));
  PetscFunctionReturn(0);
}

// Every step end: the stop signal, the divergence check, the cut-off, then
// the step-end sinks (window, samples, progress line).
PetscErrorCode PostStep(TS ts)
{
  Run *run;
  PetscReal t;
  PetscInt step;
  Vec z;
  EnergyParts e;
  PetscFunctionBeginUser;
  PetscCall(TSGetApplicationContext(ts, &run));
  PetscCall(TSGetStepNumber(ts, &step));
  PetscCall(CheckInterruptAtStep(run->lat->Comm(), step)); // a stop signal ends the run here
  PetscCall(TSGetTime(ts, &t));
  PetscCall(TSGetSolution(ts, &z));
  PetscCall(run->energy.At(*run->fx, ts, t, z, &e));
  PetscCheck(std::isfinite(e.Total()), run->lat->Comm(), PETSC_ERR_FP,
             "non-finite state at t = %g: the integration diverged (reduce -sim_ts_dt or tighten -sim_ts_rtol)", (double)t);
  PetscCall(WindowOnStages(ts, run, t));
  if (run->rhs.Forcing()) {
    run->r->energy_peak = std::max(run->r->energy_peak, e.Total());
    PetscCall(CutOffAtStepEnd(ts, run, &t, z, &e));
  }
  if (run->rhs.Forcing() && t >= run->burst_end) { // E* missed: the caller retries with a larger S
    run->r->aborted = true;
    PetscCall(TSSetConvergedReason(ts, TS_CONVERGED_USER));
  }
  PetscCall(run->window.Step(t, z, e, &run->r->window_start));
  PetscCall(run->sampler.Through(ts, t, z, e, run->r->t_off));
  PetscCall(run->progress.Step(ts, t, e, run->rhs.Forcing()));
  PetscFunctionReturn(0);
}

// The TS of the run: -sim_ts_* over rk 5dp at rtol = atol = 1e-8, the
// right-hand side, the state Jacobian for the types that solve with it, and
// the window integrals as quadrature states (carried by the types that
// integrate a quadrature TS: PETSc's rk, nltopo's rkn).
PetscErrorCode CreateRunTS(const EffectList &fx, const SimulationOptions &o, Run *run, TS *ts, OwnedMat &J)
{
  const Lattice &lat = fx.Lat();
  TSType type;
  const TSTraits *traits;
  TS quad;
  Vec q;
  PetscErrorCode (*tableau)(void) = NULL, (*quadrature)(void) = NULL;
  PetscFunctionBeginUser;
  PetscCall(TSCreate(lat.Comm(), ts));
  PetscCall(TSSetOptionsPrefix(*ts, "sim_"));
  PetscCall(TSSetApplicationContext(*ts, run));
  PetscCall(TSSetProblemType(*ts, TS_NONLINEAR));
  PetscCall(TSSetType(*ts, TSDefaultType("sim_")));
  PetscCall(TSRKSetType(*ts, TSRK5DP)); // rk's tableau unless -sim_ts_rk_type (no-op for other types)
  PetscCall(TSSetRHSFunction(*ts, NULL, RhsFunction, run));
  PetscCall(TSSetAcceleration(*ts, RunAcceleration, run)); // symsplit, rkn: raw-array accelerations
  PetscCall(TSSetTolerances(*ts, 1e-8, NULL, 1e-8, NULL));
  PetscCall(TSSetExactFinalTime(*ts, TS_EXACTFINALTIME_MATCHSTEP));
  PetscCall(TSSetMaxTime(*ts, o.t_final));
  PetscCall(TSSetMaxSteps(*ts, PETSC_MAX_INT));
  PetscCall(TSSetTimeStep(*ts, kInitialStep)); // -sim_ts_dt overrides (the fixed step of basicsymplectic)
  PetscCall(TSSetErrorIfStepFails(*ts, PETSC_FALSE));
  PetscCall(TSSetPostStep(*ts, PostStep));
  PetscCall(TSSetFromOptions(*ts));
  PetscCall(TSGetType(*ts, &type));
  PetscCall(TSGetTraits(*ts, &traits)); // a type the integrator table lacks is refused here
  if (!traits->explicit_step) {         // the state Jacobian only for the types that solve with it
    PetscCall(lat.CreateStateMatrix(J.out()));
    PetscCall(TSSetRHSJacobian(*ts, J, J, RhsJacobian, run));
  }
  if (traits->position_only) {
    const std::string who = std::string("-sim_ts_type ") + type;
    PetscCall(fx.RequirePositionOnly(who.c_str()));
  }
  // The window integrals: on the stages of an explicit Runge-Kutta tableau,
  // as a quadrature TS where the type integrates one forward and rolls it
  // back with the step (rkn), else over the step ends.
  PetscCall(PetscObjectQueryFunction((PetscObject)*ts, "TSRKGetTableau_C", &tableau));
  PetscCall(PetscObjectQueryFunction((PetscObject)*ts, "TSForwardQuadratureRollsBack_C", &quadrature));
  run->rk_stages = tableau != NULL;
  if (!tableau && quadrature) {
    PetscCall(run->window.Integrals(&q));
    PetscCall(TSCreateQuadratureTS(*ts, PETSC_TRUE, &quad));
    PetscCall(TSSetRHSFunction(quad, NULL, WindowRate, &run->window));
    PetscCall(TSSetSolution(quad, q));
  }
  PetscFunctionReturn(0);
}

// More fixed steps than any run can take (days at a microsecond a step).
static const double kMaxFixedSteps = 1e12;

// The fixed step of basicsymplectic and symsplit (times dt_scale and the
// quartic-energy factor), shortened to divide the run into equal steps.
PetscErrorCode SetFixedStep(const EffectList &fx, const SimulationOptions &o, Run *run, TS ts, Vec z, bool symplectic, bool splitting)
{
  const Lattice &lat = fx.Lat();
  const ToneBurst *forcing = fx.Burst();
  MPI_Comm comm = lat.Comm();
  PetscFunctionBeginUser;
  if (symplectic || splitting) {
    // The fixed step times dt_scale (the sweep's accuracy ladder) and, above
    // E_q, (E_q / E)^(1/4): in the quartic regime a bond's frequency grows as
    // E^(1/4) (V ~ Gamma d^4 / 4 at amplitude d ~ E^(1/4)), so this keeps
    // h omega, and a fixed-step scheme's error per period, at its E_q level.
    PetscReal scale = o.dt_scale, dt;
    if (o.dt_quartic_energy > 0) {
      PetscReal E;
      if (forcing && forcing->Present()) E = forcing->EnergyStar();
      else {
        EnergyParts e;
        PetscCall(fx.Energy(z, &e));
        E = e.Total();
      }
      scale *= QuarticStepFactor(o, E);
    }
    PetscCall(TSGetTimeStep(ts, &dt));
    if (o.dt_base > 0) dt = o.dt_base;
    // a step so short that the run could never end (a tiny -sim_dt_quartic_energy) is refused, not run
    const double steps = (double)(o.t_final - o.t_start) / (dt * scale);
    PetscCheck(std::isfinite(steps) && steps <= kMaxFixedSteps, comm, PETSC_ERR_USER,
               "-sim_ts_dt %g, scaled by %g (-sim_dt_quartic_energy %g), needs %.3g steps for -sim_t_final %g: more than %.0e; raise "
               "-sim_ts_dt or -sim_dt_quartic_energy",
               (double)dt, (double)scale, (double)o.dt_quartic_energy, steps, (double)o.t_final, kMaxFixedSteps);
    if (scale != 1 || o.dt_base > 0) PetscCall(TSSetTimeStep(ts, dt * scale));
  }
  if (splitting) {
    // Fixed step, shortened to divide the run into equal steps; the cut-off is
    // located by the event below (symsplit rolls back) and samples interpolated.
    PetscReal dt;
    PetscCall(TSGetTimeStep(ts, &dt));
    const PetscReal span = o.t_final - o.t_start;
    PetscCheck(dt > 0 && dt <= span, comm, PETSC_ERR_USER, "-sim_ts_dt must lie in (0, -sim_t_final], got %g", (double)dt);
    PetscCall(TSSetTimeStep(ts, span / std::ceil(span / dt - 1e-9)));
  }
  if (symplectic) {
    // Fixed step dividing t_final (the type ignores MATCHSTEP), split RHS.
    PetscReal dt;
    PetscCall(TSGetTimeStep(ts, &dt));
    const PetscReal span = o.t_final - o.t_start;
    PetscCheck(dt > 0 && dt <= span, comm, PETSC_ERR_USER, "-sim_ts_dt must lie in (0, -sim_t_final], got %g", (double)dt);
    const PetscInt n = (PetscInt)std::ceil(span / dt - 1e-9);
    PetscCall(TSSetTimeStep(ts, span / n));
    PetscCall(TSSetMaxSteps(ts, n));
    PetscCall(TSRHSSplitSetIS(ts, "position", lat.PositionIS()));
    PetscCall(TSRHSSplitSetIS(ts, "momentum", lat.MomentumIS()));
    PetscCall(TSRHSSplitSetRHSFunction(ts, "position", NULL, PositionRate, run));
    PetscCall(TSRHSSplitSetRHSFunction(ts, "momentum", NULL, MomentumRate, run));
  }
  PetscFunctionReturn(0);
}

// Configure: the TS, its step, and how the cut-off is found (a TS event where
// the type rolls back a step, on the interpolant for symsplit, after each step
// otherwise).
PetscErrorCode Configure(const EffectList &fx, const SimulationOptions &o, Run *run, TS *ts, OwnedMat &J, Vec z)
{
  const TSTraits *traits;
  PetscFunctionBeginUser;
  PetscCall(CreateRunTS(fx, o, run, ts, J));
  PetscCall(TSGetTraits(*ts, &traits));
  // fixed steps on the split right-hand side (basicsymplectic) or on the acceleration (symsplit)
  const bool symplectic = traits->fixed_step && traits->split_rhs, splitting = traits->fixed_step && !traits->split_rhs;
  PetscCall(SetFixedStep(fx, o, run, *ts, z, symplectic, splitting));
  if (symplectic) {
    run->interpolate = false;
    run->sampler.WithoutInterpolant();
  } else if (run->rhs.Forcing() && splitting) {
    run->locate_in_step = true;
  } else if (run->rhs.Forcing() && traits->rolls_back) {
    // Locate the cut-off E(t) = E* (relative tolerance 1e-10) with a TS event,
    // registered after the step size is final (guide, pitfall a). Types that
    // cannot roll back a step (euler, ssp, ...) check after every step instead.
    PetscInt dir = 1;
    PetscBool term = PETSC_FALSE;
    PetscReal vtol = 1e-10;
    PetscCall(TSSetEventHandler(*ts, 1, &dir, &term, CutOffIndicator, CutOffEvent, run));
    PetscCall(TSSetEventTolerances(*ts, PETSC_DECIDE, &vtol));
    run->event_mode = true;
  }
  PetscFunctionReturn(0);
}

// Integrate: the first sample and window state at t_start, then the solve;
// any failure inside it (a NaN caught by TSAdapt, a diverged implicit step,
// the post-step's check) is reported once, with the time.
PetscErrorCode Integrate(const SimulationOptions &o, Run *run, TS ts, Vec z)
{
  MPI_Comm comm = run->lat->Comm();
  TSConvergedReason reason;
  PetscReal t;
  PetscFunctionBeginUser;
  {
    EnergyParts e0;
    PetscCall(run->fx->Energy(z, &e0));
    PetscCall(run->window.Step(o.t_start, z, e0, &run->r->window_start));
    PetscCall(run->sampler.Through(ts, o.t_start, z, e0, run->r->t_off));
  }
  PetscCall(TSSetTime(ts, o.t_start));
  PetscCall(TSSetStepNumber(ts, 0));
  PetscCall(run->progress.Start());
  PetscErrorCode ierr;
  char msg[512];
  PetscCall(CaptureError([&]() { return TSSolve(ts, z); }, &ierr, msg, sizeof msg));
  PetscCall(CostRecordSolve(ts, run->rhs.Counters().rhs));       // the work, also of a failed solve
  PetscCheck(!IsInterrupt(ierr), comm, PETSC_ERR_SIG, "%s", ""); // stopped by a signal: passed on, silent
  PetscCall(TSGetTime(ts, &t));
  PetscCheck(!ierr, comm, PETSC_ERR_NOT_CONVERGED, "time integration failed at t = %g: %s", (double)t, msg);
  PetscCall(TSGetConvergedReason(ts, &reason));
  PetscCheck(reason >= 0, comm, PETSC_ERR_NOT_CONVERGED, "time integration failed at t = %g: %s (see -sim_ts_* options)", (double)t,
             TSConvergedReasons[reason]);
  PetscCheck(t >= o.t_final * (1 - 1e-10) || run->r->aborted, comm, PETSC_ERR_NOT_CONVERGED, "time integration stopped at t = %g before -sim_t_final %g",
             (double)t, (double)o.t_final);
  PetscFunctionReturn(0);
}

// Collect: steps, the window's RMS, MCR and ratio, the final energy and state.
PetscErrorCode Collect(Run *run, TS ts, OwnedVec &z)
{
  SimulationResult *r = run->r;
  EnergyParts e;
  PetscFunctionBeginUser;
  PetscCall(TSGetStepNumber(ts, &r->steps));
  PetscCall(TSGetStepRejections(ts, &r->rejected));
  PetscCall(PetscLogEventBegin(Log().diagnostics, 0, 0, 0, 0));
  PetscCall(DMCreateGlobalVector(run->lat->SiteDM(), r->rms.out()));
  PetscCall(PetscObjectSetName((PetscObject)r->rms.get(), "rms"));
  PetscCall(run->window.Finish(r->window_start, r->rms, &r->nl_ratio));
  PetscCall(Mcr(r->rms, &r->mcr));
  PetscCall(PetscLogEventEnd(Log().diagnostics, 0, 0, 0, 0));
  PetscCall(run->fx->Energy(z, &e));
  r->energy_final = e.Total();
  r->counters = run->rhs.Counters();
  r->z_final = std::move(z);
  PetscFunctionReturn(0);
}

} // namespace

PetscErrorCode AfterCutoffSamples::Sample(PetscReal t, Vec z, const EnergyParts &e)
{
  const PetscScalar *a;
  PetscFunctionBeginUser;
  PetscCall(VecGetArrayRead(z, &a));
  u_.insert(u_.end(), a, a + n_);
  PetscCall(VecRestoreArrayRead(z, &a));
  t_.push_back(t);
  PetscFunctionReturn(0);
}

PetscErrorCode SimulateForced(const EffectList &fx, const SimulationOptions &o, SampleSink *sink, SimulationResult *r, PetscInt *rescalings)
{
  ToneBurst *burst = fx.Burst();
  PetscFunctionBeginUser;
  if (!burst) { // no forcing (-force_profile none): one free run
    PetscCall(Simulate(fx, o, NULL, sink, r));
    r->rhs_all_attempts = r->counters.rhs;
    *rescalings = 0;
    PetscFunctionReturn(0);
  }
  const PetscInt retries = burst->AmplitudeFromRule() ? burst->Options().retries : 0;
  SimulationOptions attempt = o;
  PetscInt work = 0;
  PetscReal S_prev = 0, E_prev = 0;
  for (PetscInt k = 0;; k++) {
    attempt.abort_if_missed = k < retries; // the last attempt is a complete run
    if (sink) sink->Restart();
    PetscCall(Simulate(fx, attempt, NULL, sink, r));
    work += r->counters.rhs;
    r->rhs_all_attempts = work;
    if (!r->aborted) {
      *rescalings = r->reached || !burst->Present() ? k : -1;
      PetscFunctionReturn(0);
    }
    // The peak energy grows like S^p: p = 2 in the linear lattice, nearer 1
    // once the hardened lattice detunes from the burst. Take p = 1 after the
    // first miss, then the log-log slope of the last two attempts (clamped to
    // [0.3, 2]), aim 20 % above E*, and at least double S.
    const PetscReal S = burst->Amplitude(), E = std::max(r->energy_peak, PETSC_SMALL * burst->EnergyStar());
    PetscReal p = 1;
    if (k > 0 && E > E_prev && S > S_prev) p = std::min<PetscReal>(2, std::max<PetscReal>(0.3, std::log(E / E_prev) / std::log(S / S_prev)));
    const PetscReal f = std::min<PetscReal>(100, std::max<PetscReal>(2, std::pow(1.2 * burst->EnergyStar() / E, 1 / p)));
    PetscCall(PetscInfo(NULL, "amplitude rule: S = %g reached E_peak = %g < E* = %g by the burst end; p = %g, S x %g\n", (double)S, (double)E,
                        (double)burst->EnergyStar(), (double)p, (double)f));
    S_prev = S;
    E_prev = E;
    burst->ScaleAmplitude(f);
  }
}

PetscErrorCode Simulate(const EffectList &fx, const SimulationOptions &o, Vec z0, SampleSink *sink, SimulationResult *r)
{
  const ToneBurst *forcing = fx.Burst();
  OwnedTS ts;
  OwnedMat J;
  OwnedVec z;
  PetscFunctionBeginUser;
  *r = SimulationResult();
  Run run(fx, o, sink, r);
  // E* missed by the end of the burst (t0 + 3 tau), or by t_final when the
  // burst outlasts the run but its peak t0 lies inside it (low omega_ext); a
  // run that ends before the peak is too short to judge S and is not repeated.
  if (o.abort_if_missed && forcing && forcing->Present()) {
    const PetscReal tb = forcing->T0() + 3 * forcing->Tau();
    if (tb <= o.t_final) run.burst_end = tb;
    else if (forcing->T0() <= o.t_final) run.burst_end = o.t_final * (1 - 1e-12);
  }
  // RMS window when E* is never reached: after the burst (t0 + 3 tau), or the
  // whole run if the burst does not end before t_final (docs/model.md).
  if (run.rhs.Forcing()) {
    const PetscReal tb = forcing->T0() + 3 * forcing->Tau();
    r->window_start = tb < o.t_final ? tb : 0;
  }
  PetscCall(fx.Lat().CreateStateVector(z.out()));
  if (z0) PetscCall(VecCopy(z0, z));
  else PetscCall(VecZeroEntries(z));
  PetscCall(Configure(fx, o, &run, ts.out(), J, z));
  PetscCall(Integrate(o, &run, ts, z));
  PetscCall(Collect(&run, ts, z));
  PetscFunctionReturn(0);
}

} // namespace nltopo
