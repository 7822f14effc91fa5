// Two-parameter continuation of located events (stability/codim2.hpp, issue 37)
// against exact truth: -lattice_cubic is degenerate. With u = lambda w the
// equations of motion at Gamma are those at Gamma lambda^2 for w, and E maps
// to E / lambda^2 at the same omega and multipliers (the fixed-step discrete
// map too: it is equivariant under the scaling). So every event curve in
// (E, Gamma) is E Gamma = const at constant omega.
#include "branch_record.hpp"
#include "core/gather.hpp"
#include "helpers.hpp"
#include "nnm_fixture.hpp"
#include "stability/bifurcation_locator.hpp"
#include "stability/branch_switch.hpp"
#include "stability/codim2.hpp"
#include <cmath>

using namespace nltopo;
using namespace nltopo::test;

namespace {

// The energy maximum (fold, direction +1) of mode 0 of the N = 6 interface
// lattice at Gamma (its E rises to ~66 x 0.5 / Gamma at omega 0.96852, then
// falls: test_bifurcations.cpp), located to 1e-9 in omega; with its orbit.
struct FoldOfMode0 {
  NnmFixture nf;
  BifurcationLocator loc;
  std::vector<BifurcationEvent> ev;
  PetscInt index = -1;
  EventKind kind = EventKind::Fold; // the first event of this kind that begins (fold: an E maximum) is selected
  const char *name = "mode0";       // the branch of ev (messages)
  PetscInt mode = 0;                // the family of this linear mode
  PetscErrorCode Locate(PetscReal Gamma, PetscReal omega_max = 0.9692)
  {
    LatticeParams p;
    p.cells = 1, p.Gamma = Gamma;
    return Locate(p, omega_max, 0.2); // by default just past the fold (omega 0.96852, the same at every Gamma)
  }
  // at any lattice of one cell, continued up to omega_max with steps of at most max_change
  PetscErrorCode Locate(const LatticeParams &p, PetscReal omega_max, PetscReal max_change)
  {
    PetscFunctionBeginUser;
    PetscCall(nf.Setup(p));
    PetscCall(ContinueAndLocate(omega_max, max_change));
    PetscFunctionReturn(0);
  }
  // (on the lattice nf is set up on)
  PetscErrorCode ContinueAndLocate(PetscReal omega_max, PetscReal max_change)
  {
    PetscFunctionBeginUser;
    ContinuationOptions co;
    co.verbose = PETSC_FALSE;
    co.energy_max = 1e3;
    co.omega_max = omega_max;
    co.max_change = max_change;
    Record rec(nf.flow);
    Branch b;
    PetscCall(nf.Continue(mode, co, &b, &rec));
    PetscCall(LocateRecorded(loc, nf.shoot, b, rec, name, &ev));
    for (size_t k = 0; k < ev.size(); k++)
      if (ev[k].kind == kind && ev[k].direction > 0 && index < 0) index = (PetscInt)k;
    PetscFunctionReturn(0);
  }
  // The event of the kind nearest omega (the rule of -cont_codim2), -1 if none.
  PetscInt Nearest(PetscReal omega) const
  {
    PetscInt best = -1;
    for (size_t k = 0; k < ev.size(); k++)
      if (ev[k].kind == kind && (best < 0 || std::abs(ev[k].omega - omega) < std::abs(ev[best].omega - omega))) best = (PetscInt)k;
    return best;
  }
  // The located fold's orbit, as -cont_codim2 starts from it.
  PetscErrorCode Start(Codim2Start *s)
  {
    OwnedVec X, z;
    bool found;
    PetscFunctionBeginUser;
    PetscCall(nf.shoot.CreateUnknowns(X.out()));
    PetscCall(nf.lat.CreateStateVector(z.out()));
    const BifurcationEvent &e = ev[index];
    PetscCall(loc.OrbitAt(e.point, e.sigma, X, &found));
    PetscCheck(found, PETSC_COMM_WORLD, PETSC_ERR_NOT_CONVERGED, "the fold's orbit was not found again");
    PetscCall(nf.shoot.Unpack(X, z, &s->period, &s->beta));
    s->omega = 2 * PETSC_PI / s->period;
    EnergyParts en;
    PetscCall(nf.flow.Effects().Energy(z, &en));
    s->energy = en.Total();
    s->z0.clear();
    PetscCall(AppendStateRow(nf.lat, z, &s->z0));
    PetscCall(BroadcastFromRoot(PETSC_COMM_WORLD, MPIU_REAL, &s->z0));
    PetscFunctionReturn(0);
  }
  // The located event (index) continued in -lattice_cubic over [0.3, 0.8] from Gamma = 0.5.
  PetscErrorCode ContinueInCubic(Codim2Curve *c)
  {
    Codim2Start start;
    Codim2Options o;
    LatticeParams p;
    PetscFunctionBeginUser;
    PetscCall(Start(&start));
    o.parameter = Codim2Parameter::Cubic;
    o.pmin = 0.3, o.pmax = 0.8;
    o.step = 0.05, o.step_max = 0.15;
    o.verbose = PETSC_FALSE;
    p.cells = 1, p.Gamma = 0.5;
    PetscCall(ContinueCodim2(PETSC_COMM_WORLD, p, FlowOptions(), ShootingOptions(), FloquetOptions(), 1, o, ev[index], index, start, name, c));
    PetscFunctionReturn(0);
  }
};

// A period doubling (kind 3). The lattice's own NNM families have none (x(t +
// T/2) = -x(t) makes multipliers near -1 come as quadruplets: docs/continuation.md
// "Branch switching"); the families switched onto at a branch point break that
// symmetry. On the N = 6 lattice, mode 3's first branch point (omega 2.50275,
// E 53.0 at Gamma 0.5) starts a family whose first period doubling (a window
// opening at omega 3.43444, E 223.0) this locates: ev, loc and index are the
// switched family's, so that Start and ContinueInCubic work as for the fold.
struct DoublingOnSwitchedFamily : FoldOfMode0 {
  BifurcationLocator parent_loc;
  PetscErrorCode LocateDoubling(PetscReal Gamma)
  {
    LatticeParams p;
    ContinuationOptions co;
    Branch b, start, fam;
    std::vector<BifurcationEvent> pev;
    SwitchJob job;
    bool found, pinned;
    PetscFunctionBeginUser;
    kind = EventKind::PeriodDoubling, name = "mode3_bp_plus";
    p.cells = 1, p.Gamma = Gamma;
    PetscCall(nf.Setup(p));
    co.verbose = PETSC_FALSE;
    co.energy_max = 60 * 0.5 / Gamma; // past the branch point (E Gamma is its invariant)
    Record rec(nf.flow);
    PetscCall(nf.Continue(3, co, &b, &rec));
    PetscCall(LocateRecorded(parent_loc, nf.shoot, b, rec, "mode3", &pev));
    for (size_t k = 0; k < pev.size() && job.plan.parent.empty(); k++)
      if (pev[k].kind == EventKind::BranchPoint && pev[k].direction > 0) job.plan.parent = "mode3", job.plan.event = (PetscInt)k, job.e = pev[k];
    PetscCheck(!job.plan.parent.empty(), PETSC_COMM_WORLD, PETSC_ERR_NOT_CONVERGED, "mode 3 has no branch point below E %g", (double)co.energy_max);
    PetscCall(nf.shoot.CreateUnknowns(job.Xs.out()));
    PetscCall(parent_loc.OrbitAt(job.e.point, job.e.sigma, job.Xs, &found));
    PetscCheck(found, PETSC_COMM_WORLD, PETSC_ERR_NOT_CONVERGED, "the branch point's orbit was not found again");
    Record frec(nf.flow);
    PetscCall(StartFamily(nf.shoot, job, 0.02, +1, frec, &start, &pinned));
    PetscCheck(pinned, PETSC_COMM_WORLD, PETSC_ERR_NOT_CONVERGED, "no orbit off the branch point");
    co.energy_max = 230 * 0.5 / Gamma; // just past the period doubling
    PetscCall(ContinueBranch(nf.shoot, nullptr, 0, co, "mode3_bp_plus", &fam, &frec, &start));
    PetscCall(LocateRecorded(loc, nf.shoot, fam, frec, "mode3_bp_plus", &ev));
    for (size_t k = 0; k < ev.size(); k++)
      if (ev[k].kind == kind && ev[k].direction > 0 && index < 0) index = (PetscInt)k;
    PetscFunctionReturn(0);
  }
};

// The coupled dimers (dimers.hpp) at gamma, from the linear lattice: lambda_hi =
// Omega_3^2 and kappa = (Omega_3^2 - Omega_2^2) / 2, and the first-order
// averaging prediction of their pitchfork (test_bifurcations.cpp, "the pitchfork
// of two coupled dimers"): Omega^2 = lambda_hi + kappa. On the backbone of mode
// 3, u = a phi cos(Omega t) (phi of unit norm), Omega^2 = lambda_hi + (3/4)
// Gamma a^2 S4 with S4 = sum over stiff bonds of (phi_i - phi_j)^4, and E =
// lambda_hi a^2 / 2: at the pitchfork E* = 2 lambda_hi kappa / (3 Gamma S4).
// Both to O(kappa / Omega^2).
struct DimerAveraging {
  PetscReal lam_hi = 0, kappa = 0, energy = 0;
  explicit DimerAveraging(PetscReal gamma)
  {
    LatticeParams p;
    p.layout = Layout::Right, p.cells = 2, p.gamma = gamma;
    Lattice lat;
    LinearModes modes;
    PCHK(lat.Setup(PETSC_COMM_WORLD, p));
    PCHK(modes.Compute(lat, LinearModesOptions()));
    const auto &w = modes.Omega();
    lam_hi = w[3] * w[3], kappa = (lam_hi - w[2] * w[2]) / 2;
    const std::vector<PetscReal> phi = Gather(modes.Mode(3));
    PetscReal nrm = 0, s4 = 0;
    for (PetscReal x : phi) nrm += x * x;
    for (PetscInt b = 0; b + 1 < p.N(); b++)
      if (p.Stiff(b)) s4 += std::pow((phi[b] - phi[b + 1]) / std::sqrt(nrm), 4);
    energy = 2 * lam_hi * kappa / (3 * p.Gamma * s4);
  }
};

// The pitchfork of the coupled dimers' upper optical NNM (mode 3) at gamma 0.9,
// located as in test_bifurcations.cpp (steps of 0.05, up to Omega^2 = lambda_hi + 3 kappa).
struct DimerPitchfork : FoldOfMode0 {
  PetscErrorCode LocatePitchfork()
  {
    LatticeParams p;
    PetscFunctionBeginUser;
    kind = EventKind::BranchPoint, name = "dimers", mode = 3;
    p.layout = Layout::Right, p.cells = 2, p.gamma = 0.9;
    const DimerAveraging av(p.gamma);
    PetscCall(nf.Setup(p));
    PetscCall(ContinueAndLocate(std::sqrt(av.lam_hi + 1.5 * av.kappa), 0.2));
    PetscFunctionReturn(0);
  }
};

// The exact truth of -lattice_cubic (the file's head) on a curve continued from
// the event at Gamma = 0.5 over [0.3, 0.8]: it spans the range in order of p,
// its test function is 0, and E Gamma and omega are constant along it.
void RequireScaledCurve(const Codim2Curve &c, const char *what)
{
  const size_t n = c.p.size();
  REQUIRE(n >= 6);
  REQUIRE(c.p.front() < 0.36);
  REQUIRE(c.p.back() > 0.7);
  REQUIRE(c.p[c.event_point] == 0.5);
  for (size_t k = 1; k < n; k++) REQUIRE(c.p[k] > c.p[k - 1]);
  const PetscReal EG = c.energy[c.event_point] * c.p[c.event_point], w = c.omega[c.event_point];
  PetscReal worst_eg = 0, worst_w = 0;
  for (size_t k = 0; k < n; k++) {
    worst_eg = std::max(worst_eg, std::abs(c.energy[k] * c.p[k] / EG - 1));
    worst_w = std::max(worst_w, std::abs(c.omega[k] / w - 1));
    REQUIRE(std::abs(c.test[k]) <= 1e-6);
  }
  INFO("worst |E Gamma / (E Gamma)* - 1| " << worst_eg << ", worst |omega / omega* - 1| " << worst_w);
  PCHK(PetscPrintf(PETSC_COMM_WORLD,
                   "  codim2 %s in -lattice_cubic: %zu points, Gamma %.4g .. %.4g, max |E Gamma / (E Gamma)* - 1| = %.1e, max |omega / omega* - 1| = %.1e\n",
                   what, n, (double)c.p.front(), (double)c.p.back(), (double)worst_eg, (double)worst_w));
  REQUIRE(worst_eg <= 1e-8);
  REQUIRE(worst_w <= 1e-8);
}

// An independent one-parameter run's event h of the curve's kind, at the
// curve's last p: at the curve's omega to 1e-6 and its E to 1e-5 relative.
void RequireEventAtCurveEnd(const BifurcationEvent &h, const Codim2Curve &c, const char *what)
{
  const size_t n = c.p.size();
  INFO("one-parameter " << what << " at Gamma " << c.p[n - 1] << ": omega " << h.omega << ", E " << h.energy << "; the curve's " << c.omega[n - 1] << ", "
                        << c.energy[n - 1]);
  REQUIRE(std::abs(h.omega - c.omega[n - 1]) <= 1e-6);
  REQUIRE(std::abs(h.energy - c.energy[n - 1]) <= 1e-5 * h.energy);
  PCHK(PetscPrintf(PETSC_COMM_WORLD, "  one-parameter %s at Gamma %.6g: |omega - curve's| = %.1e, |E / curve's - 1| = %.1e\n", what, (double)c.p[n - 1],
                   (double)std::abs(h.omega - c.omega[n - 1]), (double)std::abs(h.energy / c.energy[n - 1] - 1)));
}

} // namespace

