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
#include "stability/collision_subspace.hpp"
#include <array>
#include <cmath>
#include <petscblaslapack.h>

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
  // The event (located at Gamma 0.5 on the one-cell lattice) followed in -lattice_gamma over [pmin, pmax].
  PetscErrorCode ContinueInGamma(PetscReal pmin, PetscReal pmax, PetscInt max_points, Codim2Curve *c)
  {
    Codim2Start start;
    Codim2Options o;
    LatticeParams p;
    PetscFunctionBeginUser;
    PetscCall(Start(&start));
    o.parameter = Codim2Parameter::Gamma;
    o.pmin = pmin, o.pmax = pmax, o.max_points = max_points;
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
    // the follower's own bound on g (kNoise): a converged point lies within -cont_codim2_tol of the curve,
    // and a fold's g changes by ~1e4 per unit of ln omega (E(omega) is sharply curved at its maximum)
    REQUIRE(std::abs(c.test[k]) <= 1e-5);
  }
  INFO("worst |E Gamma / (E Gamma)* - 1| " << worst_eg << ", worst |omega / omega* - 1| " << worst_w);
  PCHK(PetscPrintf(PETSC_COMM_WORLD,
                   "  codim2 %s in -lattice_cubic: %zu points, Gamma %.4g .. %.4g, max |E Gamma / (E Gamma)* - 1| = %.1e, max |omega / omega* - 1| = %.1e\n",
                   what, n, (double)c.p.front(), (double)c.p.back(), (double)worst_eg, (double)worst_w));
  REQUIRE(worst_eg <= 1e-8);
  REQUIRE(worst_w <= 1e-8);
}

// The curve's last row inside its bounds of p (a side that reached a bound
// keeps the first point past it).
size_t LastInside(const Codim2Curve &c)
{
  const size_t n = c.p.size();
  return c.stop_reason.find("reached -cont_codim2_max") != std::string::npos && n >= 2 ? n - 2 : n - 1;
}

// An independent one-parameter run's event h of the curve's kind, at the
// curve's p of row m: at the curve's omega to 1e-6 and its E to 1e-5 relative.
void RequireEventAtCurveEnd(const BifurcationEvent &h, const Codim2Curve &c, const char *what, size_t m)
{
  INFO("one-parameter " << what << " at Gamma " << c.p[m] << ": omega " << h.omega << ", E " << h.energy << "; the curve's " << c.omega[m] << ", "
                        << c.energy[m]);
  REQUIRE(std::abs(h.omega - c.omega[m]) <= 1e-6);
  REQUIRE(std::abs(h.energy - c.energy[m]) <= 1e-5 * h.energy);
  PCHK(PetscPrintf(PETSC_COMM_WORLD, "  one-parameter %s at Gamma %.6g: |omega - curve's| = %.1e, |E / curve's - 1| = %.1e\n", what, (double)c.p[m],
                   (double)std::abs(h.omega - c.omega[m]), (double)std::abs(h.energy / c.energy[m] - 1)));
}

