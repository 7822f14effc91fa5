// NNM continuation against known truth: the Duffing period (complete elliptic
// integral), the linear frequencies at low energy, closure of every stored
// orbit, and a branch with energy folds that is followed through them.
#include "bands/linear_modes.hpp"
#include "helpers.hpp"
#include "nnm_fixture.hpp"
#include "orbits/continuation.hpp"
#include <cmath>
#include <limits>

using namespace nltopo;
using namespace nltopo::test;

namespace {

using Fixture = NnmFixture;

// Complete elliptic integral of the first kind K(m) by the arithmetic-geometric mean.
PetscReal EllipticK(PetscReal m)
{
  PetscReal a = 1, b = std::sqrt(1 - m);
  for (int i = 0; i < 60; i++) {
    const PetscReal an = (a + b) / 2;
    b = std::sqrt(a * b);
    a = an;
  }
  return PETSC_PI / (2 * a);
}

ContinuationOptions Quiet()
{
  ContinuationOptions o;
  o.verbose = PETSC_FALSE;
  return o;
}

} // namespace

TEST_CASE("Duffing oscillator: period along the branch equals the elliptic-integral period to 1e-8", "[continuation]")
{
  // The right layout with one cell is two sites joined by one stiff cubic bond;
  // its antisymmetric mode u1 = -u2 = x obeys x'' + w0^2 x + c x^3 = 0 with
  // w0^2 = k_hat + k1 and c = 8 Gamma, the Duffing oscillator; E = 2 e_Duffing.
  LatticeParams p;
  p.layout = Layout::Right;
  p.cells = 1;
  Fixture f;
  PCHK(f.Setup(p));
  ContinuationOptions o = Quiet();
  o.energy_max = 100;
  Branch b;
  PCHK(f.Continue(1, o, &b)); // mode 1: the antisymmetric, nonlinear one
  REQUIRE(b.reached_max);
  const PetscReal w02 = p.KHat() + p.K1(), c = 8 * p.Gamma;
  PetscReal worst = 0;
  for (size_t k = 0; k < b.energy.size(); k++) {
    const PetscReal e = b.energy[k] / 2;
    const PetscReal A2 = (-w02 / 2 + std::sqrt(w02 * w02 / 4 + c * e)) / (c / 2); // e = w0^2 A^2/2 + c A^4/4
    const PetscReal w2 = w02 + c * A2, m = c * A2 / (2 * w2);
    const PetscReal T = 4 * EllipticK(m) / std::sqrt(w2);
    worst = std::max(worst, std::abs(b.period[k] - T) / T);
  }
  INFO("worst relative period error " << worst << " over " << b.energy.size() << " points up to E = " << b.energy.back());
  REQUIRE(worst < 1e-8);
  REQUIRE(b.omega.back() / b.omega.front() > 2); // strongly hardened
}

TEST_CASE("every branch starts at its linear frequency (to 1e-6) at E = 1e-5", "[continuation]")
{
  LatticeParams p;
  p.cells = 2; // N = 10
  Fixture f;
  PCHK(f.Setup(p));
  ContinuationOptions o = Quiet();
  o.max_points = 1;
  for (PetscInt j = 0; j < f.lat.N(); j++) {
    Branch b;
    PCHK(f.Continue(j, o, &b));
    REQUIRE(b.energy[0] == Approx(1e-5).epsilon(1e-6)); // the energy constraint, to the Newton tolerance
    REQUIRE(b.omega[0] == Approx(f.modes.Omega()[j]).epsilon(1e-6));
  }
}