TEST_CASE("codim-2: the energy fold continued in -lattice_cubic lies on E Gamma = const at constant omega, through the one-parameter runs' folds", "[codim2]")
{
  FoldOfMode0 f;
  PCHK(f.Locate(0.5));
  REQUIRE(f.index >= 0);
  const BifurcationEvent &e = f.ev[f.index];
  Codim2Curve c;
  PCHK(f.ContinueInCubic(&c));
  const size_t n = c.p.size();
  INFO("curve " << c.name << ": " << n << " points, p " << c.p.front() << " .. " << c.p.back() << ", " << c.solves << " orbits, " << c.stop_reason);
  REQUIRE(c.name == "fold" + std::to_string(f.index));
  // the event itself: the located fold, to the one-parameter run's bracket
  REQUIRE(std::abs(c.omega[c.event_point] - e.omega) <= 1e-8);
  REQUIRE(std::abs(c.energy[c.event_point] - e.energy) <= 1e-8 * e.energy);
  RequireScaledCurve(c, "fold");
  // at a fold the multiplier +1 is fourfold: the trivial pair and the pair passing +1
  for (size_t k = 0; k < n; k++)
    for (PetscInt j = 0; j < Codim2Curve::kMultipliers; j++)
      REQUIRE(std::hypot(c.mu_re[k * Codim2Curve::kMultipliers + j] - 1, c.mu_im[k * Codim2Curve::kMultipliers + j]) <= 1e-2);
  // an independent one-parameter run at the curve's last p locates the same fold there
  FoldOfMode0 g;
  PCHK(g.Locate(c.p[n - 1]));
  REQUIRE(g.index >= 0);
  const BifurcationEvent &h = g.ev[g.index];
  RequireEventAtCurveEnd(h, c, "fold");
}

