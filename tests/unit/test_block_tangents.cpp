// Blocked tangent products (PeriodicFlow::IntegrateWithTangents, issue 35
// item 5): s start vectors integrated in one pass over the orbit give the same
// products as s single tangent integrations (IntegrateWithTangent with its beta
// and T sources zero), to rounding relative to |M|, for block sizes that divide
// nothing nicely (s = 3 and 8 on N = 22: 11 sites per rank at 2 ranks), with
// beta != 0 (B_beta's derivative applied to every column) and at beta = 0.
#include "monodromy_fd.hpp"
#include "orbits/flow.hpp"
#include <cmath>

using namespace nltopo;
using namespace nltopo::test;

namespace {

// max_j |w_block[j] - w_single[j]|_inf and max_j |w_single[j]|_inf / |dz[j]|_inf (a lower bound of |M|_inf).
void CompareBlock(PeriodicFlow &flow, const Lattice &lat, PetscInt s, PetscReal T, PetscReal beta, PetscReal *diff, PetscReal *mnorm, PetscReal *zdiff)
{
  const PetscInt N = lat.N();
  OwnedVec z0, zT, zTb, ws;
  PCHK(lat.CreateStateVector(z0.out()));
  for (OwnedVec *v : {&zT, &zTb, &ws}) PCHK(VecDuplicate(z0, v->out()));
  SetState(lat, Pseudo(N, 5), Pseudo(N, 6), z0); // amplitude ~1: strongly nonlinear
  std::vector<OwnedVec> dzo(s), wo(s);
  std::vector<Vec> dz(s), w(s);
  for (PetscInt j = 0; j < s; j++) {
    PCHK(VecDuplicate(z0, dzo[j].out()));
    PCHK(VecDuplicate(z0, wo[j].out()));
    SetState(lat, Pseudo(N, 20 + 2 * j), Pseudo(N, 21 + 2 * j), dzo[j]);
    dz[j] = dzo[j], w[j] = wo[j];
  }
  PCHK(flow.IntegrateWithTangents(z0, T, beta, dz, zTb, w));
  *diff = 0, *mnorm = 0;
  for (PetscInt j = 0; j < s; j++) {
    PetscReal nd, nw, nr;
    PCHK(flow.IntegrateWithTangent(z0, T, beta, dz[j], 0.0, 0.0, zT, ws));
    PCHK(VecNorm(dz[j], NORM_INFINITY, &nd));
    PCHK(VecNorm(ws, NORM_INFINITY, &nw));
    PCHK(VecAXPY(ws, -1.0, w[j]));
    PCHK(VecNorm(ws, NORM_INFINITY, &nr));
    *diff = std::max(*diff, nr / nd);
    *mnorm = std::max(*mnorm, nw / nd);
  }
  PCHK(VecAXPY(zTb, -1.0, zT));
  PCHK(VecNorm(zTb, NORM_INFINITY, zdiff));
}

} // namespace

TEST_CASE("blocked tangent products equal s single products to rounding (s = 3, 8; beta = 0.01 and 0)", "[orbits][symsplit]")
{
  ScopedOptions opts{{"-nnm_ts_type", "symsplit"}, {"-nnm_ts_symsplit_scheme", "bm4"}};
  LatticeParams p;
  p.cells = 5; // N = 22
  p.Gamma = 0.5;
  Lattice lat;
  PCHK(lat.Setup(PETSC_COMM_WORLD, p));
  auto fx = Effects(lat);
  PeriodicFlow flow;
  FlowOptions fo;
  fo.steps = 48;
  PCHK(flow.Setup(*fx, fo));
  REQUIRE(flow.Symplectic());
  for (PetscInt s : {3, 8})
    for (PetscReal beta : {0.01, 0.0}) {
      PetscReal diff, mnorm, zdiff;
      CompareBlock(flow, lat, s, 3.3, beta, &diff, &mnorm, &zdiff);
      INFO("s = " << s << ", beta = " << beta << ": max |w_block - w_single| / |dz| = " << diff << ", |M| >= " << mnorm << ", |zT_block - zT| = " << zdiff);
      REQUIRE(mnorm > 1);             // a nontrivial product (the test can fail)
      REQUIRE(diff <= 1e-13 * mnorm); // the same arithmetic per column: rounding at most
      REQUIRE(zdiff <= 1e-13);        // and the same orbit
    }
}

TEST_CASE("blocked tangent products on the RK route: s single products", "[orbits]")
{
  ScopedOptions opts{{"-nnm_ts_type", "rk"}};
  LatticeParams p;
  p.cells = 2;
  p.Gamma = 0.5;
  Lattice lat;
  PCHK(lat.Setup(PETSC_COMM_WORLD, p));
  auto fx = Effects(lat);
  PeriodicFlow flow;
  FlowOptions fo;
  fo.steps = 24;
  PCHK(flow.Setup(*fx, fo));
  REQUIRE(!flow.Symplectic());
  PetscReal diff, mnorm, zdiff;
  CompareBlock(flow, lat, 3, 3.3, 0.01, &diff, &mnorm, &zdiff);
  INFO("max |w_block - w_single| / |dz| = " << diff << ", |M| >= " << mnorm);
  REQUIRE(mnorm > 1);
  REQUIRE(diff <= 1e-13 * mnorm);
}
