// Periodic-orbit building blocks: monodromy and beta column from TS forward
// sensitivities against central finite differences of the flow; the
// tangent-linear action against the dense monodromy.
#include "helpers.hpp"
#include "bands/linear_modes.hpp"
#include "orbits/flow.hpp"
#include "orbits/linear_monodromy_pc.hpp"
#include "orbits/shooting.hpp"
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

// The N = 14 interface chain with the paper's cubic coefficient (Gamma = 0.5).
struct NonlinearChain14 {
  LatticeParams p;
  Lattice lat;
  NonlinearChain14()
  {
    p.cells = 3;
    p.Gamma = 0.5;
    PCHK(lat.Setup(PETSC_COMM_WORLD, p));
  }
};

// |P^-1 (M - I) x - x| / |x| for a pseudo-random x, with M the monodromy over T
// of the linear lattice lat (Gamma = 0) from its integrated tangent-linear flow.
static PetscReal PreconditionerError(const Lattice &lat, LinearMonodromyPC &pc, PetscReal T, unsigned seed)
{
  PeriodicFlow flow;
  FlowOptions fo;
  fo.steps = 2000;
  PCHK(flow.Setup(lat, fo));
  PCHK(pc.SetPeriod(T));
  OwnedVec z0, x, zT, w, y;
  PCHK(lat.CreateStateVector(z0.out()));
  for (OwnedVec *v : {&x, &zT, &w, &y}) PCHK(VecDuplicate(z0, v->out()));
  PCHK(VecZeroEntries(z0));
  SetState(lat, Pseudo(lat.N(), seed), Pseudo(lat.N(), seed + 1), x);
  PCHK(flow.IntegrateWithTangent(z0, T, 0.0, x, 0.0, zT, w)); // w = M x
  PCHK(VecAXPY(w, -1.0, x));                                   // (M - I) x
  PCHK(pc.Apply(w, y));
  PetscReal e, nx;
  PCHK(VecAXPY(y, -1.0, x));
  PCHK(VecNorm(y, NORM_INFINITY, &e));
  PCHK(VecNorm(x, NORM_INFINITY, &nx));
  return e / nx;
}

// The preconditioner of the matrix-free shooting is the exact inverse of
// M_lin - I: applied to (M_lin - I) x, with M_lin from the integrated flow of
// the linear lattice, it returns x.
TEST_CASE("linear monodromy preconditioner inverts M_lin - I of the linear lattice", "[orbits][mf]")
{
  auto layout = GENERATE(Layout::Interface, Layout::Right);
  LatticeParams p;
  p.layout = layout;
  p.cells = 5;
  p.Gamma = 0; // the linear lattice
  Lattice lat;
  PCHK(lat.Setup(PETSC_COMM_WORLD, p));
  LinearMonodromyPC pc;
  PCHK(pc.Setup(lat));
  const PetscReal err = PreconditionerError(lat, pc, 3.3, 21); // 2 pi / T = 1.904, in the gap: M_lin - I is regular
  INFO("shifted solves: " << pc.Shifts() << ", |P^-1 (M_lin - I) x - x| / |x| = " << err);
  REQUIRE(err < 1e-8);
}

// With another stiffness (SetStiffness, the route of -nnm_mf_pc averaged) the
// preconditioner is the exact inverse of M - I of the linear lattice with that
// stiffness: here the K of a lattice with other couplings, integrated as its own flow.
TEST_CASE("preconditioner with a replaced stiffness inverts that lattice's M - I", "[orbits][mf]")
{
  LatticeParams pa, pb;
  pa.cells = pb.cells = 5;
  pa.Gamma = pb.Gamma = 0;
  pb.gamma = 0.5; // other couplings, same chain; 2 pi / T = 1.904 stays in its gap (1.414 .. 2)
  Lattice a, b;
  PCHK(a.Setup(PETSC_COMM_WORLD, pa));
  PCHK(b.Setup(PETSC_COMM_WORLD, pb));
  std::vector<PetscReal> diag, off;
  for (PetscInt i = b.OwnedStart(); i < b.OwnedStart() + b.OwnedCount(); i++) {
    PetscScalar c[3];
    b.TangentRow(i, NULL, c);
    diag.push_back(c[1]);
    off.push_back(c[2]);
  }
  LinearMonodromyPC pc;
  PCHK(pc.Setup(a));
  PCHK(pc.SetStiffness(diag, off));
  const PetscReal err = PreconditionerError(b, pc, 3.3, 23);
  INFO("|P^-1 (M_b - I) x - x| / |x| = " << err);
  REQUIRE(err < 1e-8);
}