TEST_CASE("codim-2: a Hamiltonian-Hopf onset continued in -lattice_cubic lies on E Gamma = const at constant omega, through the one-parameter runs' "
          "onsets",
          "[codim2][once]")
{
  // [once]: its distributed path (the walk, the lattice rebuilt at each p, the multipliers per point; the
  // energy-constrained solve in every branch's first orbit) runs at 2 ranks in the fold case above: at 2 ranks
  // on 6 sites this one costs ~25 s.
  // past the E maximum, the onset at omega 0.96993 (E 62.7 at Gamma 0.5) of an E-E quadruplet (Krein -1, +1).
  // In (E / E*, Gamma / 0.5) the curve is a hyperbola: the corrector, not the predictor, puts the points on it.
  FoldOfMode0 f;
  f.kind = EventKind::HamiltonianHopf;
  PCHK(f.Locate(0.5, 0.9702));
  REQUIRE(f.index >= 0);
  const BifurcationEvent &e = f.ev[f.index];
  Codim2Curve c;
  PCHK(f.ContinueInCubic(&c));
  const size_t n = c.p.size();
  INFO("curve " << c.name << ": " << n << " points, p " << c.p.front() << " .. " << c.p.back() << ", " << c.solves << " orbits, " << c.stop_reason);
  REQUIRE(c.name == "hh" + std::to_string(f.index));
  REQUIRE(std::abs(c.omega[c.event_point] - e.omega) <= 1e-8);
  RequireScaledCurve(c, "Hamiltonian-Hopf");
  // the four colliding multipliers: on the unit circle at the onset (a double pair, two of each), at the event's angle
  for (size_t k = 0; k < n; k++)
    for (PetscInt j = 0; j < Codim2Curve::kMultipliers; j++) {
      const PetscReal re = c.mu_re[k * Codim2Curve::kMultipliers + j], im = c.mu_im[k * Codim2Curve::kMultipliers + j];
      REQUIRE(std::abs(std::hypot(re, im) - 1) <= 1e-3);
      REQUIRE(std::abs(std::abs(std::atan2(im, re)) - std::atan2(e.mu_im, e.mu_re)) <= 1e-3);
    }
  FoldOfMode0 g;
  g.kind = EventKind::HamiltonianHopf;
  LatticeParams q;
  q.cells = 1, q.Gamma = c.p[n - 1];
  PCHK(g.Locate(q, 0.9702, 0.05)); // short steps: the onset follows the fold closely, and the locator's probes fail across it at 0.2
  // (the first onset there may be another: a short bubble near omega 0.954 that the probes of the run at Gamma 0.5 step over)
  const PetscInt hi = g.Nearest(c.omega[n - 1]);
  REQUIRE(hi >= 0);
  const BifurcationEvent &h = g.ev[hi];
  REQUIRE(h.direction == e.direction);
  RequireEventAtCurveEnd(h, c, "onset");
}

