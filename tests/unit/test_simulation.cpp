// Forced and free runs: effects composed per scene (counters), energy
// conservation tied to the TS tolerance, the cut-off.
#include "bands/linear_modes.hpp"
#include "energy_trace.hpp"
#include "helpers.hpp"
#include "timeint/simulation.hpp"
#include <cmath>

using namespace nltopo;
using namespace nltopo::test;

static ToneBurstOptions SiteBurst(PetscReal S, PetscReal estar)
{
  ToneBurstOptions o;
  o.profile = ForceProfile::Site;
  o.omega = std::sqrt(3.0);
  o.site = 51; // model.md's site 52 = m + 1
  o.amplitude = S;
  o.energy = estar;
  return o;
}

TEST_CASE("a linear scene never runs the cubic kernel; a nonlinear one always does", "[effects]")
{
  for (PetscReal Gamma : {0.0, 0.5}) {
    LatticeParams p;
    p.Gamma = Gamma;
    Lattice lat;
    PCHK(lat.Setup(PETSC_COMM_WORLD, p));
    ToneBurst burst;
    PCHK(burst.Setup(lat, SiteBurst(0.05, 1e30), nullptr));
    SimulationOptions so;
    so.t_final = 50;
    SimulationResult r;
    PCHK(Simulate(*Effects(lat, &burst), so, NULL, NULL, &r));
    REQUIRE(r.counters.rhs > 0);
    REQUIRE(r.counters.linear == r.counters.rhs);
    REQUIRE(r.counters.cubic == (Gamma == 0 ? 0 : r.counters.rhs));
    REQUIRE(r.counters.forcing == r.counters.rhs); // never cut off (E* = 1e30)
    REQUIRE(!r.reached);
  }
}

TEST_CASE("after the cut-off the forcing is never evaluated; no forcing, no forcing calls", "[effects]")
{
  LatticeParams p;
  Lattice lat;
  PCHK(lat.Setup(PETSC_COMM_WORLD, p));
  ToneBurst burst;
  PCHK(burst.Setup(lat, SiteBurst(0.05, 0.2), nullptr));
  // Two runs share every step up to t_off; the longer one must not evaluate the forcing once more.
  SimulationResult a, b;
  SimulationOptions so;
  so.t_final = 500;
  PCHK(Simulate(*Effects(lat, &burst), so, NULL, NULL, &a));
  so.t_final = 800;
  PCHK(Simulate(*Effects(lat, &burst), so, NULL, NULL, &b));
  REQUIRE(a.reached);
  REQUIRE(b.reached);
  REQUIRE(a.t_off == b.t_off);
  REQUIRE(b.counters.rhs > a.counters.rhs + 100);
  REQUIRE(b.counters.forcing == a.counters.forcing);
  REQUIRE(a.counters.forcing < a.counters.rhs);
  // The cut-off is located: E(t_off) = E* to the event tolerance, then conserved.
  REQUIRE(b.energy_final == Approx(0.2).epsilon(1e-3));

  ToneBurstOptions none = SiteBurst(0.05, 0.2);
  none.profile = ForceProfile::None;
  ToneBurst off;
  PCHK(off.Setup(lat, none, nullptr));
  SimulationResult c;
  so.t_final = 50;
  PCHK(Simulate(*Effects(lat, &off), so, NULL, NULL, &c));
  REQUIRE(c.counters.forcing == 0);
  REQUIRE(c.energy_final == 0.0);
}

// Free run from the insulated mode's shape with E = 100 (strongly nonlinear).
static PetscErrorCode FreeRun(const Lattice &lat, Vec z0, PetscReal t_final, EnergyTrace *trace, PetscReal *drift)
{
  SimulationOptions so;
  so.t_final = t_final;
  so.sample_dt = 1.0;
  SimulationResult r;
  PetscFunctionBeginUser;
  PetscCall(Simulate(*Effects(lat), so, z0, trace, &r));
  PetscReal d = 0;
  for (PetscReal e : trace->e) d = std::max(d, std::abs(e - trace->e[0]) / trace->e[0]);
  *drift = d;
  PetscFunctionReturn(0);
}

