// Periodic-orbit building blocks: monodromy and beta column from TS forward
// sensitivities against central finite differences of the flow; the
// tangent-linear action against the dense monodromy.
#include "helpers.hpp"
#include "orbits/flow.hpp"
#include <cmath>

using namespace nltopo;
using namespace nltopo::test;

TEST_CASE("monodromy (variational TS and TSForward routes) equals central differences", "[orbits]")
{
  auto route = GENERATE(MonodromyRoute::Variational, MonodromyRoute::TSForward);
  LatticeParams p;
  p.cells = 2; // N = 10
  p.Gamma = 0.5;
  Lattice lat;
  PCHK(lat.Setup(PETSC_COMM_WORLD, p));
  const PetscInt N = lat.N(), n = 2 * N;
  PeriodicFlow flow;
  FlowOptions fo;
  fo.steps = 400;
  fo.route = route;
  PCHK(flow.Setup(lat, fo));
  OwnedVec z0, zT, zp, zm, w;
  OwnedMat S;
  PCHK(lat.CreateStateVector(z0.out()));
  PCHK(VecDuplicate(z0, zT.out()));
  PCHK(VecDuplicate(z0, zp.out()));
  PCHK(VecDuplicate(z0, zm.out()));
  PCHK(VecDuplicate(z0, w.out()));
  auto u = Pseudo(N, 5), v = Pseudo(N, 6); // amplitude ~1: strongly nonlinear
  SetState(lat, u, v, z0);
  const PetscReal T = 3.3, beta = 0.01;
  PCHK(flow.CreateSensitivityMatrix(S.out()));
  PCHK(flow.IntegrateWithMonodromy(z0, T, beta, zT, S));
  const PetscReal h = 1e-6;
  PetscReal maxerr = 0, maxval = 0;
  for (PetscInt j = 0; j <= n; j++) { // columns: initial conditions, then beta
    std::vector<PetscReal> up = u, um = u, vp = v, vm = v;
    PetscReal bp = beta, bm = beta;
    if (j < N) { up[j] += h; um[j] -= h; }
    else if (j < n) { vp[j - N] += h; vm[j - N] -= h; }
    else { bp += h; bm -= h; }
    SetState(lat, up, vp, zp);
    SetState(lat, um, vm, zm);
    PCHK(flow.Integrate(zp, T, bp, zp));
    PCHK(flow.Integrate(zm, T, bm, zm));
    PCHK(VecAXPY(zp, -1.0, zm));
    PCHK(VecScale(zp, 0.5 / h));
    const auto fd = Gather(zp);
    // column j of S in state ordering: column index = state index of the perturbed entry
    const PetscInt col = j < N ? lat.StateIndexU(j) : (j < n ? lat.StateIndexV(j - N) : n);
    Vec c;
    PCHK(MatDenseGetColumnVecRead(S, col, &c));
    const auto sc = Gather(c);
    PCHK(MatDenseRestoreColumnVecRead(S, col, &c));
    for (PetscInt i = 0; i < n; i++) {
      maxerr = std::max(maxerr, std::abs(sc[i] - fd[i]));
      maxval = std::max(maxval, std::abs(sc[i]));
    }
  }
  INFO("max |S - FD| = " << maxerr << ", max |S| = " << maxval);
  REQUIRE(maxerr < 1e-6 * std::max<PetscReal>(1, maxval));

  // One tangent direction (dz, dbeta) equals S [dz; dbeta].
  auto dzu = Pseudo(N, 9), dzv = Pseudo(N, 10);
  OwnedVec dz, Sdz;
  PCHK(VecDuplicate(z0, dz.out()));
  PCHK(VecDuplicate(z0, Sdz.out()));
  SetState(lat, dzu, dzv, dz);
  const PetscReal dbeta = 0.3;
  PCHK(flow.IntegrateWithTangent(z0, T, beta, dz, dbeta, zT, w));
  OwnedVec x;
  PCHK(MatCreateVecs(S, x.out(), NULL));
  {
    // x = [dz in state ordering, dbeta]
    PetscInt lo, hi;
    PCHK(VecGetOwnershipRange(x, &lo, &hi));
    const auto d = Gather(dz);
    for (PetscInt i = lo; i < hi; i++) PCHK(VecSetValue(x, i, i < n ? d[i] : dbeta, INSERT_VALUES));
    PCHK(VecAssemblyBegin(x));
    PCHK(VecAssemblyEnd(x));
  }
  PCHK(MatMult(S, x, Sdz));
  PCHK(VecAXPY(Sdz, -1.0, w));
  PetscReal e, nw;
  PCHK(VecNorm(Sdz, NORM_INFINITY, &e));
  PCHK(VecNorm(w, NORM_INFINITY, &nw));
  REQUIRE(e < 1e-10 * nw);
}