TEST_CASE("codim-2: a period doubling continued in -lattice_cubic lies on E Gamma = const at constant omega, through the one-parameter runs' "
          "doublings",
          "[codim2][once]")
{
  // [once]: three continuations and a curve of 30 orbits on a lattice of 6 sites cost ~25 times as much at 2
  // ranks as serially (distributing 12 unknowns); its distributed parts (the walk, the lattice rebuilt at each p,
  // the multipliers per point, which the test function shares with Record) run at 2 ranks in the fold case.
  // on a family switched onto at a branch point (the lattice's own families have none); a window of
  // instability opens there (a real pair leaves through -1): g = b + 1 > 0 below it, < 0 inside
  DoublingOnSwitchedFamily f;
  PCHK(f.LocateDoubling(0.5));
  REQUIRE(f.index >= 0);
  const BifurcationEvent &e = f.ev[f.index];
  REQUIRE(std::abs(e.mu_re + 1) <= 1e-3);
  Codim2Curve c;
  PCHK(f.ContinueInCubic(&c));
  const size_t n = c.p.size();
  INFO("curve " << c.name << ": " << n << " points, p " << c.p.front() << " .. " << c.p.back() << ", " << c.solves << " orbits, " << c.stop_reason);
  REQUIRE(c.name == "pd" + std::to_string(f.index));
  REQUIRE(c.kind == EventKind::PeriodDoubling);
  REQUIRE(std::abs(c.omega[c.event_point] - e.omega) <= 1e-8);
  REQUIRE(std::abs(c.energy[c.event_point] - e.energy) <= 1e-8 * e.energy);
  RequireScaledCurve(c, "period doubling");
  // the pair at -1, the two multipliers nearest it (a Jordan block there: each is off by the root of rounding)
  for (size_t k = 0; k < n; k++)
    for (PetscInt j = 0; j < 2; j++) REQUIRE(std::hypot(c.mu_re[k * Codim2Curve::kMultipliers + j] + 1, c.mu_im[k * Codim2Curve::kMultipliers + j]) <= 1e-2);
  // an independent one-parameter run (parent, branch point, switched family) at the curve's last p
  DoublingOnSwitchedFamily g;
  PCHK(g.LocateDoubling(c.p[n - 1]));
  const PetscInt hi = g.Nearest(c.omega[n - 1]);
  REQUIRE(hi >= 0);
  const BifurcationEvent &h = g.ev[hi];
  REQUIRE(h.direction == e.direction);
  RequireEventAtCurveEnd(h, c, "period doubling");
}