// A constructed pair with a Hamiltonian-Hopf curve known in closed form: two
// oscillators of opposite Krein signature, coupled,
//   H = (p1^2 + w1^2 q1^2)/2 - (p2^2 + w2^2 q2^2)/2 + c q1 q2,
// so q'' = -K q, K = [[w1^2, c], [-c, w2^2]], whose frequencies Omega^2 =
// (w1^2 + w2^2)/2 +- sqrt(((w1^2 - w2^2)/2)^2 - c^2) collide, and leave the
// real axis (a quadruplet of multipliers), where |w1^2 - w2^2| = 2 |c|. With
// w1^2 = s(a) + r(a), w2^2 = s(a) - r(a) and c = b the curves are b = +-r(a):
// r(a) = a (2 - a) / 2 turns in b at a = 1 (b = +-1/2), and the two curves meet
// at (a, b) = (2, 0) (c = 0, w1 = w2: a semisimple double frequency). The
// collision's frequency on the curve is Omega* = sqrt(s(a)), s(a) = a - 1/4, so
// its b* = cos(Omega* T) reaches +1 at a = 1/4 (Omega* -> 0: a 1:1 resonance),
// where the curve ends (beyond, a pair is real). The monodromy exp(T J Hess H)
// over T = 1 goes through the lattice's own Hamiltonian-Hopf test function
// (TrackCollision) and the same follower (FollowCodim2); p = b, E = a.
class OppositePair : public Codim2Function {
public:
  static PetscReal R(PetscReal a) { return 0.5 * a * (2 - a); }
  static PetscReal S(PetscReal a) { return a - 0.25; }
  static constexpr PetscReal kT = 1;
  PetscErrorCode Sample(PetscReal a, PetscReal b, const Codim2Sample &, Codim2Sample *x) override
  {
    PetscFunctionBeginUser;
    *x = Codim2Sample();
    x->a = a, x->b = b, x->p = b, x->energy = a, x->omega = std::sqrt(std::max(S(a), (PetscReal)0));
    const M4 E = Monodromy(S(a) + R(a), S(a) - R(a), b);
    std::vector<PetscReal> m(16);
    for (int i = 0; i < 4; i++)
      for (int j = 0; j < 4; j++) m[4 * j + i] = E[4 * i + j]; // column-major
    CollisionChoice ch;
    PetscCall(TrackCollision(4, m.data(), FloquetOptions().tol, bstar_, basis_, &ch));
    x->ok = ch.ok && std::isfinite(ch.g), x->basis = std::move(ch.basis);
    if (x->ok) x->g = ch.g, x->bmid = ch.bmid;
    PetscFunctionReturn(0);
  }
  void Accept(const Codim2Sample &x) override { bstar_ = x.bmid, basis_ = x.basis; }
  bool Collision() const override { return true; }
  // The start: on the curve b = sign r(a), off it by 0.01 in b (the corrector puts it back), the collision's b* there.
  static Codim2Sample Guess(PetscReal a, PetscReal sign)
  {
    Codim2Sample s;
    s.a = a, s.b = sign * R(a) + 0.01, s.p = s.b, s.energy = a, s.bmid = std::cos(std::sqrt(S(a)) * kT);
    return s;
  }

private:
  PetscReal bstar_ = 0;
  std::vector<PetscReal> basis_;

public:
  using M4 = std::array<PetscReal, 16>; // row-major
  // M = exp(T A), A = J Hess H in z = (q1, q2, p1, p2) (scaling and squaring of the Taylor series).
  static M4 Monodromy(PetscReal w1s, PetscReal w2s, PetscReal c)
  {
    auto mul = [](const M4 &x, const M4 &y) {
      M4 z{};
      for (int i = 0; i < 4; i++)
        for (int k = 0; k < 4; k++)
          for (int j = 0; j < 4; j++) z[4 * i + j] += x[4 * i + k] * y[4 * k + j];
      return z;
    };
    // q1' = p1, q2' = -p2, p1' = -w1^2 q1 - c q2, p2' = w2^2 q2 - c q1
    M4 A{0, 0, 1, 0, 0, 0, 0, -1, -w1s, -c, 0, 0, -c, w2s, 0, 0};
    PetscReal norm = 0;
    for (PetscReal v : A) norm = std::max(norm, std::abs(v) * kT);
    int sq = 0;
    while (4 * norm > 0.5) norm *= 0.5, sq++; // ||T A / 2^sq||_1 <= 4 max|entry| <= 1/2
    for (PetscReal &v : A) v *= kT / std::ldexp(1.0, sq);
    M4 E{1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1}, term = E;
    for (int k = 1; k <= 24; k++) {
      term = mul(term, A);
      for (PetscReal &v : term) v /= k;
      for (int i = 0; i < 16; i++) E[i] += term[i];
    }
    for (int k = 0; k < sq; k++) E = mul(E, E);
    return E;
  }
};

// Both curves of the pair, from (a, b) = (1.5, +-r(1.5)), p in [-0.6, 0.6].
void FollowPair(PetscReal sign, Codim2Trace *t)
{
  OppositePair f;
  Codim2Options o;
  o.pmin = -0.6, o.pmax = 0.6;
  o.verbose = PETSC_FALSE;
  PCHK(FollowCodim2(PETSC_COMM_WORLD, f, o, OppositePair::Guess(1.5, sign), sign > 0 ? "pair +" : "pair -", t));
  REQUIRE(t->started);
  INFO("curve b = " << sign << " r(a): " << t->pts.size() << " points; p decreasing: " << t->why_down << "; p increasing: " << t->why_up);
  REQUIRE(t->pts.size() >= 20);
}

} // namespace