// The orbit-averaged tangent stiffness against its small-amplitude limit: on
// u(t) = a phi cos(w t) (a linear mode, a -> 0) every stiff bond b = (i, i+1)
// adds 3 Gamma <d_b^2> = 3 Gamma a^2 (phi_i - phi_{i+1})^2 / 2 to K (model.md
// tangent stiffness); corrections are O(Gamma a^2) relative.
TEST_CASE_METHOD(NonlinearChain14, "orbit-averaged tangent stiffness equals its small-amplitude limit", "[orbits][mf]")
{
  const PetscInt N = lat.N();
  LinearModes modes;
  PCHK(modes.Compute(lat, LinearModesOptions()));
  REQUIRE(modes.Complete());
  const PetscInt j = N - 1; // the top optical mode: non-degenerate
  const PetscReal a = 1e-3, omega = modes.Omega()[j];
  OwnedVec phi, z0, zT;
  PCHK(VecDuplicate(modes.Mode(j), phi.out()));
  PCHK(modes.CopyMode(j, phi));
  const std::vector<PetscReal> ph = Gather(phi);
  std::vector<PetscReal> u0(N), v0(N, 0.0);
  for (PetscInt i = 0; i < N; i++) u0[i] = a * ph[i];
  PCHK(lat.CreateStateVector(z0.out()));
  PCHK(VecDuplicate(z0, zT.out()));
  SetState(lat, u0, v0, z0);
  PeriodicFlow flow;
  PCHK(flow.Setup(lat, FlowOptions()));
  std::vector<PetscReal> diag, off;
  PCHK(flow.IntegrateAveragingStiffness(z0, 2 * PETSC_PI / omega, 0.0, zT, &diag, &off));
  PetscReal err = 0, dmax = 0;
  for (PetscInt i = lat.OwnedStart(); i < lat.OwnedStart() + lat.OwnedCount(); i++) {
    PetscScalar c[3];
    lat.TangentRow(i, NULL, c); // K
    PetscReal dd = 0, de = 0;   // predicted additions to K(i,i) and K(i,i+1)
    for (PetscInt b : {i - 1, i}) {
      if (b < 0 || b + 1 >= N || !p.Stiff(b)) continue;
      const PetscReal s = 1.5 * p.Gamma * a * a * (ph[b] - ph[b + 1]) * (ph[b] - ph[b + 1]);
      dd += s;
      if (b == i) de = -s;
    }
    const PetscInt k = i - lat.OwnedStart();
    err = std::max({err, std::abs(diag[k] - c[1] - dd), std::abs(off[k] - c[2] - de)});
    dmax = std::max(dmax, std::abs(dd));
  }
  PetscReal gerr, gmax;
  MPI_Allreduce(&err, &gerr, 1, MPIU_REAL, MPI_MAX, PETSC_COMM_WORLD);
  MPI_Allreduce(&dmax, &gmax, 1, MPIU_REAL, MPI_MAX, PETSC_COMM_WORLD);
  INFO("largest addition " << gmax << ", error " << gerr);
  REQUIRE(gmax > 1e-8);
  REQUIRE(gerr < 1e-4 * gmax);
}

// The matrix-free shooting Jacobian (one tangent-linear integration per
// product, bordered by the phase and constraint rows) equals the assembled
// dense one times a vector, for each constraint the continuation uses.
TEST_CASE_METHOD(NonlinearChain14, "matrix-free shooting Jacobian action equals the dense Jacobian", "[orbits][mf]")
{
  const PetscInt N = lat.N();
  PeriodicFlow flow;
  PCHK(flow.Setup(lat, FlowOptions()));
  Shooting dense, mf;
  ShootingOptions so;
  PCHK(dense.Setup(flow, so));
  so.jacobian = ShootingJacobian::MatrixFree;
  PCHK(mf.Setup(flow, so));
  OwnedVec z, X, t, x, yd, ym;
  PCHK(lat.CreateStateVector(z.out()));
  SetState(lat, Pseudo(N, 31), Pseudo(N, 32), z); // amplitude ~1: strongly nonlinear
  PCHK(dense.CreateUnknowns(X.out()));
  for (OwnedVec *v : {&t, &x, &yd, &ym}) PCHK(VecDuplicate(X, v->out()));
  PCHK(dense.Pack(z, 3.4, 1e-3, X));
  Scatter(Pseudo(2 * N + 2, 33), t);
  Scatter(Pseudo(2 * N + 2, 34), x);
  for (int c = 0; c < 2; c++) {
    for (Shooting *s : {&dense, &mf}) {
      if (c == 0) PCHK(s->SetEnergyConstraint(z, 2.0));
      else PCHK(s->SetArclengthConstraint(z, t, X));
      PCHK(s->Jacobian(X, s->Operator()));
    }
    PCHK(MatMult(dense.Operator(), x, yd));
    PCHK(MatMult(mf.Operator(), x, ym));
    PetscReal e, n;
    PCHK(VecNorm(yd, NORM_INFINITY, &n));
    PCHK(VecAXPY(ym, -1.0, yd));
    PCHK(VecNorm(ym, NORM_INFINITY, &e));
    INFO((c ? "arclength" : "energy") << " constraint: |J_mf x - J_dense x| / |J_dense x| = " << e / n);
    REQUIRE(e < 1e-8 * n);
  }
}