TEST_CASE("codim-2: a branch point continued in -lattice_cubic lies on E Gamma = const at constant omega, through the one-parameter runs' "
          "branch points",
          "[codim2][once]")
{
  // [once]: the branch point's test function and the walk run at 2 ranks in the dimers' case below (this one
  // costs ~50 times its serial time at 2 ranks on 6 sites).
  // mode 3 of the N = 6 interface lattice: its first branch point (omega 2.50275, E 53.0 at Gamma 0.5), where
  // a real pair leaves +1 and the mirror-breaking families of docs/continuation.md "Branch switching" begin
  FoldOfMode0 f;
  f.kind = EventKind::BranchPoint, f.mode = 3, f.name = "mode3";
  LatticeParams q;
  q.cells = 1, q.Gamma = 0.5;
  PCHK(f.Locate(q, 2.51, 0.2));
  REQUIRE(f.index >= 0);
  const BifurcationEvent &e = f.ev[f.index];
  REQUIRE(std::abs(e.mu_re - 1) <= 1e-3);
  Codim2Curve c;
  PCHK(f.ContinueInCubic(&c));
  const size_t n = c.p.size();
  INFO("curve " << c.name << ": " << n << " points, p " << c.p.front() << " .. " << c.p.back() << ", " << c.solves << " orbits, " << c.stop_reason);
  REQUIRE(c.name == "bp" + std::to_string(f.index));
  REQUIRE(c.kind == EventKind::BranchPoint);
  REQUIRE(std::abs(c.omega[c.event_point] - e.omega) <= 1e-8);
  REQUIRE(std::abs(c.energy[c.event_point] - e.energy) <= 1e-8 * e.energy);
  RequireScaledCurve(c, "branch point");
  // the trivial pair and the critical one at +1 (each a Jordan block there: off by the root of rounding)
  for (size_t k = 0; k < n; k++)
    for (PetscInt j = 0; j < Codim2Curve::kMultipliers; j++)
      REQUIRE(std::hypot(c.mu_re[k * Codim2Curve::kMultipliers + j] - 1, c.mu_im[k * Codim2Curve::kMultipliers + j]) <= 1e-2);
  FoldOfMode0 g;
  g.kind = EventKind::BranchPoint, g.mode = 3, g.name = "mode3";
  q.Gamma = c.p[n - 1];
  PCHK(g.Locate(q, 2.51, 0.2));
  const PetscInt hi = g.Nearest(c.omega[n - 1]);
  REQUIRE(hi >= 0);
  const BifurcationEvent &h = g.ev[hi];
  REQUIRE(h.direction == e.direction);
  RequireEventAtCurveEnd(h, c, "branch point");
}