TEST_CASE("codim-2: a constructed pair's Hamiltonian-Hopf curve |c| = |w1^2 - w2^2| / 2, through the lattice's test function and follower", "[codim2]")
{
  for (PetscReal sign : {1.0, -1.0}) {
    Codim2Trace t;
    FollowPair(sign, &t);
    PetscReal worst = 0, worst_b = 0, amin = 10, amax = 0;
    for (const Codim2Sample &x : t.pts) {
      worst = std::max(worst, std::abs(x.b - sign * OppositePair::R(x.a)));
      worst_b = std::max(worst_b, std::abs(x.bmid - std::cos(std::sqrt(OppositePair::S(x.a)) * OppositePair::kT)));
      amin = std::min(amin, x.a), amax = std::max(amax, x.a);
    }
    const Codim2Trace::Point &lo = t.points.front(), &hi = t.points.back();
    const Codim2Trace::Point &end = sign > 0 ? hi : lo; // the side running to a = 1/4 (p increasing on b = +r)
    PCHK(PetscPrintf(PETSC_COMM_WORLD,
                     "  codim2 pair, b = %+g r(a): %zu points, a %.6f .. %.6f, max |b - b(a)| = %.1e, max |b* - cos(Omega* T)| = %.1e; end at a = %.6g "
                     "(b* = %.8f, point kind %d)\n",
                     (double)sign, t.pts.size(), (double)amin, (double)amax, (double)worst, (double)worst_b, (double)end.x.a, (double)end.x.bmid,
                     (int)end.kind));
    REQUIRE(worst <= 1e-8);   // on the closed form (the corrector's distance to the curve: -cont_codim2_test_tol |grad g| and below)
    REQUIRE(worst_b <= 1e-8); // and the collision is where it is (the middle of a Jordan block's computed pair: exact to rounding)
    REQUIRE(amax > 2.1);      // through the meeting with the other curve at (2, 0)
    // the end at the 1:1 resonance: the last point near a = 1/4, where b* -> 1
    REQUIRE(end.kind == Codim2PointKind::CollisionPlus);
    REQUIRE(end.x.a - 0.25 >= 0);
    REQUIRE(end.x.a - 0.25 <= 2e-3); // (it ends where a finite-difference probe finds a real pair: s(a) ~ sqrt(kH))
    REQUIRE(1 - end.x.bmid <= 1e-2);
    // the other end: the bound of p (-0.6 on b = +r, +0.6 on b = -r), past the meeting at (2, 0): not a codim-2 point
    REQUIRE((sign > 0 ? lo : hi).kind == Codim2PointKind::End);
    REQUIRE((sign > 0 ? t.why_down : t.why_up) == (sign > 0 ? "reached -cont_codim2_min" : "reached -cont_codim2_max"));
  }
}

