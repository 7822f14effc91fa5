// The effect list (effects/effect.hpp): one list serves the TS right-hand
// side, the variational flow and the energy; the damping effect against the
// modal solution and finite differences.
#include "bands/linear_modes.hpp"
#include "effects/rhs.hpp"
#include "energy_trace.hpp"
#include "helpers.hpp"
#include "orbits/flow.hpp"
#include "timeint/simulation.hpp"
#include <cmath>

using namespace nltopo;
using namespace nltopo::test;

namespace {

PetscReal MaxAbsDiff(Vec a, Vec b)
{
  const auto x = Gather(a), y = Gather(b);
  PetscReal d = 0;
  for (size_t i = 0; i < x.size(); i++) d = std::max(d, std::abs(x[i] - y[i]));
  return d;
}

// Largest entry difference over the first ncol columns of two dense matrices.
PetscReal MaxAbsDiff(Mat A, Mat B, PetscInt ncol)
{
  const PetscScalar *a, *b;
  PetscInt m, lda, ldb;
  PetscReal d = 0;
  MatGetLocalSize(A, &m, NULL);
  MatDenseGetLDA(A, &lda);
  MatDenseGetLDA(B, &ldb);
  MatDenseGetArrayRead(A, &a);
  MatDenseGetArrayRead(B, &b);
  for (PetscInt c = 0; c < ncol; c++)
    for (PetscInt i = 0; i < m; i++) d = std::max(d, std::abs(a[i + c * lda] - b[i + c * ldb]));
  MatDenseRestoreArrayRead(B, &b);
  MatDenseRestoreArrayRead(A, &a);
  MPI_Allreduce(MPI_IN_PLACE, &d, 1, MPIU_REAL, MPIU_MAX, PETSC_COMM_WORLD);
  return d;
}

} // namespace

TEST_CASE("removing the cubic effect removes it from the right-hand side, the variational flow and the energy", "[effects]")
{
  LatticeParams p;
  p.cells = 3;
  Lattice lat;
  PCHK(lat.Setup(PETSC_COMM_WORLD, p));
  auto with = Effects(lat), without = Effects(lat);
  without->Remove("cubic");
  REQUIRE(with->Has("cubic"));
  REQUIRE(!without->Has("cubic"));

  // A large state: the cubic terms are O(1) here.
  OwnedVec z, f, g;
  PCHK(lat.CreateStateVector(z.out()));
  PCHK(VecDuplicate(z, f.out()));
  PCHK(VecDuplicate(z, g.out()));
  SetState(lat, Pseudo(lat.N(), 3), Pseudo(lat.N(), 4), z);
  PCHK(VecScale(z, 2.0));

  // 1. The TS right-hand side: without the cubic effect it is L z exactly.
  OwnedMat L;
  PCHK(lat.CreateStateMatrix(L.out()));
  PCHK(with->AssembleStateJacobian(NULL, L)); // at rest: L = [[0, I], [-K, 0]]
  PCHK(MatMult(L, z, g));
  Rhs r_without(*without), r_with(*with);
  PCHK(r_without.Evaluate(0, z, f));
  REQUIRE(MaxAbsDiff(f, g) < 1e-13);
  REQUIRE(r_without.Counters().cubic == 0);
  PCHK(r_with.Evaluate(0, z, f));
  REQUIRE(MaxAbsDiff(f, g) > 1e-2);
  REQUIRE(r_with.Counters().cubic == 1);

  // 2. The variational flow: without the cubic effect the monodromy (the
  // state columns; the beta column is grad E(z(T))) does not depend on the
  // orbit (the flow is linear); with it, it does.
  for (bool cubic : {false, true}) {
    PeriodicFlow flow;
    FlowOptions fo;
    fo.steps = 64;
    PCHK(flow.Setup(cubic ? *with : *without, fo));
    OwnedMat S0, S1;
    OwnedVec zT, zero;
    PCHK(flow.CreateSensitivityMatrix(S0.out()));
    PCHK(flow.CreateSensitivityMatrix(S1.out()));
    PCHK(VecDuplicate(z, zT.out()));
    PCHK(VecDuplicate(z, zero.out()));
    PCHK(VecZeroEntries(zero));
    PCHK(flow.IntegrateWithMonodromy(zero, 3.0, 0.0, zT, S0));
    PCHK(flow.IntegrateWithMonodromy(z, 3.0, 0.0, zT, S1));
    if (cubic) REQUIRE(MaxAbsDiff(S0, S1, 2 * lat.N()) > 1e-2);
    else REQUIRE(MaxAbsDiff(S0, S1, 2 * lat.N()) < 1e-12);
  }

  // 3. The energy: no quartic part without the cubic effect, the same other parts.
  EnergyParts e_with, e_without;
  PCHK(with->Energy(z, &e_with));
  PCHK(without->Energy(z, &e_without));
  REQUIRE(e_without.quartic == 0.0);
  REQUIRE(e_with.quartic > 1e-2);
  REQUIRE(e_without.linear == Approx(e_with.linear).epsilon(1e-14));
  REQUIRE(e_without.kinetic == Approx(e_with.kinetic).epsilon(1e-14));
}