TEST_CASE("codim-2: the energy fold continued in -lattice_gamma passes through the folds of independent one-parameter runs at its ends", "[codim2][once]")
{
  // [once]: the distributed path (the lattice rebuilt at each p, the bordered solve) runs at 2 ranks in the
  // -lattice_cubic case above; at 2 ranks on a lattice of 6 sites this one costs ~20 times its serial time.
  // not degenerate: omega and E Gamma change along this curve (at gamma 0.4 omega 0.96852, E 65.8; at 0.45 about 0.9427, 40.9)
  FoldOfMode0 f;
  PCHK(f.Locate(0.5));
  REQUIRE(f.index >= 0);
  Codim2Start start;
  PCHK(f.Start(&start));
  Codim2Options o;
  o.parameter = Codim2Parameter::Gamma;
  o.pmin = 0.36, o.pmax = 0.45;
  o.verbose = PETSC_FALSE;
  LatticeParams p;
  p.cells = 1, p.Gamma = 0.5;
  Codim2Curve c;
  PCHK(ContinueCodim2(PETSC_COMM_WORLD, p, FlowOptions(), ShootingOptions(), FloquetOptions(), 1, o, f.ev[f.index], f.index, start, "mode0", &c));
  const size_t n = c.p.size();
  REQUIRE(n >= 4);
  REQUIRE(c.p[c.event_point] == 0.4);
  REQUIRE(c.omega.front() > c.omega.back() + 0.02); // the fold moves down in omega as gamma grows
  for (size_t k : {(size_t)0, n - 1}) {
    FoldOfMode0 g;
    LatticeParams q;
    q.cells = 1, q.Gamma = 0.5, q.gamma = c.p[k];
    PCHK(g.Locate(q, c.omega[k] + 7e-4, 0.05)); // just past the fold, as at gamma 0.4; steps that do not cut it (at
                                                // gamma 0.31 the default 0.2 steps over a pair of folds the curve finds)
    REQUIRE(g.index >= 0);
    const BifurcationEvent &h = g.ev[g.index];
    INFO("gamma " << c.p[k] << ": one-parameter fold at omega " << h.omega << ", E " << h.energy << "; the curve's " << c.omega[k] << ", " << c.energy[k]);
    REQUIRE(std::abs(h.omega - c.omega[k]) <= 1e-6);
    REQUIRE(std::abs(h.energy - c.energy[k]) <= 1e-5 * h.energy);
    PCHK(PetscPrintf(PETSC_COMM_WORLD, "  codim2 fold in -lattice_gamma at %.6g: |omega - one-parameter fold's| = %.1e, |E / its - 1| = %.1e\n", (double)c.p[k],
                     (double)std::abs(h.omega - c.omega[k]), (double)std::abs(h.energy / c.energy[k] - 1)));
  }
}