TEST_CASE("codim-2: the colliding pairs are told apart by their invariant subspace, not by the nearest b (a third pair between them)", "[codim2]")
{
  // The constructed pair on the circle side near its collision (a = 1.5, c = 0.37 < r(a) = 0.375): b1, b2
  // around b* = (b1 + b2)/2, and a third oscillator (frequency wc, b = cos(wc T)) between them, nearer b*
  // than either: the two nearest b* pair it with one of them. The 6 x 6 monodromy blockdiag(M_pair, M_c) is
  // rotated by an orthogonal Q (the eigenvalues and the subspaces' geometry kept); the last point's subspace
  // is the pair's own coordinates, Q's first four columns.
  const PetscReal a = 1.5, c = 0.37, r = OppositePair::R(a), s = OppositePair::S(a), d = std::sqrt(r * r - c * c);
  const PetscReal b1 = std::cos(std::sqrt(s + d) * OppositePair::kT), b2 = std::cos(std::sqrt(s - d) * OppositePair::kT);
  const PetscReal bstar = 0.5 * (b1 + b2), bc = bstar + 0.1 * (b2 - b1), wc = std::acos(bc) / OppositePair::kT;
  const OppositePair::M4 P = OppositePair::Monodromy(s + r, s - r, c);
  const int n = 6;
  std::vector<PetscReal> M(n * n, 0.0), Q(n * n), A(n * n, 0.0); // M, A row-major; Q column-major (its columns orthonormal)
  for (int i = 0; i < 4; i++)
    for (int j = 0; j < 4; j++) M[n * i + j] = P[4 * i + j];
  // q' = p, p' = -wc^2 q over T: [[cos, sin / wc], [-wc sin, cos]]
  M[n * 4 + 4] = std::cos(wc * OppositePair::kT), M[n * 4 + 5] = std::sin(wc * OppositePair::kT) / wc;
  M[n * 5 + 4] = -wc * std::sin(wc * OppositePair::kT), M[n * 5 + 5] = std::cos(wc * OppositePair::kT);
  for (int k = 0; k < n * n; k++) Q[k] = std::sin(1.0 + 7.3 * k) + (k % (n + 1) == 0 ? 2.0 : 0.0); // Gram-Schmidt below
  for (int j = 0; j < n; j++) {
    for (int i = 0; i < j; i++) {
      PetscReal dot = 0;
      for (int k = 0; k < n; k++) dot += Q[n * i + k] * Q[n * j + k];
      for (int k = 0; k < n; k++) Q[n * j + k] -= dot * Q[n * i + k];
    }
    PetscReal nrm = 0;
    for (int k = 0; k < n; k++) nrm += Q[n * j + k] * Q[n * j + k];
    for (int k = 0; k < n; k++) Q[n * j + k] /= std::sqrt(nrm);
  }
  // A = Q M Q^T, column-major for LAPACK: A[col * n + row]
  for (int i = 0; i < n; i++)
    for (int j = 0; j < n; j++)
      for (int k = 0; k < n; k++)
        for (int l = 0; l < n; l++) A[n * j + i] += Q[n * k + i] * M[n * k + l] * Q[n * l + j];
  const std::vector<PetscReal> prev(Q.begin(), Q.begin() + 4 * n);
  const PetscReal truth = (b1 - b2) * (b1 - b2);
  CollisionChoice tracked, nearest;
  std::vector<PetscReal> A2 = A;
  PCHK(TrackCollision(n, A.data(), 1e-6, bstar, prev, &tracked));
  PCHK(TrackCollision(n, A2.data(), 1e-6, bstar, {}, &nearest));
  INFO("b1 " << b1 << ", b2 " << b2 << ", third " << bc << "; g tracked " << tracked.g << " (overlap " << tracked.overlap << "), nearest two "
             << nearest.g << ", truth " << truth);
  REQUIRE(tracked.ok);
  REQUIRE(std::abs(tracked.g - truth) <= 1e-10 * truth);
  REQUIRE(std::abs(tracked.bmid - bstar) <= 1e-10);
  REQUIRE(tracked.overlap >= 1 - 1e-10);
  REQUIRE(nearest.ok);
  REQUIRE(std::abs(nearest.g - truth) > 0.5 * truth); // the nearest two are not the pair
  PCHK(PetscPrintf(PETSC_COMM_WORLD, "  codim2 collision subspace: g tracked %.6e (truth %.6e, overlap %.12f), nearest two in b %.6e\n", (double)tracked.g,
                   (double)truth, (double)tracked.overlap, (double)nearest.g));
}

TEST_CASE("codim-2: the curve is smooth through a turning point in p, located at p's extremum (the constructed pair)", "[codim2]")
{
  // (no quick real lattice curve with a turn in p is known yet: the fold curve of mode 0 of N = 6 runs to E -> 0)
  for (PetscReal sign : {1.0, -1.0}) {
    Codim2Trace t;
    FollowPair(sign, &t);
    std::vector<const Codim2Trace::Point *> turns;
    for (const Codim2Trace::Point &q : t.points)
      if (q.kind == Codim2PointKind::Turn) turns.push_back(&q);
    REQUIRE(turns.size() == 1);
    const Codim2Trace::Point &q = *turns[0];
    // where the locator puts it: at p's extremum b = +-1/2, a = 1 (b - b* is quadratic in a - 1 there)
    PCHK(PetscPrintf(PETSC_COMM_WORLD, "  codim2 pair, b = %+g r(a): turn in p located at a = %.12f (|a - 1| = %.1e), p = %.14f (|p - p*| = %.1e), arc %.4f\n",
                     (double)sign, (double)q.x.a, (double)std::abs(q.x.a - 1), (double)q.x.p, (double)std::abs(q.x.p - 0.5 * sign), (double)q.arc));
    REQUIRE(std::abs(q.x.a - 1) <= 1e-8);
    REQUIRE(std::abs(q.x.p - 0.5 * sign) <= 1e-12);
    // between the rows it names, and no written point beyond the extremum
    const size_t r = (size_t)q.arc;
    REQUIRE(r + 1 < t.pts.size());
    REQUIRE((t.pts[r].a - 1) * (t.pts[r + 1].a - 1) < 0);
    for (const Codim2Sample &x : t.pts) REQUIRE(sign * x.p <= sign * q.x.p + 1e-14);
    // one smooth curve through it: the points on both sides continue on the closed form (the case above), the
    // chords turn by at most about step x curvature (<= 1 here) and the rows' arclength steps change smoothly
    PetscReal worst_turn = 0;
    for (size_t k = 1; k + 1 < t.pts.size(); k++) {
      const PetscReal u0 = t.pts[k].a - t.pts[k - 1].a, v0 = t.pts[k].b - t.pts[k - 1].b, u1 = t.pts[k + 1].a - t.pts[k].a, v1 = t.pts[k + 1].b - t.pts[k].b;
      const PetscReal angle = std::abs(std::atan2(u0 * v1 - v0 * u1, u0 * u1 + v0 * v1));
      worst_turn = std::max(worst_turn, angle);
      if (k == r || k == r + 1) REQUIRE(angle <= 0.2); // across the turn itself
    }
    INFO("largest angle between successive chords " << worst_turn);
    REQUIRE(worst_turn <= 0.25);
    REQUIRE(std::abs(t.pts[r].b - sign * OppositePair::R(t.pts[r].a)) <= 1e-8);
    REQUIRE(std::abs(t.pts[r + 1].b - sign * OppositePair::R(t.pts[r + 1].a)) <= 1e-8);
  }
}

