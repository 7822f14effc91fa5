// The symsplit TS type (timeint/ts_symsplit.hpp) against known truth: the
// observed order of every scheme on the harmonic oscillator and on the Duffing
// oscillator (exact Jacobi-elliptic solution), exact symplecticity of the
// one-step map, bounded energy error over 10^5 periods, the Hermite
// interpolant's order, the generic (RHS) path equal to the raw-array path, and
// the forced lattice run: cut-off at E*, the same result on 1 and 2 ranks.
#include "helpers.hpp"
#include "oscillators.hpp"
#include "timeint/simulation.hpp"
#include "timeint/ts_symsplit.hpp"
#include <cmath>
#include <algorithm>
#include <cstring>

using namespace nltopo;
using namespace nltopo::test;

namespace {

// A symsplit TS on one rank with the given scheme (set through its option, as a user would).
TS NewSymSplit(const char *scheme)
{
  TS ts;
  PCHK(TSCreate(PETSC_COMM_SELF, &ts));
  PCHK(TSSetOptionsPrefix(ts, "symsplit_unit_"));
  PCHK(TSSetType(ts, TSSYMSPLIT));
  PCHK(PetscOptionsSetValue(NULL, "-symsplit_unit_ts_symsplit_scheme", scheme));
  PCHK(TSSetFromOptions(ts));
  PCHK(PetscOptionsClearValue(NULL, "-symsplit_unit_ts_symsplit_scheme"));
  return ts;
}

struct RunSpec {
  const char *scheme;
  PetscReal h, t_final, eps, u0;
  bool generic = false; // the RHS path instead of TSSetAcceleration
};

// Integrates one oscillator and returns (u, v) at t_final.
void Integrate(const RunSpec &s, PetscReal *u, PetscReal *v, PetscInt *calls = nullptr)
{
  TS ts;
  Vec z;
  Oscillator osc;
  osc.eps = s.eps;
  z = OscillatorState(s.u0, 0.0);
  ts = NewSymSplit(s.scheme);
  PCHK(TSSetRHSFunction(ts, NULL, OscRhs, &osc));
  if (!s.generic) PCHK(TSSetAcceleration(ts, OscAcceleration, &osc));
  PCHK(TSSetTimeStep(ts, s.h));
  PCHK(TSSetMaxTime(ts, s.t_final));
  PCHK(TSSetExactFinalTime(ts, TS_EXACTFINALTIME_MATCHSTEP));
  PCHK(TSSolve(ts, z));
  const PetscScalar *x;
  PCHK(VecGetArrayRead(z, &x));
  *u = x[0];
  *v = x[1];
  PCHK(VecRestoreArrayRead(z, &x));
  if (calls) *calls = s.generic ? -1 : osc.calls;
  PCHK(TSDestroy(&ts));
  PCHK(VecDestroy(&z));
}

PetscInt SchemeIndex(const char *name)
{
  for (PetscInt i = 0; i < SymSplitSchemeCount(); i++)
    if (!std::strcmp(SymSplitScheme(i).name, name)) return i;
  return -1;
}

} // namespace

TEST_CASE("symsplit: every scheme has its order on the harmonic and the Duffing oscillator", "[symsplit][serial]")
{
  for (PetscInt i = 0; i < SymSplitSchemeCount(); i++) {
    const SymSplitSchemeInfo info = SymSplitScheme(i);
    for (PetscReal eps : {0.0, 1.0}) {
      const PetscReal A = 1, T = 10;
      double uT, vT;
      OscillatorExact(eps, A, T, &uT, &vT);
      auto Err = [&](PetscReal u, PetscReal v) { return std::hypot(u - uT, v - vT); };
      // the largest h = 2^-k with an error below 1e-8 (asymptotic range), then h/2:
      // the errors stay far above rounding even at order 8
      PetscReal h = 1, u1, v1, u2, v2, u3, v3;
      for (;; h /= 2) {
        Integrate({info.name, h, T, eps, A}, &u1, &v1);
        if (Err(u1, v1) < 1e-8) break;
      }
      Integrate({info.name, h / 2, T, eps, A}, &u2, &v2);
      Integrate({info.name, h / 4, T, eps, A}, &u3, &v3);
      // the order from (h, h/2), or from (h/2, h/4) where an optimised scheme's
      // small leading term still competes with the next one at h
      const PetscReal e1 = Err(u1, v1), e2 = Err(u2, v2), e3 = Err(u3, v3), p1 = std::log2(e1 / e2), p2 = std::log2(e2 / e3);
      INFO(info.name << " eps " << eps << ": errors " << e1 << ", " << e2 << ", " << e3 << ", observed orders " << p1 << ", " << p2);
      CHECK(e2 > 1e-13); // the ratio measures the method, not rounding
      CHECK((std::abs(p1 - info.order) < 0.3 || (e3 > 3e-13 && std::abs(p2 - info.order) < 0.3)));
    }
  }
}

