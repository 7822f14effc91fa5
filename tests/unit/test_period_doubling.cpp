// Period doubling against known truth. On the interface lattice the symmetric
// NNM orbits have x(t + T/2) = -x(t), so their monodromy is the square of the
// half-period map and a single real pair through -1 is not generic there; the
// test builds a system with a genuine period doubling from the real machinery:
// the two-site lattice (layout right, Nc = 1: one stiff dimer, grounded) with
// its cubic bonds off and a test-defined effect V = (c/2) q_a q_s^2 coupling
// its two linear modes, q_a = (u_1 - u_2)/sqrt 2 (frequency w_a) and q_s =
// (u_1 + u_2)/sqrt 2 (w_s, tuned by the grounding to delta = (w_s/w_a)^2 =
// 1/4 + d). On q_s = 0, q_a = A cos(w_a t) exactly at every amplitude (its NNM
// family is linear, of constant period), and the variation of q_s obeys
// exactly Mathieu's equation x'' + (delta + eps cos tau) x = 0, tau = w_a t,
// eps = c A / w_a^2: the family loses stability where eps crosses the first
// tongue's upper boundary delta = 1/4 + eps/2 - eps^2/8 - eps^3/32 + O(eps^4)
// through -1. First-order averaging of the 1:2 resonance (H = w_a I_a + w_s I_s
// + kappa sqrt(I_a) I_s cos(phi_a - 2 phi_s)) puts the doubled family on the
// unstable side, E - E* ~ w_a I_s, its pumped mode's amplitude growing like the
// square root of the distance from the located point.
#include "bands/linear_modes.hpp"
#include "core/gather.hpp"
#include "branch_record.hpp"
#include "helpers.hpp"
#include "orbits/continuation.hpp"
#include "stability/bifurcation_locator.hpp"
#include "stability/branch_switch.hpp"
#include <algorithm>
#include <cmath>

using namespace nltopo;
using namespace nltopo::test;

namespace {

// V = (c/2) q_a q_s^2 on the two sites of the chain (N = 2: every pair of sites
// is a bond, so its stiffness is nearest-neighbour). Its energy goes into the
// "quartic" part (EnergyParts has no other nonlinear part; the total is what counts).
class ModePump : public Effect {
public:
  ModePump(const Lattice &lat, PetscReal c) : xs_(lat.OwnedStart()), xe_(lat.OwnedStart() + lat.OwnedCount()), c_(c) {}
  const char *Name() const override { return "mode_pump"; }
  const char *LogName() const override { return "RhsTestModePump"; }
  std::string EnabledBy() const override { return "test_period_doubling.cpp"; }
  bool Conservative() const override { return true; }