TEST_CASE("codim-2: Codim2Intersections finds where two curves' polylines cross", "[codim2][serial]")
{
  // straight lines: exact; a crossing at a shared vertex counted once
  auto x = Codim2Intersections({0, 1, 2}, {0, 1, 2}, {0, 2}, {2, 0});
  REQUIRE(x.size() == 1);
  REQUIRE(x[0].p == Approx(1).margin(1e-15));
  REQUIRE(x[0].energy == Approx(1).margin(1e-15));
  REQUIRE(x[0].arc1 == Approx(1).margin(1e-15));
  REQUIRE(x[0].arc2 == Approx(0.5).margin(1e-15));
  // twice; parallel and disjoint: none
  x = Codim2Intersections({0, 1, 2}, {0, 1, 0}, {0, 2}, {0.5, 0.5});
  REQUIRE(x.size() == 2);
  REQUIRE(x[0].p == Approx(0.5).margin(1e-15));
  REQUIRE(x[1].p == Approx(1.5).margin(1e-15));
  REQUIRE(x[1].arc1 == Approx(1.5).margin(1e-15));
  REQUIRE(Codim2Intersections({0, 1}, {0, 1}, {0, 1}, {1, 2}).empty());
  REQUIRE(Codim2Intersections({0, 1}, {0, 1}, {2, 3}, {1, 0}).empty());
  REQUIRE(Codim2Intersections({0}, {0}, {0, 1}, {1, 0}).empty());
  // the constructed pair's two Hamiltonian-Hopf curves meet at (p, E) = (0, 2) (c = 0, w1 = w2), to the chords' error
  Codim2Trace up, dn;
  FollowPair(1, &up);
  FollowPair(-1, &dn);
  std::vector<PetscReal> p1, e1, p2, e2;
  for (const Codim2Sample &s : up.pts) p1.push_back(s.p), e1.push_back(s.energy);
  for (const Codim2Sample &s : dn.pts) p2.push_back(s.p), e2.push_back(s.energy);
  x = Codim2Intersections(p1, e1, p2, e2);
  REQUIRE(x.size() == 1);
  INFO("meeting at p " << x[0].p << ", E " << x[0].energy);
  REQUIRE(std::abs(x[0].p) <= 2e-3);
  REQUIRE(std::abs(x[0].energy - 2) <= 2e-3);
  const size_t i = (size_t)x[0].arc1;
  REQUIRE((up.pts[i].a - 2) * (up.pts[i + 1].a - 2) <= 0);
}

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
  PCHK(g.Locate(c.p[LastInside(c)]));
  REQUIRE(g.index >= 0);
  const BifurcationEvent &h = g.ev[g.index];
  RequireEventAtCurveEnd(h, c, "fold", LastInside(c));
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
  q.cells = 1, q.Gamma = c.p[LastInside(c)];
  PCHK(g.Locate(q, 0.9702, 0.05)); // short steps: the onset follows the fold closely, and the locator's probes fail across it at 0.2
  // (the first onset there may be another: a short bubble near omega 0.954 that the probes of the run at Gamma 0.5 step over)
  const PetscInt hi = g.Nearest(c.omega[n - 1]);
  REQUIRE(hi >= 0);
  const BifurcationEvent &h = g.ev[hi];
  REQUIRE(h.direction == e.direction);
  RequireEventAtCurveEnd(h, c, "onset", LastInside(c));
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
  // below 0.75 (the parent's continuation steps are not scale-free, the switch is: at some Gamma,
  // e.g. 0.7886, the switched family's first orbit is not pinned)
  size_t m = 0;
  for (size_t k = 0; k < n; k++)
    if (c.p[k] <= 0.75) m = k;
  REQUIRE(c.p[m] > 0.7);
  DoublingOnSwitchedFamily g;
  PCHK(g.LocateDoubling(c.p[m]));
  const PetscInt hi = g.Nearest(c.omega[n - 1]);
  REQUIRE(hi >= 0);
  const BifurcationEvent &h = g.ev[hi];
  REQUIRE(h.direction == e.direction);
  RequireEventAtCurveEnd(h, c, "period doubling", m);
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
  const size_t m = LastInside(c);
  q.Gamma = c.p[m];
  PCHK(g.Locate(q, 2.51, 0.2));
  const PetscInt hi = g.Nearest(c.omega[m]);
  REQUIRE(hi >= 0);
  const BifurcationEvent &h = g.ev[hi];
  REQUIRE(h.direction == e.direction);
  RequireEventAtCurveEnd(h, c, "branch point", m);
}