TEST_CASE("symsplit: the raw-array path equals the RHS path and costs the scheme's accelerations per step", "[symsplit][serial]")
{
  for (PetscInt i = 0; i < SymSplitSchemeCount(); i++) {
    const SymSplitSchemeInfo info = SymSplitScheme(i);
    PetscReal u1, v1, u2, v2;
    PetscInt calls;
    Integrate({info.name, 0.1, 10, 1.0, 1.0, false}, &u1, &v1, &calls);
    Integrate({info.name, 0.1, 10, 1.0, 1.0, true}, &u2, &v2);
    CHECK(u1 == u2);
    CHECK(v1 == v2);
    CHECK(calls == 100 * info.evals + 1); // FSAL: one start-up evaluation, then evals per step
  }
}

TEST_CASE("symsplit: the one-step map is symplectic to rounding (J^T Omega J = Omega)", "[symsplit][serial]")
{
  // A 2-site nonlinear chain u1'' = -(2 u1 - u2) - u1^3, u2'' = -(2 u2 - u1) - u2^3
  // and its tangent flow for the 4 unit vectors: positions (u, du_1..du_4),
  // velocities (v, dv_1..dv_4). Kicks depend on positions only, so the scheme
  // applied to the augmented system is the exact derivative of its map.
  struct Chain {
    static PetscErrorCode Acc(TS, PetscReal, Vec z, PetscScalar *a, void *)
    {
      const PetscScalar *x;
      PetscFunctionBeginUser;
      PetscCall(VecGetArrayRead(z, &x));
      const PetscReal u1 = x[0], u2 = x[1];
      a[0] = -(2 * u1 - u2) - u1 * u1 * u1;
      a[1] = -(2 * u2 - u1) - u2 * u2 * u2;
      for (int k = 0; k < 4; k++) {
        const PetscReal d1 = x[2 + 2 * k], d2 = x[3 + 2 * k];
        a[2 + 2 * k] = -(2 + 3 * u1 * u1) * d1 + d2;
        a[3 + 2 * k] = d1 - (2 + 3 * u2 * u2) * d2;
      }
      PetscCall(VecRestoreArrayRead(z, &x));
      PetscFunctionReturn(0);
    }
  };
  for (PetscInt i = 0; i < SymSplitSchemeCount(); i++) {
    const SymSplitSchemeInfo info = SymSplitScheme(i);
    TS ts;
    Vec z;
    PetscScalar *x;
    PCHK(VecCreateSeq(PETSC_COMM_SELF, 20, &z));
    PCHK(VecZeroEntries(z));
    PCHK(VecGetArray(z, &x));
    x[0] = 0.9, x[1] = -0.4, x[10] = 0.3, x[11] = 0.7; // a large-amplitude state
    // tangent k = unit vector e_k of (u1, u2, v1, v2)
    x[2 + 0] = 1, x[2 + 3] = 1;           // du of e_1, e_2
    x[10 + 2 + 4] = 1, x[10 + 2 + 7] = 1; // dv of e_3, e_4
    PCHK(VecRestoreArray(z, &x));
    ts = NewSymSplit(info.name);
    PCHK(TSSetAcceleration(ts, Chain::Acc, NULL));
    PCHK(TSSetTimeStep(ts, 0.3));
    PCHK(TSSetMaxSteps(ts, 1));
    PCHK(TSSetMaxTime(ts, 100));
    PCHK(TSSolve(ts, z));
    PCHK(VecGetArray(z, &x));
    double J[4][4]; // J[row][k]: rows u1, u2, v1, v2
    for (int k = 0; k < 4; k++) { J[0][k] = x[2 + 2 * k], J[1][k] = x[3 + 2 * k], J[2][k] = x[12 + 2 * k], J[3][k] = x[13 + 2 * k]; }
    PCHK(VecRestoreArray(z, &x));
    double worst = 0;
    for (int r = 0; r < 4; r++)
      for (int c = 0; c < 4; c++) {
        double s = 0; // (J^T Omega J)_{rc}, Omega = [[0, I], [-I, 0]]
        for (int k = 0; k < 2; k++) s += J[k][r] * J[k + 2][c] - J[k + 2][r] * J[k][c];
        const double omega = (r < 2 && c == r + 2) ? 1 : (r >= 2 && c == r - 2) ? -1 : 0;
        worst = std::max(worst, std::abs(s - omega));
      }
    INFO(info.name << ": max |J^T Omega J - Omega| = " << worst);
    CHECK(worst < 1e-13);
    PCHK(TSDestroy(&ts));
    PCHK(VecDestroy(&z));
  }
}