  void AddAcceleration(PetscReal, const PetscScalar *u, const PetscScalar *, PetscScalar *a) const override
  {
    PetscReal qa, qs;
    Modes(u, &qa, &qs);
    const PetscReal dVa = 0.5 * c_ * qs * qs, dVs = c_ * qa * qs;                        // dV/dq_a, dV/dq_s
    const PetscReal g[2] = {(dVa + dVs) / std::sqrt(2.0), (dVs - dVa) / std::sqrt(2.0)}; // dV/du_i
    for (PetscInt i = xs_; i < xe_; i++) a[i] -= g[i];
  }
  void AddStiffness(const PetscScalar *u, PetscScalar *kd, PetscScalar *kb) const override
  {
    if (!u) return; // the Hessian of a cubic vanishes at rest
    PetscReal qa, qs;
    Modes(u, &qa, &qs);
    // P [[0, c qs], [c qs, c qa]] P^T in (a, s) -> sites, P = [[1, 1], [-1, 1]] / sqrt 2
    const PetscReal d[2] = {0.5 * c_ * (qa + 2 * qs), 0.5 * c_ * (qa - 2 * qs)};
    for (PetscInt i = xs_; i < xe_; i++) kd[i] += d[i];
    kb[0] += 0.5 * c_ * qa; // bond 0 lies in xs-1 .. xe-1 on every rank
  }
  void AddEnergy(const PetscScalar *u, EnergyParts *e) const override
  {
    PetscReal qa, qs;
    if (xs_ != 0) return; // the bond counts on the owner of site 0
    Modes(u, &qa, &qs);
    e->quartic += 0.5 * c_ * qa * qs * qs;
  }

private:
  static void Modes(const PetscScalar *u, PetscReal *qa, PetscReal *qs)
  {
    *qa = (u[0] - u[1]) / std::sqrt(2.0);
    *qs = (u[0] + u[1]) / std::sqrt(2.0);
  }
  PetscInt xs_, xe_;
  PetscReal c_;
};

// The pumped dimer: delta = (w_s / w_a)^2 = 1/4 + d.
struct PumpedDimer {
  static constexpr PetscReal d = 0.02, c = 1.0;
  Lattice lat;
  EffectList fx{lat};
  LinearModes modes;
  PeriodicFlow flow;
  Shooting shoot;
  PetscReal ws = 0, wa = 0;
  PetscErrorCode Setup()
  {
    LatticeParams p;
    PetscFunctionBeginUser;
    p.layout = Layout::Right;
    p.cells = 1;
    p.Gamma = 0; // no cubic bonds: the test's effect is the only nonlinearity
    // w_s^2 = k2 + g0, w_a^2 = 2 k1 + k2 + g0
    const PetscReal delta = 0.25 + d, k1 = p.K1(), k2 = p.K2();
    p.gamma0 = (delta * (2 * k1 + k2) - k2) / (1 - delta);
    PetscCall(lat.Setup(PETSC_COMM_WORLD, p));
    PetscCall(modes.Compute(lat, LinearModesOptions()));
    PetscCall(BuildLatticeEffects(lat, &fx));
    PetscCall(fx.Add(std::make_unique<ModePump>(lat, c)));
    PetscCall(flow.Setup(fx, FlowOptions()));
    PetscCall(shoot.Setup(flow, ShootingOptions()));
    ws = modes.Omega()[0], wa = modes.Omega()[1];
    PetscFunctionReturn(0);
  }
  // q_a, q_s and their momenta of a natural row [u_1, u_2, v_1, v_2]
  static void ModeCoordinates(const PetscReal *z, PetscReal q[4])
  {
    const PetscReal r = 1 / std::sqrt(2.0);
    q[0] = r * (z[0] - z[1]), q[1] = r * (z[0] + z[1]), q[2] = r * (z[2] - z[3]), q[3] = r * (z[2] + z[3]);
  }
};

// Mathieu's first tongue, upper boundary: eps where eps/2 - eps^2/8 - eps^3/32 = d (Newton from 2 d).
PetscReal TongueEps(PetscReal d)
{
  PetscReal e = 2 * d;
  for (int k = 0; k < 50; k++) e -= (e / 2 - e * e / 8 - e * e * e / 32 - d) / (0.5 - e / 4 - 3 * e * e / 32);
  return e;
}

// The same boundary without the series: Mathieu's equation integrated directly
// (RK4, 4000 steps over tau = 0 .. 2 pi), eps where the trace of its monodromy is -2
// (bisection between 0 and 4 d: below the tongue |trace| < 2, inside it trace < -2).
PetscReal TongueEpsDirect(PetscReal delta, PetscReal d)
{
  auto trace = [delta](PetscReal eps) {
    const int n = 4000;
    const PetscReal h = 2 * PETSC_PI / n;
    PetscReal tr = 0;
    for (int col = 0; col < 2; col++) {
      PetscReal x = col == 0, v = col == 1, t = 0;
      auto acc = [&](PetscReal tt, PetscReal xx) { return -(delta + eps * std::cos(tt)) * xx; };
      for (int k = 0; k < n; k++, t += h) {
        const PetscReal k1x = v, k1v = acc(t, x);
        const PetscReal k2x = v + 0.5 * h * k1v, k2v = acc(t + 0.5 * h, x + 0.5 * h * k1x);
        const PetscReal k3x = v + 0.5 * h * k2v, k3v = acc(t + 0.5 * h, x + 0.5 * h * k2x);
        const PetscReal k4x = v + h * k3v, k4v = acc(t + h, x + h * k3x);
        x += h / 6 * (k1x + 2 * k2x + 2 * k3x + k4x);
        v += h / 6 * (k1v + 2 * k2v + 2 * k3v + k4v);
      }
      tr += col == 0 ? x : v;
    }
    return tr;
  };
  PetscReal lo = 0, hi = 4 * d;
  for (int k = 0; k < 60; k++) {
    const PetscReal mid = 0.5 * (lo + hi);
    (trace(mid) > -2 ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

// The slope and the zero of the least-squares line y = a x + b through (x_k, y_k).
void FitLine(const std::vector<PetscReal> &x, const std::vector<PetscReal> &y, PetscReal *slope, PetscReal *zero)
{
  PetscReal sx = 0, sy = 0, sxx = 0, sxy = 0;
  const PetscReal m = (PetscReal)x.size();
  for (size_t k = 0; k < x.size(); k++) sx += x[k], sy += y[k], sxx += x[k] * x[k], sxy += x[k] * y[k];
  *slope = (m * sxy - sx * sy) / (m * sxx - sx * sx);
  *zero = -((sy - *slope * sx) / m) / *slope;
}

} // namespace

TEST_CASE(
    "period doubling of a Mathieu-pumped dimer: located on the tongue boundary, the doubled family has period 2T, leaves the parent like the root of the distance, and its orbits close over 2T",
    "[bifurcations][switch][period_doubling]")
{
  PumpedDimer pd;
  PCHK(pd.Setup());
  const PetscInt N = pd.lat.N();
  REQUIRE(N == 2);
  const PetscReal delta = std::pow(pd.ws / pd.wa, 2);
  REQUIRE(std::abs(delta - 0.25 - PumpedDimer::d) < 1e-12);
  const PetscReal eps_th = TongueEps(PumpedDimer::d);
  const PetscReal E_th = 0.5 * std::pow(eps_th * pd.wa * pd.wa / PumpedDimer::c, 2) * pd.wa * pd.wa; // w_a^2 A^2 / 2, A = eps w_a^2 / c
  // the parent: the q_a family (linear mode 1) through the onset, and its events
  ContinuationOptions co;
  co.verbose = PETSC_FALSE;
  co.energy_min = 1e-3;
  co.energy_max = 2 * E_th;
  co.max_change = 0.1;
  Record rec(pd.flow);
  Branch parent;
  PCHK(ContinueBranch(pd.shoot, pd.modes.Mode(1), 2 * PETSC_PI / pd.wa, co, "pumped", &parent, &rec));
  const PetscReal Tp = parent.period.front();
  for (PetscReal T : parent.period) REQUIRE(std::abs(T / Tp - 1) < 1e-9); // a linear family: the period of w_a at every amplitude
  REQUIRE(std::abs(Tp * pd.wa / (2 * PETSC_PI) - 1) < 1e-8);
  BifurcationLocator loc;
  std::vector<BifurcationEvent> ev;
  PCHK(LocateRecorded(loc, pd.shoot, parent, rec, "pumped", &ev));
  REQUIRE(ev.size() == 1);
  const BifurcationEvent &e = ev[0];
  REQUIRE(e.kind == EventKind::PeriodDoubling);
  REQUIRE(e.direction == 1);
  REQUIRE(e.mu_re < -1);
  REQUIRE(e.mu_re > -1 - 1e-3);
  REQUIRE(e.mu_im == 0);
  // located where Mathieu's tongue puts it: eps = c A / w_a^2 with E = w_a^2 A^2 / 2 on q_s = 0
  const PetscReal eps_loc = PumpedDimer::c * std::sqrt(2 * e.energy) / std::pow(pd.wa, 3);
  INFO("onset: eps located " << eps_loc << ", Mathieu to eps^3 " << eps_th << " (first order 2d = " << 2 * PumpedDimer::d << "), difference "
                             << eps_loc - eps_th << " against eps^4 " << std::pow(eps_th, 4) << "; E* = " << e.energy);
  REQUIRE(std::abs(eps_loc - eps_th) < 0.25 * std::pow(eps_th, 4)); // the eps^3 term alone moves it by eps^3 / 16, 6x this
  const PetscReal eps_ex = TongueEpsDirect(delta, PumpedDimer::d);
  INFO("Mathieu's equation integrated directly: eps* = " << eps_ex);
  REQUIRE(std::abs(eps_loc - eps_ex) < 1e-8);
  // the critical direction is the pumped mode q_s alone, and at the upper boundary its
  // 4 pi-periodic Mathieu solution is se_1(tau / 2): zero displacement where the pump
  // c q_a(0) cos(tau) is largest (the section: q_a at its turning point), a velocity.
  const std::vector<PetscReal> rows = AllRows(parent);
  PetscReal qp[4], qv[4];
  PumpedDimer::ModeCoordinates(rows.data() + (size_t)e.point * 2 * N, qp);
  PumpedDimer::ModeCoordinates(e.vector.data(), qv);
  INFO("parent q_a(0) = " << qp[0] << ", phi in (q_a, q_s, p_a, p_s): " << qv[0] << " " << qv[1] << " " << qv[2] << " " << qv[3]);
  REQUIRE(std::abs(qv[0]) + std::abs(qv[2]) < 1e-8);
  REQUIRE(std::abs(qp[2]) < 1e-12 * std::abs(qp[0])); // the parent's section: at rest
  const bool pump_positive = PumpedDimer::c * qp[0] > 0;
  REQUIRE(std::abs(pump_positive ? qv[1] : qv[3]) < 0.1 * std::abs(pump_positive ? qv[3] : qv[1]));

  // the doubled family
  OwnedVec Xs;
  bool found;
  PCHK(pd.shoot.CreateUnknowns(Xs.out()));
  PCHK(loc.OrbitAt(e.point, e.sigma, Xs, &found));
  REQUIRE(found);
  REQUIRE(SwitchedPeriodMultiple(e.kind) == 2);
  PeriodMultipleScope doubled(pd.flow, 2);
  Branch start, other, b;
  bool pinned;
  PetscReal away;
  PCHK(StartSwitchedBranch(pd.shoot, Xs, e, 0.02, -1, &other, &pinned, &away));
  REQUIRE(pinned);
  PCHK(StartSwitchedBranch(pd.shoot, Xs, e, 0.02, 1, &start, &pinned, &away));
  REQUIRE(pinned);
  INFO("first step " << away << " along the critical eigenvector");
  REQUIRE(away > 0.9);
  // the two sides of phi are one family (here also mirror images, q_s -> -q_s): the same orbit's energy and period
  REQUIRE(std::abs(other.energy[1] / start.energy[1] - 1) < 1e-9);
  REQUIRE(std::abs(other.period[1] / start.period[1] - 1) < 1e-9);
  ContinuationOptions cs;
  cs.verbose = PETSC_FALSE;
  cs.max_change = 0.05;
  cs.max_points = 20;
  PCHK(ContinueBranch(pd.shoot, nullptr, 0, cs, "doubled", &b, nullptr, &start));
  REQUIRE(b.energy.size() == 20);
  // point 0: the parent's orbit at the located point, traversed twice
  {
    OwnedVec zs;
    PetscReal Ts, bs;
    PCHK(pd.lat.CreateStateVector(zs.out()));
    PCHK(pd.shoot.Unpack(Xs, zs, &Ts, &bs));
    REQUIRE(b.period[0] == 2 * Ts);
    REQUIRE(std::abs(Ts / Tp - 1) < 1e-9);
  }
  REQUIRE(std::abs(b.energy[0] / e.energy - 1) < 1e-8);
  const std::vector<PetscReal> z0 = AllRows(b);
  // the pumped mode's amplitude sqrt(q_s^2 + (p_s / W)^2), W = 2 pi / T its frequency, relative to |z*|
  std::vector<PetscReal> amp;
  for (size_t k = 0; k < b.energy.size(); k++) {
    PetscReal q[4];
    PumpedDimer::ModeCoordinates(z0.data() + k * 2 * N, q);
    const PetscReal W = 2 * PETSC_PI / b.period[k];
    amp.push_back(std::hypot(q[1], q[3] / W));
  }
  INFO("pumped amplitude at the located point " << amp[0] << ", then " << amp[1] << " " << amp[5] << " " << amp.back());
  REQUIRE(amp[0] < 1e-8);
  // period 2T and not T-periodic: z(T/2) is far from z0 (the mirror point z* - eps phi, not z*),
  // z(T) is z0 to the Newton tolerance
  OwnedVec z, zT;
  PCHK(pd.lat.CreateStateVector(z.out()));
  PCHK(VecDuplicate(z, zT.out()));
  PetscReal worst_closure = 0, least_half = 1e300;
  for (size_t k = 1; k < b.energy.size(); k++) {
    REQUIRE(std::abs(b.period[k] / (2 * Tp) - 1) < 0.05);
    REQUIRE(b.energy[k] > e.energy); // on the unstable side of the parent (averaging: E - E* ~ w_a I_s)
    PetscReal nz0, dz;
    PCHK(StateFromRow(pd.lat, z0.data() + k * 2 * N, z));
    PCHK(VecNorm(z, NORM_2, &nz0));
    PCHK(pd.flow.Integrate(z, b.period[k], b.beta[k], zT));
    PCHK(VecAXPY(zT, -1.0, z));
    PCHK(VecNorm(zT, NORM_2, &dz));
    worst_closure = std::max(worst_closure, dz / nz0);
    PCHK(pd.flow.Integrate(z, 0.5 * b.period[k], b.beta[k], zT));
    PCHK(VecAXPY(zT, -1.0, z));
    PCHK(VecNorm(zT, NORM_2, &dz));
    least_half = std::min(least_half, dz / nz0);
  }
  INFO("closure |z(T) - z0| / |z0| at most " << worst_closure << "; |z(T/2) - z0| / |z0| at least " << least_half);
  REQUIRE(worst_closure < 1e-9);
  REQUIRE(least_half > 1e-2);
  // the root law: amp^2 is linear in E - E* and in the frequency shift 2 W - w*, its fits
  // over the first points vanishing at the located point (within 5 % of their span), and
  // amp against E - E* has log-log slope 1/2
  const int m = 5;
  std::vector<PetscReal> dE, dW, a2;
  for (int k = 1; k <= m; k++) dE.push_back(b.energy[k] - e.energy), dW.push_back(2 * 2 * PETSC_PI / b.period[k] - e.omega), a2.push_back(amp[k] * amp[k]);
  PetscReal sE, xE, sW, xW;
  FitLine(dE, a2, &sE, &xE);
  FitLine(dW, a2, &sW, &xW);
  const PetscReal root = std::log(amp[m] / amp[1]) / std::log(dE[m - 1] / dE[0]);
  INFO("amp^2 = " << sE << " (E - E*) vanishes at E* + " << xE << " (span " << dE.back() << "); = " << sW << " (2W - w*) vanishes at w* + " << xW << " (span "
                  << dW.back() << "); log-log slope " << root);
  PCHK(PetscPrintf(
      PETSC_COMM_WORLD,
      "  period doubling: eps* located %.10f, Mathieu to eps^3 %.10f, integrated %.10f; doubled family: closure <= %.1e, |z(T/2) - z0| / |z0| >= %.3f, "
      "amp^2 fits vanish at E* %+.1e (span %.1e) and w* %+.1e (span %.1e), log-log slope %.4f\n",
      (double)eps_loc, (double)eps_th, (double)eps_ex, (double)worst_closure, (double)least_half, (double)xE, (double)dE.back(), (double)xW, (double)dW.back(),
      (double)root));
  REQUIRE(std::abs(xE) < 0.05 * dE.back());
  REQUIRE(std::abs(xW) < 0.05 * std::abs(dW.back()));
  REQUIRE(std::abs(root - 0.5) < 0.05);
}