TEST_CASE("free run at E = 100 conserves energy to a bound tied to the TS tolerance", "[simulation]")
{
  LatticeParams p;
  Lattice lat;
  PCHK(lat.Setup(PETSC_COMM_WORLD, p));
  LinearModes modes;
  PCHK(modes.Compute(lat, LinearModesOptions()));
  OwnedVec z0;
  PCHK(lat.CreateStateVector(z0.out()));
  auto v0 = Gather(modes.Insulated());
  for (auto &x : v0) x *= std::sqrt(200.0); // E = 1/2 v.v = 100
  SetState(lat, std::vector<PetscReal>(lat.N(), 0.0), v0, z0);
  EnergyParts e0;
  PCHK(Effects(lat)->Energy(z0, &e0));
  REQUIRE(e0.Total() == Approx(100.0).epsilon(1e-12));

  PetscReal d8, d10, ds;
  {
    ScopedOptions o({{"-sim_ts_rtol", "1e-8"}, {"-sim_ts_atol", "1e-8"}});
    EnergyTrace tr;
    PCHK(FreeRun(lat, z0, 100, &tr, &d8));
  }
  {
    ScopedOptions o({{"-sim_ts_rtol", "1e-10"}, {"-sim_ts_atol", "1e-10"}});
    EnergyTrace tr;
    PCHK(FreeRun(lat, z0, 100, &tr, &d10));
  }
  // dopri5's error per unit time scales ~ tol: 100x tighter tolerance, >= 30x less drift.
  REQUIRE(d8 < 1e3 * 1e-8);
  REQUIRE(d10 < 1e3 * 1e-10);
  REQUIRE(d8 / d10 > 30);
  EnergyTrace trs; // the Stormer-Verlet run at dt = 0.01
  {
    // Symplectic (Stormer-Verlet, fixed dt): bounded energy error, no secular drift.
    ScopedOptions o({{"-sim_ts_type", "basicsymplectic"}, {"-sim_ts_basicsymplectic_type", "2"}, {"-sim_ts_dt", "0.01"}});
    EnergyTrace &tr = trs;
    PCHK(FreeRun(lat, z0, 200, &tr, &ds));
    const size_t h = tr.e.size() / 2;
    PetscReal first = 0, second = 0;
    for (size_t k = 0; k < tr.e.size(); k++) (k < h ? first : second) = std::max(k < h ? first : second, std::abs(tr.e[k] - 100.0) / 100.0);
    INFO("symplectic max error first half " << first << " second half " << second);
    REQUIRE(ds < 1e-2);
    REQUIRE(second < 1.5 * first);
  }
  {
    // Stormer-Verlet is second order: it conserves a modified energy H~ = H + dt^2 H2 + O(dt^4)
    // exactly, so H(t) - H(0) = dt^2 (H2(0) - H2(t)) + O(dt^4) along the trajectory: halving dt
    // divides the energy error at every time by 4. Compared sample by sample (the same times
    // t = 1, 2, ... s, both dt divide 1 s) over the first 20 s, before the two runs' trajectories
    // separate (E = 100 is chaotic: the whole-run max ratio falls to 3.6 at 200 s). The least-squares
    // ratio sum(a b) / sum(b b) is 4 to O((omega dt)^2) ~ 1e-3 (measured 4.0015; 4.0036 for the max).
    ScopedOptions o({{"-sim_ts_type", "basicsymplectic"}, {"-sim_ts_basicsymplectic_type", "2"}, {"-sim_ts_dt", "0.005"}});
    EnergyTrace half;
    PetscReal dh;
    PCHK(FreeRun(lat, z0, 20, &half, &dh));
    REQUIRE(half.e.size() == 21);
    REQUIRE(trs.t.size() > 21);
    PetscReal ab = 0, bb = 0;
    for (size_t k = 0; k < half.e.size(); k++) {
      REQUIRE(std::abs(trs.t[k] - half.t[k]) < 1e-9);
      const PetscReal a = trs.e[k] - trs.e[0], b = half.e[k] - half.e[0];
      ab += a * b;
      bb += b * b;
    }
    INFO("drift rk5dp 1e-8: " << d8 << ", 1e-10: " << d10 << ", symplectic dt 0.01: " << ds << "; energy error ratio dt 0.01 / 0.005 over 20 s: " << ab / bb);
    REQUIRE(bb > 0);
    CHECK(std::abs(ab / bb - 4) < 0.05);
  }
}