TEST_CASE("symsplit: 10^5 periods of Duffing keep the energy error bounded, without drift", "[symsplit][serial]")
{
  // Verlet at 20 steps per period: the energy error oscillates at O(h^2) and
  // does not grow; a non-symplectic method of the same order drifts.
  struct Monitor {
    static PetscErrorCode Energy(TS, PetscInt step, PetscReal, Vec z, void *ctx)
    {
      auto *m = static_cast<std::vector<double> *>(ctx);
      const PetscScalar *x;
      PetscFunctionBeginUser;
      PetscCall(VecGetArrayRead(z, &x));
      const double e = 0.5 * x[1] * x[1] + 0.5 * x[0] * x[0] + 0.25 * x[0] * x[0] * x[0] * x[0];
      PetscCall(VecRestoreArrayRead(z, &x));
      const size_t block = step / 100000; // 5000 periods per block
      if (m->size() <= block) m->push_back(0);
      (*m)[block] = std::max((*m)[block], std::abs(e / 0.75 - 1)); // E(0) = 1/2 + 1/4
      PetscFunctionReturn(0);
    }
  };
  TS ts;
  Vec z;
  Oscillator osc;
  osc.eps = 1;
  std::vector<double> worst;
  z = OscillatorState(1.0, 0.0);
  ts = NewSymSplit("verlet");
  PCHK(TSSetAcceleration(ts, OscAcceleration, &osc));
  PCHK(TSMonitorSet(ts, Monitor::Energy, &worst, NULL));
  // Duffing A = 1: w^2 = 2, m = 1/4, period 4 K(m) / w = 4.768; 20 steps per period, 10^5 periods
  const PetscReal T = 4 * 1.6857503548125961 / std::sqrt(2.0);
  PCHK(TSSetTimeStep(ts, T / 20));
  PCHK(TSSetMaxSteps(ts, 2000000));
  PCHK(TSSetMaxTime(ts, 1e12));
  PCHK(TSSolve(ts, z));
  PCHK(TSDestroy(&ts));
  PCHK(VecDestroy(&z));
  REQUIRE(worst.size() >= 20);
  INFO("max relative energy error, first and last 5000 periods: " << worst.front() << ", " << worst.back());
  CHECK(worst.front() > 1e-4);                // h^2 error visible: the test can fail
  CHECK(worst.back() < 1.05 * worst.front()); // bounded: no growth over 10^5 periods
  CHECK(*std::max_element(worst.begin(), worst.end()) < 1.05 * worst.front());
}

TEST_CASE("symsplit: the interpolant is accurate to O(h^6) inside a step", "[symsplit][serial]")
{
  // One step of yoshida8 (error O(h^9)) on the harmonic oscillator, then the
  // interpolant at 0.3 of the step against cos(t): halving h divides the
  // error by about 2^6.
  double err[2];
  for (int j = 0; j < 2; j++) {
    const PetscReal h = j ? 0.25 : 0.5;
    TS ts;
    Vec z, x;
    Oscillator osc;
    z = OscillatorState(1.0, 0.0);
    PCHK(VecDuplicate(z, &x));
    ts = NewSymSplit("yoshida8");
    PCHK(TSSetAcceleration(ts, OscAcceleration, &osc));
    PCHK(TSSetTimeStep(ts, h));
    PCHK(TSSetMaxSteps(ts, 1));
    PCHK(TSSetMaxTime(ts, 100));
    PCHK(TSSolve(ts, z));
    PCHK(TSInterpolate(ts, 0.3 * h, x));
    const PetscScalar *a;
    PCHK(VecGetArrayRead(x, &a));
    err[j] = std::abs(a[0] - std::cos(0.3 * h)) + std::abs(a[1] + std::sin(0.3 * h));
    PCHK(VecRestoreArrayRead(x, &a));
    PCHK(TSDestroy(&ts));
    PCHK(VecDestroy(&z));
    PCHK(VecDestroy(&x));
  }
  INFO("interpolation errors " << err[0] << ", " << err[1]);
  CHECK(std::log2(err[0] / err[1]) > 5.0);
}

TEST_CASE("symsplit: a forced lattice run cuts off at E* and gives the same result on 1 and P ranks", "[symsplit]")
{
  // The paper-default lattice forced at the insulated frequency to E* = 1:
  // after the cut-off the energy stays at E* to the scheme's energy error.
  REQUIRE(SchemeIndex("yoshida6") >= 0);
  SimulationResult r[2];
  for (int j = 0; j < 2; j++) {
    r[j] =
        ShortForcedRun(j ? PETSC_COMM_WORLD : PETSC_COMM_SELF, {{"-sim_ts_type", "symsplit"}, {"-sim_ts_symsplit_scheme", "yoshida6"}, {"-sim_ts_dt", "0.05"}});
    REQUIRE(r[j].reached);
    INFO("t_off " << r[j].t_off << ", E_final " << r[j].energy_final);
    CHECK(std::abs(r[j].energy_final - 1) < 1e-7);
    CHECK(r[j].counters.forcing < r[j].counters.rhs); // no forcing after the cut-off
  }
  CHECK(std::abs(r[0].t_off - r[1].t_off) <= 1e-9 * r[0].t_off);
  CHECK(std::abs(r[0].mcr - r[1].mcr) <= 1e-10 * r[0].mcr);
  CHECK(std::abs(r[0].energy_final - r[1].energy_final) <= 1e-12);
}