TEST_CASE("codim-2: the pitchfork of the dimer fixture, continued in its coupling, follows the averaging prediction", "[codim2]")
{
  // The coupled dimers' upper optical NNM loses stability where first-order averaging puts it, Omega^2 -
  // lambda_hi = kappa, at E* (DimerAveraging; to O(kappa / Omega^2), test_bifurcations.cpp). -lattice_gamma
  // sets the weak bond k2 = 1 - gamma that couples them (kappa = k2 / 2 to first order), so lambda_hi and
  // kappa move along the curve. lambda_hi + kappa stays near 5 (k1 + k2 = 2), so omega barely moves; E* is
  // proportional to kappa and falls by half over the curve: the curve's E must follow it.
  DimerPitchfork f;
  PCHK(f.LocatePitchfork());
  REQUIRE(f.index >= 0);
  const BifurcationEvent &e = f.ev[f.index];
  Codim2Start start;
  PCHK(f.Start(&start));
  Codim2Options o;
  o.parameter = Codim2Parameter::Gamma;
  o.pmin = 0.86, o.pmax = 0.94;
  o.verbose = PETSC_FALSE;
  LatticeParams p;
  p.layout = Layout::Right, p.cells = 2, p.gamma = 0.9;
  Codim2Curve c;
  PCHK(ContinueCodim2(PETSC_COMM_WORLD, p, FlowOptions(), ShootingOptions(), FloquetOptions(), 1, o, e, f.index, start, "dimers", &c));
  const size_t n = c.p.size();
  INFO("curve " << c.name << ": " << n << " points, p " << c.p.front() << " .. " << c.p.back() << ", " << c.solves << " orbits, " << c.stop_reason);
  REQUIRE(c.name == "bp" + std::to_string(f.index));
  REQUIRE(c.kind == EventKind::BranchPoint);
  REQUIRE(std::abs(c.omega[c.event_point] - e.omega) <= 1e-8);
  REQUIRE(std::abs(c.energy[c.event_point] - e.energy) <= 1e-8 * e.energy);
  REQUIRE(c.event_point >= 2);
  REQUIRE(n - c.event_point >= 3);
  REQUIRE(c.p.front() < 0.87);
  REQUIRE(c.p.back() > 0.93);
  PetscReal worst = 0, worst_e = 0;
  for (size_t k = 0; k < n; k++) {
    if (k) REQUIRE(c.p[k] > c.p[k - 1]);
    REQUIRE(std::abs(c.test[k]) <= 1e-6);
    const DimerAveraging av(c.p[k]);
    const PetscReal onset = (c.omega[k] * c.omega[k] - av.lam_hi) / av.kappa;
    INFO("gamma " << c.p[k] << ": omega " << c.omega[k] << ", E " << c.energy[k] << ", (Omega^2 - lambda_hi) / kappa = " << onset
                  << ", E / E* = " << c.energy[k] / av.energy);
    REQUIRE(std::abs(onset - 1) < 0.05);
    REQUIRE(std::abs(c.energy[k] / av.energy - 1) < 0.05);
    REQUIRE(std::abs(c.energy[k] / av.energy - 1) <= av.kappa / av.lam_hi); // first order: the error is O(kappa / Omega^2)
    worst = std::max(worst, std::abs(onset - 1)), worst_e = std::max(worst_e, std::abs(c.energy[k] / av.energy - 1));
    // the trivial pair and the critical one, at +1
    for (PetscInt j = 0; j < Codim2Curve::kMultipliers; j++)
      REQUIRE(std::hypot(c.mu_re[k * Codim2Curve::kMultipliers + j] - 1, c.mu_im[k * Codim2Curve::kMultipliers + j]) <= 1e-2);
  }
  PCHK(PetscPrintf(PETSC_COMM_WORLD,
                   "  codim2 dimer pitchfork in -lattice_gamma: %zu points, gamma %.4g .. %.4g, max |(Omega^2 - lambda_hi) / kappa - 1| = %.1e, "
                   "max |E / E* - 1| = %.1e\n",
                   n, (double)c.p.front(), (double)c.p.back(), (double)worst, (double)worst_e));
}