TEST_CASE("a cut-off inside a long step is found: E reaches E* between two step ends that are below it", "[simulation]")
{
  // E* = 1e-3 at omega = 1.644 (the sweep's first row): the driven energy
  // oscillates with period pi / omega ~ 1.9 and first touches E* at t = 420.31;
  // rkn dep86 at 1e-6 takes ~1 s steps there, and a test at step ends alone put
  // the cut-off one energy peak later (t = 421.89). Reference: rk 5dp at 1e-10.
  LatticeParams p;
  Lattice lat;
  PCHK(lat.Setup(PETSC_COMM_WORLD, p));
  ToneBurstOptions fo = SiteBurst(0.016691767673341795, 1e-3);
  fo.omega = 1.644;
  ToneBurst burst;
  PCHK(burst.Setup(lat, fo, nullptr));
  SimulationOptions so;
  so.t_final = 500;
  SimulationResult ref, rkn;
  {
    ScopedOptions opt({{"-sim_ts_rtol", "1e-10"}, {"-sim_ts_atol", "1e-10"}});
    PCHK(Simulate(*Effects(lat, &burst), so, NULL, NULL, &ref));
  }
  {
    ScopedOptions opt({{"-sim_ts_type", "rkn"}, {"-sim_ts_rkn_scheme", "dep86"}, {"-sim_ts_rtol", "1e-6"}, {"-sim_ts_atol", "1e-6"}});
    PCHK(Simulate(*Effects(lat, &burst), so, NULL, NULL, &rkn));
  }
  INFO("t_off: rk 5dp 1e-10 " << ref.t_off << ", rkn dep86 1e-6 " << rkn.t_off << " in " << rkn.steps << " steps");
  REQUIRE(ref.reached);
  REQUIRE(rkn.reached);
  REQUIRE(ref.t_off == Approx(420.31).margin(0.01));
  REQUIRE(std::abs(rkn.t_off - ref.t_off) < 0.02); // the same crossing: the next one is ~1.9 later
  REQUIRE(500.0 / rkn.steps > 0.3);                // the steps are long against the energy's period
}

TEST_CASE("-sim_dt_quartic_energy: the fixed step shrinks as E^(-1/4) and keeps the energy error of the E_q level", "[simulation]")
{
  // In the quartic regime a bond's frequency grows as E^(1/4), so a fixed-step
  // scheme of order p has an energy error ~ (h omega)^p that grows with E at a
  // fixed h; h = dt (E_q / E)^(1/4) holds h omega, and the error, at its E_q
  // level. Free runs from the insulated mode's shape, symsplit bm4 (order 4).
  LatticeParams p;
  Lattice lat;
  PCHK(lat.Setup(PETSC_COMM_WORLD, p));
  LinearModes modes;
  PCHK(modes.Compute(lat, LinearModesOptions()));
  auto run = [&](PetscReal E, PetscReal eq, PetscReal *err, PetscInt *steps) {
    OwnedVec z0;
    PCHK(lat.CreateStateVector(z0.out()));
    auto v0 = Gather(modes.Insulated());
    for (auto &x : v0) x *= std::sqrt(2 * E);
    SetState(lat, std::vector<PetscReal>(lat.N(), 0.0), v0, z0);
    SimulationOptions so;
    so.t_final = 100;
    so.sample_dt = 0.5;
    so.dt_quartic_energy = eq;
    SimulationResult r;
    EnergyTrace tr;
    ScopedOptions o({{"-sim_ts_type", "symsplit"}, {"-sim_ts_dt", "0.4"}});
    PCHK(Simulate(*Effects(lat), so, z0, &tr, &r));
    PetscReal d = 0;
    for (PetscReal e : tr.e) d = std::max(d, std::abs(e - E) / E);
    *err = d;
    *steps = r.steps;
  };
  PetscReal e1, e100, e100_fixed, e_below;
  PetscInt s1, s100, s100_fixed, s_below;
  run(1, 1, &e1, &s1);                   // at E_q: the step as given
  run(100, 1, &e100, &s100);             // E = 100 E_q: h = 0.4 / 100^(1/4)
  run(100, 0, &e100_fixed, &s100_fixed); // the rule off
  run(100, 1000, &e_below, &s_below);    // E below E_q: the step as given
  INFO("max relative energy error: E = 1, h = 0.4: " << e1 << "; E = 100, h = 0.4 / 100^(1/4): " << e100 << "; E = 100, h = 0.4: " << e100_fixed);
  REQUIRE(s1 == 250);
  REQUIRE(s100_fixed == 250);
  REQUIRE(s_below == 250);
  REQUIRE(s100 == (PetscInt)std::ceil(100 / (0.4 / std::pow(100.0, 0.25)) - 1e-9)); // 791 equal steps
  REQUIRE(e100_fixed > 100 * e100); // without the rule: (omega h)^4 is ~100x larger, and more as the step nears stability
  REQUIRE(e100 < 3 * e1);           // with it: the E_q level (the linear part makes E = 1 not purely quartic)
}