TEST_CASE("-lattice_damping 0 builds no damping effect and never calls its kernel; c > 0 calls it at every evaluation", "[effects][damping]")
{
  LatticeParams p;
  p.cells = 3;
  Lattice lat;
  PCHK(lat.Setup(PETSC_COMM_WORLD, p));
  OwnedVec z0;
  PCHK(lat.CreateStateVector(z0.out()));
  SetState(lat, Pseudo(lat.N(), 5), Pseudo(lat.N(), 6), z0);
  for (const char *c : {"0", "0.1"}) {
    ScopedOptions o({{"-lattice_damping", c}});
    auto fx = Effects(lat);
    const bool damped = std::string(c) != "0";
    REQUIRE(fx->Has("damping") == damped);
    REQUIRE(fx->Conservative() == !damped);
    SimulationOptions so;
    so.t_final = 5;
    so.sample_dt = 0;
    SimulationResult r;
    PCHK(Simulate(*fx, so, z0, NULL, &r));
    REQUIRE(r.counters.rhs > 0);
    REQUIRE(r.counters.damping == (damped ? r.counters.rhs : 0));
  }
}

TEST_CASE("the damped linear lattice loses energy at the rate of its modal solution", "[effects][damping]")
{
  LatticeParams p;
  p.cells = 2;
  p.Gamma = 0; // linear: the modes decouple under uniform damping C = c I
  Lattice lat;
  PCHK(lat.Setup(PETSC_COMM_WORLD, p));
  LinearModes modes;
  PCHK(modes.Compute(lat, LinearModesOptions()));
  const PetscReal c = 0.05, a = 0.3;
  const PetscInt j = 3;
  const PetscReal w = modes.Omega()[j], wd = std::sqrt(w * w - c * c / 4);
  OwnedVec z0;
  PCHK(lat.CreateStateVector(z0.out()));
  auto u0 = Gather(modes.Mode(j));
  for (auto &x : u0) x *= a;
  SetState(lat, u0, std::vector<PetscReal>(lat.N(), 0.0), z0);

  ScopedOptions o({{"-lattice_damping", "0.05"}, {"-sim_ts_rtol", "1e-11"}, {"-sim_ts_atol", "1e-11"}});
  auto fx = Effects(lat);
  SimulationOptions so;
  so.t_final = 60;
  so.sample_dt = 2;
  EnergyTrace tr;
  SimulationResult r;
  PCHK(Simulate(*fx, so, z0, &tr, &r));
  REQUIRE(tr.t.size() == 31);
  // q(t) = a e^{-ct/2} (cos wd t + c/(2 wd) sin wd t), q' = -a e^{-ct/2} (w^2/wd) sin wd t;
  // E = (q'^2 + w^2 q^2) / 2 (unit-norm mode, unit masses).
  PetscReal worst = 0;
  for (size_t k = 0; k < tr.t.size(); k++) {
    const PetscReal t = tr.t[k], d = a * std::exp(-c * t / 2);
    const PetscReal q = d * (std::cos(wd * t) + c / (2 * wd) * std::sin(wd * t)), qd = -d * (w * w / wd) * std::sin(wd * t);
    const PetscReal E = 0.5 * (qd * qd + w * w * q * q);
    worst = std::max(worst, std::abs(tr.e[k] - E) / E);
  }
  REQUIRE(worst < 1e-7);
  REQUIRE(tr.e.back() < 0.1 * tr.e.front()); // e^{-c t} = e^{-3}: the decay is real, not rounding
}

TEST_CASE("the damped state Jacobian matches finite differences of the right-hand side", "[effects][damping]")
{
  LatticeParams p;
  p.cells = 2;
  Lattice lat;
  PCHK(lat.Setup(PETSC_COMM_WORLD, p));
  ScopedOptions o({{"-lattice_damping", "0.3"}});
  auto fx = Effects(lat);
  REQUIRE(fx->Has("damping"));
  REQUIRE(fx->Has("cubic"));
  const PetscInt n = 2 * lat.N();
  OwnedVec z, zp, zm, fp, fm;
  OwnedMat A;
  PCHK(lat.CreateStateVector(z.out()));
  for (Vec *v : {zp.out(), zm.out(), fp.out(), fm.out()}) PCHK(VecDuplicate(z, v));
  SetState(lat, Pseudo(lat.N(), 7), Pseudo(lat.N(), 8), z);
  PCHK(lat.CreateStateMatrix(A.out()));
  PCHK(fx->AssembleStateJacobian(z, A));
  Rhs rhs(*fx);
  const PetscReal h = 1e-5;
  PetscReal worst = 0;
  for (PetscInt col = 0; col < n; col++) {
    PetscInt lo, hi;
    PCHK(VecCopy(z, zp));
    PCHK(VecCopy(z, zm));
    PCHK(VecGetOwnershipRange(z, &lo, &hi));
    if (col >= lo && col < hi) {
      PetscScalar *a;
      PCHK(VecGetArray(zp, &a));
      a[col - lo] += h;
      PCHK(VecRestoreArray(zp, &a));
      PCHK(VecGetArray(zm, &a));
      a[col - lo] -= h;
      PCHK(VecRestoreArray(zm, &a));
    }
    PCHK(rhs.Evaluate(0, zp, fp));
    PCHK(rhs.Evaluate(0, zm, fm));
    PCHK(VecAXPY(fp, -1.0, fm));
    PCHK(VecScale(fp, 1 / (2 * h)));
    OwnedVec ac;
    PCHK(VecDuplicate(z, ac.out()));
    PCHK(MatGetColumnVector(A, ac, col));
    worst = std::max(worst, MaxAbsDiff(fp, ac));
  }
  REQUIRE(worst < 1e-8);
}