TEST_CASE("codim-2: -cont_codim2 items are parsed, and kinds 4 and 6 (no boundaries of stability) refused", "[codim2][serial]")
{
  Codim2Spec s;
  PCHK(ParseCodim2Spec(PETSC_COMM_SELF, "insulated:fold@1.9", &s));
  REQUIRE(s.branch == "insulated");
  REQUIRE(s.kind == EventKind::Fold);
  REQUIRE(s.omega == 1.9);
  PCHK(ParseCodim2Spec(PETSC_COMM_SELF, "mode0:1@2.5", &s));
  REQUIRE(s.branch == "mode0");
  REQUIRE(s.kind == EventKind::Fold);
  PetscPushErrorHandler(PetscReturnErrorHandler, nullptr);
  for (const char *bad : {"insulated", "insulated:fold", "insulated:fold@", "insulated:fold@-1", ":fold@2", "insulated:fold@x", "insulated:kink@2"})
    REQUIRE(ParseCodim2Spec(PETSC_COMM_SELF, bad, &s) == PETSC_ERR_USER);
  PCHK(ParseCodim2Spec(PETSC_COMM_SELF, "insulated:hamiltonian_hopf@1.8", &s));
  REQUIRE(s.kind == EventKind::HamiltonianHopf);
  PCHK(ParseCodim2Spec(PETSC_COMM_SELF, "insulated:5@1.8", &s));
  REQUIRE(s.kind == EventKind::HamiltonianHopf);
  PCHK(ParseCodim2Spec(PETSC_COMM_SELF, "insulated_bp3_plus:period_doubling@2.5", &s));
  REQUIRE((s.branch == "insulated_bp3_plus" && s.kind == EventKind::PeriodDoubling && s.omega == 2.5));
  PCHK(ParseCodim2Spec(PETSC_COMM_SELF, "insulated:pd@2", &s));
  REQUIRE(s.kind == EventKind::PeriodDoubling);
  PCHK(ParseCodim2Spec(PETSC_COMM_SELF, "insulated:3@2", &s));
  REQUIRE(s.kind == EventKind::PeriodDoubling);
  for (const char *bp : {"insulated:bp@2.4", "insulated:2@2.4", "insulated:branch_point@2.4"}) {
    PCHK(ParseCodim2Spec(PETSC_COMM_SELF, bp, &s));
    REQUIRE((s.branch == "insulated" && s.kind == EventKind::BranchPoint && s.omega == 2.4));
  }
  for (const char *no : {"insulated:4@2.4", "insulated:6@2.4", "insulated:krein_collision@2.4", "insulated:resonance@2.4"})
    REQUIRE(ParseCodim2Spec(PETSC_COMM_SELF, no, &s) == PETSC_ERR_USER); // (named: not a boundary of stability)
  PetscPopErrorHandler();
}