// The RMS window against known truth: a single linear mode u = phi cos(omega
// t) of the linear lattice (Gamma = 0), released from rest, has the window
// average of u_i^2 over [0, T] equal to phi_i^2 (1/2 + sin(2 omega T) / (4
// omega T)). The adaptive types integrate the window on their own stages, so
// the RMS follows the tolerance, on steps far too long for the trapezoid.
TEST_CASE("the RMS window of a single linear mode is exact to the run's accuracy (rk 8vr, rk 5dp, rkn dep1210)", "[simulation]")
{
  Lattice lat;
  LinearModes modes;
  LatticeParams p;
  p.Gamma = 0;
  PCHK(lat.Setup(PETSC_COMM_WORLD, p));
  PCHK(modes.Compute(lat, LinearModesOptions()));
  REQUIRE(modes.Named().interface >= 0);
  const PetscInt j = modes.Named().interface; // the interface mode (an eigenvector, largest entry 1 in 2-norm units)
  const auto phi = Gather(modes.Mode(j));
  const PetscReal omega = modes.Omega()[j], T = 50.3, avg = 0.5 + std::sin(2 * omega * T) / (4 * omega * T);
  OwnedVec z0;
  PCHK(lat.CreateStateVector(z0.out()));
  SetState(lat, phi, std::vector<PetscReal>(lat.N(), 0.0), z0);
  struct Case {
    const char *type, *key, *scheme, *tol;
    PetscReal bound, mean_step; // the RMS error bound; the mean step is at least this
  };
  const Case cases[] = {{"rk", "-sim_ts_rk_type", "8vr", "1e-12", 1e-9, 0.05},
                        {"rk", "-sim_ts_rk_type", "5dp", "1e-11", 1e-8, 0.01},
                        {"rkn", "-sim_ts_rkn_scheme", "dep1210", "1e-12", 1e-9, 0.3}};
  PetscReal phimax = 0;
  for (PetscReal x : phi) phimax = std::max(phimax, std::abs(x));
  for (const Case &c : cases) {
    ScopedOptions o({{"-sim_ts_type", c.type}, {c.key, c.scheme}, {"-sim_ts_rtol", c.tol}, {"-sim_ts_atol", c.tol}});
    SimulationOptions so;
    so.t_final = T;
    so.sample_dt = 0;
    SimulationResult r;
    PCHK(Simulate(*Effects(lat), so, z0, NULL, &r));
    REQUIRE(r.window_start == 0);
    const auto rms = Gather(r.rms);
    PetscReal err = 0;
    for (PetscInt i = 0; i < lat.N(); i++) err = std::max(err, std::abs(rms[i] - std::abs(phi[i]) * std::sqrt(avg)) / (phimax * std::sqrt(avg)));
    INFO(c.scheme << ": " << r.steps << " steps (mean " << T / r.steps << "), max RMS error relative to the largest " << err);
    CHECK(T / r.steps > c.mean_step); // long steps: the trapezoid over them would be far off
    CHECK(err < c.bound);
    CHECK(r.nl_ratio == 0);
  }
}