TEST_CASE("codim-2: the energy fold continued in -lattice_gamma passes through the folds of independent one-parameter runs at its ends", "[codim2][once]")
{
  // [once]: the distributed path (the lattice rebuilt at each p, the bordered solve) runs at 2 ranks in the
  // -lattice_cubic case above; at 2 ranks on a lattice of 6 sites this one costs ~20 times its serial time.
  // not degenerate: omega and E Gamma change along this curve (at gamma 0.4 omega 0.96852, E 65.8; at 0.45 about 0.9427, 40.9)
  FoldOfMode0 f;
  PCHK(f.Locate(0.5));
  REQUIRE(f.index >= 0);
  Codim2Curve c;
  PCHK(f.ContinueInGamma(0.36, 0.45, Codim2Options().max_points, &c));
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

TEST_CASE("codim-2: the energy fold of mode 0 continued in -lattice_gamma ends at the linear limit, written as that codim-2 point", "[codim2][once]")
{
  // [once]: the orbit path at 2 ranks runs in the -lattice_cubic fold case. From gamma 0.4 (E 65.8) the E
  // maximum's fold curve runs down to E -> 0 as gamma grows (docs/continuation.md "Where the curves end"):
  // the branch's frequency shift at E -> 0 changes sign there. The corrector's steps collapse as g gets noisy.
  FoldOfMode0 f;
  PCHK(f.Locate(0.5));
  REQUIRE(f.index >= 0);
  Codim2Curve c;
  PCHK(f.ContinueInGamma(0.39, 0.8, 80, &c));
  const size_t n = c.p.size(), m = c.point_kind.size();
  INFO("curve " << c.name << ": " << n << " points, p " << c.p.front() << " .. " << c.p.back() << ", E " << c.energy.back() << ": " << c.stop_reason);
  REQUIRE(m == 2); // both ends, no turn in p
  REQUIRE(c.point_kind[0] == (PetscInt)Codim2PointKind::End);
  REQUIRE(c.point_arc[0] == 0);
  REQUIRE(c.point_kind[1] == (PetscInt)Codim2PointKind::LinearLimit);
  REQUIRE(c.point_arc[1] == (PetscReal)(n - 1));
  REQUIRE(c.point_p[1] == c.p[n - 1]);
  REQUIRE(c.point_energy[1] == c.energy[n - 1]);
  REQUIRE(c.point_energy[1] <= 1e-2 * c.energy[c.event_point]);
  REQUIRE(std::abs(c.point_p[1] - 0.6736) <= 1e-3);
  for (size_t k = 1; k < n; k++) REQUIRE(c.p[k] > c.p[k - 1]);
  PCHK(PetscPrintf(PETSC_COMM_WORLD, "  codim2 fold in -lattice_gamma: linear limit at gamma %.6f, omega %.6f, E %.3g (%zu points, %" PetscInt_FMT " orbits)\n",
                   (double)c.point_p[1], (double)c.point_omega[1], (double)c.point_energy[1], n, c.solves));
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