TEST_CASE("a branch with energy folds is followed through them, and every orbit closes", "[continuation][once]")
{
  // [once]: at 2 ranks the same continuation through the folds runs in test_bifurcations.cpp
  // ("energy folds of a folded branch are located ..."); repeating it here only repeats the physics.
  // Mode 0 of the N = 6 interface lattice: its energy rises to ~66, falls to ~8
  // and rises again (two folds) while the frequency turns twice.
  // rk 5dp: with the default splitting the secant steps cut the sharp fold at
  // E ~ 496 at more than a right angle, which the reversal check below counts.
  ScopedOptions rk{{"-nnm_ts_type", "rk"}};
  LatticeParams p;
  p.cells = 1;
  Fixture f;
  PCHK(f.Setup(p));
  ContinuationOptions o = Quiet();
  o.energy_max = 1e3;
  Branch b;
  PCHK(f.Continue(0, o, &b));
  REQUIRE(b.reached_max);
  const size_t n = b.energy.size();
  PetscInt folds = 0;
  for (size_t k = 1; k + 1 < n; k++)
    if ((b.energy[k] - b.energy[k - 1]) * (b.energy[k + 1] - b.energy[k]) < 0) folds++;
  REQUIRE(folds >= 2);
  // No reversal: consecutive steps in (z0, T) never point backwards (rank 0 holds the rows).
  const PetscInt N = f.lat.N();
  int reversals = 0;
  if (Rank() == 0)
    for (size_t k = 1; k + 1 < n; k++) {
      PetscReal dot = (b.period[k] - b.period[k - 1]) * (b.period[k + 1] - b.period[k]);
      for (PetscInt i = 0; i < 2 * N; i++) dot += (b.z0[k * 2 * N + i] - b.z0[(k - 1) * 2 * N + i]) * (b.z0[(k + 1) * 2 * N + i] - b.z0[k * 2 * N + i]);
      reversals += dot <= 0;
    }
  MPI_Bcast(&reversals, 1, MPI_INT, 0, PETSC_COMM_WORLD);
  REQUIRE(reversals == 0);
  // Every stored orbit, re-integrated for one period, closes and has the stored energy.
  std::vector<PetscReal> rows(b.z0);
  PetscInt nrow = n;
  MPI_Bcast(&nrow, 1, MPIU_INT, 0, PETSC_COMM_WORLD);
  rows.resize(nrow * 2 * N);
  MPI_Bcast(rows.data(), (int)rows.size(), MPIU_REAL, 0, PETSC_COMM_WORLD);
  OwnedVec z, zT;
  PCHK(f.lat.CreateStateVector(z.out()));
  PCHK(VecDuplicate(z, zT.out()));
  PetscReal worst = 0, worst0 = 0, worst_e = 0;
  for (PetscInt k = 0; k < nrow; k++) {
    std::vector<PetscReal> u(rows.begin() + k * 2 * N, rows.begin() + k * 2 * N + N), v(rows.begin() + k * 2 * N + N, rows.begin() + (k + 1) * 2 * N);
    SetState(f.lat, u, v, z);
    // With the solved beta (the unfolding parameter; it absorbs the fixed-step
    // integrator's energy defect, |beta| ~ 1e-8 near the modal interactions
    // of this branch) the stored orbit is a fixed point of the discrete flow.
    PCHK(f.flow.Integrate(z, b.period[k], b.beta[k], zT));
    EnergyParts e;
    PCHK(Effects(f.lat)->Energy(z, &e));
    PetscReal nz, d;
    PCHK(VecNorm(z, NORM_2, &nz));
    PCHK(VecAXPY(zT, -1.0, z));
    PCHK(VecNorm(zT, NORM_2, &d));
    worst = std::max(worst, d / nz);
    PCHK(f.flow.Integrate(z, b.period[k], 0.0, zT)); // the conservative flow itself
    PCHK(VecAXPY(zT, -1.0, z));
    PCHK(VecNorm(zT, NORM_2, &d));
    worst0 = std::max(worst0, d / nz);
    worst_e = std::max(worst_e, std::abs(e.Total() - b.energy[k]) / b.energy[k]);
  }
  INFO("worst closure " << worst << " (beta = 0: " << worst0 << "), worst energy mismatch " << worst_e);
  REQUIRE(worst < 1e-9);
  REQUIRE(worst0 < 1e-4); // bounded by the integration error (-nnm_steps_per_period 128)
  REQUIRE(worst_e < 1e-12);
}

TEST_CASE("a resume state that is not finite stops the branch, never loops (issue 34, class 7)", "[continuation]")
{
  // The step-collapse test must fire on a NaN or inf norm or step: before, a
  // NaN orbit halved "ds 0 -> 0" without end. (A -cont_resume file holding
  // one is refused before this: studies/continuation_record.cpp.)
  LatticeParams p;
  p.cells = 1;
  Fixture f;
  PCHK(f.Setup(p));
  ContinuationOptions o = Quiet();
  o.max_points = 3;
  Branch b;
  PCHK(f.Continue(0, o, &b));
  REQUIRE(b.energy.size() == 3);
  o.max_points = 6;
  const PetscReal nan = std::numeric_limits<PetscReal>::quiet_NaN(), inf = std::numeric_limits<PetscReal>::infinity();
  for (int which = 0; which < 5; which++) {
    Branch r = b, out;
    if (which == 0 && Rank() == 0) r.z0.back() = nan; // the last orbit (rank 0 holds the rows)
    if (which == 1 && Rank() == 0) r.z0.back() = inf;
    if (which == 2) r.next_ds = nan;
    if (which == 3) r.next_ds = 0; // (a zero orbit would also have given 0 >= ds_min * 0)
    if (which == 4 && Rank() == 0) r.next_tangent.back() = nan;
    INFO("case " << which);
    PCHK(ContinueBranch(f.shoot, nullptr, 0, o, "corrupt", &out, nullptr, &r));
    REQUIRE(out.energy.size() == 3); // no new point
    REQUIRE((out.stop_reason.find("step collapse") == 0 || out.stop_reason.find("the orbit is not finite") == 0));
  }
}
