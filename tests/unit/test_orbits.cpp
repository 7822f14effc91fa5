// Periodic-orbit building blocks on the rk route (-nnm_ts_type rk, 5dp):
// monodromy and beta column from TS forward sensitivities against central
// finite differences of the flow; the tangent-linear action against the
// dense monodromy.
#include "helpers.hpp"
#include "monodromy_fd.hpp"
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
  ScopedOptions rk{{"-nnm_ts_type", "rk"}}; // the rk route (the symplectic one: test_orbits_symplectic.cpp)
  PeriodicFlow flow;
  FlowOptions fo;
  fo.steps = 400;
  fo.route = route;
  auto fx_flow = Effects(lat);
  PCHK(flow.Setup(*fx_flow, fo));
  OwnedVec z0, zT, w;
  OwnedMat S;
  PCHK(lat.CreateStateVector(z0.out()));
  PCHK(VecDuplicate(z0, zT.out()));
  PCHK(VecDuplicate(z0, w.out()));
  auto u = Pseudo(N, 5), v = Pseudo(N, 6); // amplitude ~1: strongly nonlinear
  SetState(lat, u, v, z0);
  const PetscReal T = 3.3, beta = 0.01;
  PCHK(flow.CreateSensitivityMatrix(S.out()));
  PCHK(flow.IntegrateWithMonodromy(z0, T, beta, zT, S));
  PetscReal maxerr, maxval;
  MonodromyAgainstFD(lat, flow, u, v, T, beta, S, 1e-6, &maxerr, &maxval);
  INFO("max |S - FD| = " << maxerr << ", max |S| = " << maxval);
  REQUIRE(maxerr < 1e-6 * std::max<PetscReal>(1, maxval));

  // One tangent direction (dz, dbeta) equals S [dz; dbeta].
  auto dzu = Pseudo(N, 9), dzv = Pseudo(N, 10);
  OwnedVec dz, Sdz;
  PCHK(VecDuplicate(z0, dz.out()));
  PCHK(VecDuplicate(z0, Sdz.out()));
  SetState(lat, dzu, dzv, dz);
  const PetscReal dbeta = 0.3;
  PCHK(flow.IntegrateWithTangent(z0, T, beta, dz, dbeta, 0.0, zT, w));
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

// The tangent's T column is the T-derivative of the fixed-step discrete map
// z0 -> z_n (n steps of T/n), not the exact flow's f(z(T)): on a coarse grid
// (16 steps per period, discretization error ~1e-3) it equals the central
// difference of the discrete map in T, which f(z(T)) does not. Newton on the
// shooting residual needs the former (docs/long-lattices.md).
TEST_CASE("tangent T column is the derivative of the discrete flow", "[orbits][mf]")
{
  LatticeParams p;
  p.cells = 2; // N = 10
  p.Gamma = 0.5;
  Lattice lat;
  PCHK(lat.Setup(PETSC_COMM_WORLD, p));
  ScopedOptions rk{{"-nnm_ts_type", "rk"}}; // the rk route (the symplectic one: test_orbits_symplectic.cpp)
  PeriodicFlow flow;
  FlowOptions fo;
  fo.steps = 16;
  auto fx_flow = Effects(lat);
  PCHK(flow.Setup(*fx_flow, fo));
  OwnedVec z0, zero, zT, zp, zm, w, f;
  PCHK(lat.CreateStateVector(z0.out()));
  for (OwnedVec *v : {&zero, &zT, &zp, &zm, &w, &f}) PCHK(VecDuplicate(z0, v->out()));
  SetState(lat, Pseudo(lat.N(), 5), Pseudo(lat.N(), 6), z0); // amplitude ~1: strongly nonlinear
  PCHK(VecZeroEntries(zero));
  const PetscReal T = 3.3, beta = 0.01, h = 1e-5;
  PCHK(flow.IntegrateWithTangent(z0, T, beta, zero, 0.0, 1.0, zT, w)); // dT = 1
  PCHK(flow.Integrate(z0, T + h, beta, zp));
  PCHK(flow.Integrate(z0, T - h, beta, zm));
  PCHK(VecAXPY(zp, -1.0, zm));
  PCHK(VecScale(zp, 0.5 / h));  // central difference of the discrete map
  PCHK(flow.EvalRhs(T, zT, f)); // the exact flow's derivative at the discrete z(T)
  PetscReal nfd, ew, ef;
  PCHK(VecNorm(zp, NORM_INFINITY, &nfd));
  PCHK(VecAXPY(w, -1.0, zp));
  PCHK(VecAXPY(f, -1.0, zp));
  PCHK(VecNorm(w, NORM_INFINITY, &ew));
  PCHK(VecNorm(f, NORM_INFINITY, &ef));
  INFO("|w_T - FD| / |FD| = " << ew / nfd << ", |f(z(T)) - FD| / |FD| = " << ef / nfd);
  REQUIRE(ew < 1e-8 * nfd);
  REQUIRE(ef > 1e3 * ew); // the grid is coarse enough for the difference to show
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
  ScopedOptions rk{{"-nnm_ts_type", "rk"}}; // the rk route (the symplectic one: test_orbits_symplectic.cpp)
  PeriodicFlow flow;
  FlowOptions fo;
  fo.steps = 2000;
  auto fx_flow = Effects(lat);
  PCHK(flow.Setup(*fx_flow, fo));
  PCHK(pc.SetPeriod(T));
  OwnedVec z0, x, zT, w, y;
  PCHK(lat.CreateStateVector(z0.out()));
  for (OwnedVec *v : {&x, &zT, &w, &y}) PCHK(VecDuplicate(z0, v->out()));
  PCHK(VecZeroEntries(z0));
  SetState(lat, Pseudo(lat.N(), seed), Pseudo(lat.N(), seed + 1), x);
  PCHK(flow.IntegrateWithTangent(z0, T, 0.0, x, 0.0, 0.0, zT, w)); // w = M x
  PCHK(VecAXPY(w, -1.0, x));                                       // (M - I) x
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
  INFO("|P^-1 (M_lin - I) x - x| / |x| = " << err);
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
    b.KRow(i, c);
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

// The parametric preconditioner against the Hill equation it approximates:
// x'' + (K + Kc cos 2wt + Ks sin 2wt) x = 0 on the N = 14 chain, with w just
// below the top optical mode's frequency and the 2w term strong enough to put
// that mode inside its 1:1 parametric-resonance tongue (|Kc + i Ks|/2 > K - w^2
// there). M is integrated here by classical RK4 (independent of the PC). The
// averaged preconditioner (Kc = Ks = 0) misses the tongue and is far from
// (M - I)^-1; the rotating-wave block brings P^-1 (M - I) close to the identity,
// to first order in the 2w term (the averaging theorem's error).
TEST_CASE("parametric preconditioner inverts M - I of a Hill equation near the 1:1 resonance", "[orbits][mf]")
{
  LatticeParams p;
  p.cells = 3;
  p.Gamma = 0; // K only
  Lattice lat;
  PCHK(lat.Setup(PETSC_COMM_WORLD, p));
  const PetscInt N = lat.N();
  LinearModes modes;
  PCHK(modes.Compute(lat, LinearModesOptions()));
  REQUIRE(modes.Complete());
  const PetscReal nu = modes.Omega()[N - 1], w = nu * (1 - 0.002), T = 2 * PETSC_PI / w, c = 0.012 * w * w;
  // K and the 2w harmonics, whole chain (diag, off = (i, i+1))
  std::vector<PetscReal> kd(N, 0.0), ko(N, 0.0), cd(N, c), co(N, 0.25 * c), sd(N, 0.5 * c), so(N, -0.3 * c);
  for (PetscInt i = lat.OwnedStart(); i < lat.OwnedStart() + lat.OwnedCount(); i++) { // owned rows, then summed over ranks
    PetscScalar r[3];
    lat.KRow(i, r);
    kd[i] = r[1];
    ko[i] = i + 1 < N ? r[2] : 0.0;
  }
  MPI_Allreduce(MPI_IN_PLACE, kd.data(), (int)N, MPIU_REAL, MPI_SUM, PETSC_COMM_WORLD);
  MPI_Allreduce(MPI_IN_PLACE, ko.data(), (int)N, MPIU_REAL, MPI_SUM, PETSC_COMM_WORLD);
  co[N - 1] = so[N - 1] = 0;
  auto owned = [&](const std::vector<PetscReal> &a) {
    return std::vector<PetscReal>(a.begin() + lat.OwnedStart(), a.begin() + lat.OwnedStart() + lat.OwnedCount());
  };
  // y = (M - I) x by RK4 on z = (u, v), 4000 steps
  auto hill = [&](const std::vector<PetscReal> &u0, const std::vector<PetscReal> &v0, std::vector<PetscReal> *yu, std::vector<PetscReal> *yv) {
    const PetscInt steps = 4000;
    const PetscReal h = T / steps;
    std::vector<PetscReal> u = u0, v = v0;
    auto acc = [&](PetscReal t, const std::vector<PetscReal> &x) {
      const PetscReal cs = std::cos(2 * w * t), sn = std::sin(2 * w * t);
      std::vector<PetscReal> a(N);
      for (PetscInt i = 0; i < N; i++) {
        PetscReal s = (kd[i] + cd[i] * cs + sd[i] * sn) * x[i];
        if (i > 0) s += (ko[i - 1] + co[i - 1] * cs + so[i - 1] * sn) * x[i - 1];
        if (i + 1 < N) s += (ko[i] + co[i] * cs + so[i] * sn) * x[i + 1];
        a[i] = -s;
      }
      return a;
    };
    for (PetscInt k = 0; k < steps; k++) {
      const PetscReal t = k * h;
      std::vector<PetscReal> u2(N), v2(N), u3(N), v3(N), u4(N), v4(N);
      const auto a1 = acc(t, u);
      for (PetscInt i = 0; i < N; i++) u2[i] = u[i] + 0.5 * h * v[i], v2[i] = v[i] + 0.5 * h * a1[i];
      const auto a2 = acc(t + 0.5 * h, u2);
      for (PetscInt i = 0; i < N; i++) u3[i] = u[i] + 0.5 * h * v2[i], v3[i] = v[i] + 0.5 * h * a2[i];
      const auto a3 = acc(t + 0.5 * h, u3);
      for (PetscInt i = 0; i < N; i++) u4[i] = u[i] + h * v3[i], v4[i] = v[i] + h * a3[i];
      const auto a4 = acc(t + h, u4);
      for (PetscInt i = 0; i < N; i++) {
        u[i] += h / 6 * (v[i] + 2 * v2[i] + 2 * v3[i] + v4[i]);
        v[i] += h / 6 * (a1[i] + 2 * a2[i] + 2 * a3[i] + a4[i]);
      }
    }
    yu->resize(N);
    yv->resize(N);
    for (PetscInt i = 0; i < N; i++) (*yu)[i] = u[i] - u0[i], (*yv)[i] = v[i] - v0[i];
  };
  LinearMonodromyPC avg, par;
  PCHK(avg.Setup(lat));
  PCHK(par.Setup(lat));
  PCHK(par.SetParametricTerm(owned(cd), owned(co), owned(sd), owned(so), 1.0));
  PCHK(avg.SetPeriod(T));
  PCHK(par.SetPeriod(T));
  OwnedVec r, x;
  PCHK(lat.CreateStateVector(r.out()));
  PCHK(VecDuplicate(r, x.out()));
  PetscReal eavg = 0, epar = 0;
  // x: the resonant mode (the direction that matters) and two pseudo-random vectors
  OwnedVec phi;
  PCHK(VecDuplicate(modes.Mode(N - 1), phi.out()));
  PCHK(modes.CopyMode(N - 1, phi));
  const std::vector<std::vector<PetscReal>> xs = {Gather(phi), Pseudo(N, 31), Pseudo(N, 32)};
  for (const auto &xu : xs) {
    const std::vector<PetscReal> xv = Pseudo(N, 33);
    std::vector<PetscReal> yu, yv;
    hill(xu, xv, &yu, &yv);
    SetState(lat, yu, yv, r);
    PetscReal xmax = 0;
    for (PetscInt i = 0; i < N; i++) xmax = std::max({xmax, std::abs(xu[i]), std::abs(xv[i])});
    for (auto *pc : {&avg, &par}) {
      PCHK(pc->Apply(r, x));
      const auto z = Gather(x); // state ordering
      PetscReal e = 0;
      for (PetscInt i = 0; i < N; i++) e = std::max({e, std::abs(z[lat.StateIndexU(i)] - xu[i]), std::abs(z[lat.StateIndexV(i)] - xv[i])});
      (pc == &avg ? eavg : epar) = std::max(pc == &avg ? eavg : epar, e / xmax);
    }
  }
  INFO("|P^-1 (M - I) x - x| / |x|: averaged " << eavg << ", parametric " << epar);
  REQUIRE(eavg > 0.5);
  REQUIRE(epar < 0.1);
}

// The orbit's tangent-stiffness harmonics against their small-amplitude limit:
// on u(t) = a phi cos(w t) (a linear mode, a -> 0) every stiff bond b = (i, i+1)
// has d_b^2 = a^2 (phi_i - phi_{i+1})^2 (1 + cos 2wt) / 2, so it adds
// 3 Gamma a^2 (phi_i - phi_{i+1})^2 / 2 to K (model.md tangent stiffness), the
// same to the cos 2wt harmonic Kc, and nothing to Ks; corrections are
// O(Gamma a^2) relative.
TEST_CASE_METHOD(NonlinearChain14, "orbit tangent-stiffness harmonics equal their small-amplitude limit", "[orbits][mf]")
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
  ScopedOptions rk{{"-nnm_ts_type", "rk"}}; // the rk route (the symplectic one: test_orbits_symplectic.cpp)
  PeriodicFlow flow;
  auto fx_flow = Effects(lat);
  PCHK(flow.Setup(*fx_flow, FlowOptions()));
  StiffnessHarmonics h;
  h.parametric = true;
  PCHK(flow.IntegrateAveragingStiffness(z0, 2 * PETSC_PI / omega, 0.0, zT, &h));
  const std::vector<PetscReal> &diag = h.d0, &off = h.o0;
  PetscReal err = 0, dmax = 0, herr = 0;
  for (PetscInt i = lat.OwnedStart(); i < lat.OwnedStart() + lat.OwnedCount(); i++) {
    PetscScalar c[3];
    lat.KRow(i, c);           // K
    PetscReal dd = 0, de = 0; // predicted additions to K(i,i) and K(i,i+1)
    for (PetscInt b : {i - 1, i}) {
      if (b < 0 || b + 1 >= N || !p.Stiff(b)) continue;
      const PetscReal s = 1.5 * p.Gamma * a * a * (ph[b] - ph[b + 1]) * (ph[b] - ph[b + 1]);
      dd += s;
      if (b == i) de = -s;
    }
    const PetscInt k = i - lat.OwnedStart();
    err = std::max({err, std::abs(diag[k] - c[1] - dd), std::abs(off[k] - c[2] - de)});
    herr = std::max({herr, std::abs(h.dc[k] - dd), std::abs(h.oc[k] - de), std::abs(h.ds[k]), std::abs(h.os[k])});
    dmax = std::max(dmax, std::abs(dd));
  }
  PetscReal gerr, gmax, gherr;
  MPI_Allreduce(&err, &gerr, 1, MPIU_REAL, MPI_MAX, PETSC_COMM_WORLD);
  MPI_Allreduce(&herr, &gherr, 1, MPIU_REAL, MPI_MAX, PETSC_COMM_WORLD);
  MPI_Allreduce(&dmax, &gmax, 1, MPIU_REAL, MPI_MAX, PETSC_COMM_WORLD);
  INFO("largest addition " << gmax << ", error of the average " << gerr << ", of the 2 w harmonics " << gherr);
  REQUIRE(gmax > 1e-8);
  REQUIRE(gerr < 1e-4 * gmax);
  REQUIRE(gherr < 1e-4 * gmax);
}

// The matrix-free shooting Jacobian (one tangent-linear integration per
// product, bordered by the phase and constraint rows) equals the assembled
// dense one times a vector, for each constraint the continuation uses.
TEST_CASE_METHOD(NonlinearChain14, "matrix-free shooting Jacobian action equals the dense Jacobian", "[orbits][mf]")
{
  const PetscInt N = lat.N();
  ScopedOptions rk{{"-nnm_ts_type", "rk"}}; // the rk route (the symplectic one: test_orbits_symplectic.cpp)
  PeriodicFlow flow;
  auto fx_flow = Effects(lat);
  PCHK(flow.Setup(*fx_flow, FlowOptions()));
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
  auto xs = Pseudo(2 * N + 2, 34);
  xs[2 * N] = 0; // no T component: the mf T column is the discrete map's (tested below), the dense one f(z(T))
  Scatter(xs, x);
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

// The matrix-free Jacobian is the derivative of the shooting residual that
// Newton drives to zero, T column included: against central differences of
// Shooting::Residual on a coarse grid (24 steps per period), where the dense
// route's f(z(T)) column is visibly off. A Jacobian off by the discretization
// error stalled inexact Newton at |F| ~ 1e-9 on the N = 10^4 branch.
TEST_CASE_METHOD(NonlinearChain14, "matrix-free shooting Jacobian is the derivative of the residual", "[orbits][mf]")
{
  const PetscInt N = lat.N();
  ScopedOptions rk{{"-nnm_ts_type", "rk"}}; // the rk route (the symplectic one: test_orbits_symplectic.cpp)
  PeriodicFlow flow;
  FlowOptions fo;
  fo.steps = 24;
  auto fx_flow = Effects(lat);
  PCHK(flow.Setup(*fx_flow, fo));
  Shooting dense, mf;
  ShootingOptions so;
  PCHK(dense.Setup(flow, so));
  so.jacobian = ShootingJacobian::MatrixFree;
  PCHK(mf.Setup(flow, so));
  OwnedVec z, X, t, x, Xp, Fp, Fm, y;
  PCHK(lat.CreateStateVector(z.out()));
  SetState(lat, Pseudo(N, 31), Pseudo(N, 32), z);
  PCHK(mf.CreateUnknowns(X.out()));
  for (OwnedVec *v : {&t, &x, &Xp, &Fp, &Fm, &y}) PCHK(VecDuplicate(X, v->out()));
  PCHK(mf.Pack(z, 3.4, 1e-3, X));
  Scatter(Pseudo(2 * N + 2, 33), t);
  Scatter(Pseudo(2 * N + 2, 34), x); // dz, dT and dbeta all nonzero
  const PetscReal h = 1e-6;
  PetscReal err[2], nfd = 0;
  Shooting *routes[2] = {&mf, &dense};
  for (int r = 0; r < 2; r++) {
    Shooting &s = *routes[r];
    PCHK(s.SetArclengthConstraint(z, t, X));
    PCHK(VecWAXPY(Xp, h, x, X));
    PCHK(s.Residual(Xp, Fp));
    PCHK(VecWAXPY(Xp, -h, x, X));
    PCHK(s.Residual(Xp, Fm));
    PCHK(VecAXPY(Fp, -1.0, Fm));
    PCHK(VecScale(Fp, 0.5 / h));
    PCHK(s.Jacobian(X, s.Operator()));
    PCHK(MatMult(s.Operator(), x, y));
    PCHK(VecNorm(Fp, NORM_INFINITY, &nfd));
    PCHK(VecAXPY(y, -1.0, Fp));
    PCHK(VecNorm(y, NORM_INFINITY, &err[r]));
    err[r] /= nfd;
  }
  INFO("|J x - FD| / |FD|: matrix-free " << err[0] << ", dense " << err[1]);
  REQUIRE(err[0] < 1e-7);
  REQUIRE(err[1] > 10 * err[0]);
}

// z = amp times the top linear mode (displacements; velocities zero): a strongly nonlinear orbit's guess.
static void TopModeState(const Lattice &lat, const LinearModes &modes, PetscReal amp, Vec z)
{
  PetscScalar *a;
  const PetscScalar *m;
  const PetscInt top = lat.N() - 1;
  PCHK(VecZeroEntries(z));
  PCHK(VecGetArray(z, &a));
  PCHK(VecGetArrayRead(modes.Mode(top), &m));
  for (PetscInt k = 0; k < lat.OwnedCount(); k++) a[k] = amp * m[k];
  PCHK(VecRestoreArrayRead(modes.Mode(top), &m));
  PCHK(VecRestoreArray(z, &a));
}

// -nnm_orbit_rtol: Newton accepts an orbit once |F| <= rtol |z0|. From the
// same guess (the top linear mode at amplitude 0.3, strongly nonlinear) a
// loose rtol stops earlier, with a residual within it; rtol 0 goes on to the
// SNES atol. A huge rtol accepts the guess itself (no iteration).
TEST_CASE_METHOD(NonlinearChain14, "-nnm_orbit_rtol stops Newton at |F| <= rtol |z0|", "[orbits][mf]")
{
  const PetscInt N = lat.N();
  LinearModes modes;
  PCHK(modes.Compute(lat, LinearModesOptions()));
  ScopedOptions rk{{"-nnm_ts_type", "rk"}}; // the rk route (the symplectic one: test_orbits_symplectic.cpp)
  PeriodicFlow flow;
  auto fx_flow = Effects(lat);
  PCHK(flow.Setup(*fx_flow, FlowOptions()));
  OwnedVec z, zs, X, F;
  PCHK(lat.CreateStateVector(z.out()));
  PCHK(VecDuplicate(z, zs.out()));
  TopModeState(lat, modes, 0.3, z);
  EnergyParts e;
  PCHK(Effects(lat)->Energy(z, &e));
  const PetscReal T = 2 * PETSC_PI / modes.Omega()[N - 1];
  PetscInt its[3];
  PetscReal fn[3], zn[3];
  const PetscReal rtols[3] = {0, 1e-3, 0.9};
  for (int r = 0; r < 3; r++) {
    ShootingOptions so;
    so.jacobian = ShootingJacobian::MatrixFree;
    so.start_dense_max = 0; // the main (inexact-Newton GMRES) solver from the first orbit on
    so.orbit_rtol = rtols[r];
    Shooting s;
    PCHK(s.Setup(flow, so));
    PCHK(s.CreateUnknowns(X.out()));
    PCHK(VecDuplicate(X, F.out()));
    PCHK(s.Pack(z, T, 0.0, X));
    PCHK(s.SetEnergyConstraint(z, e.Total()));
    bool ok;
    PCHK(s.Solve(X, &ok, &its[r]));
    REQUIRE(ok);
    PetscReal Tr, br;
    PCHK(s.Residual(X, F));
    PCHK(VecNorm(F, NORM_2, &fn[r]));
    PCHK(s.Unpack(X, zs, &Tr, &br));
    PCHK(VecNorm(zs, NORM_2, &zn[r]));
  }
  INFO("Newton iterations " << its[0] << ", " << its[1] << ", " << its[2] << "; |F| " << fn[0] << ", " << fn[1] << ", " << fn[2]);
  REQUIRE(fn[0] <= 1e-12);
  REQUIRE(fn[1] <= 1e-3 * zn[1]);
  REQUIRE(its[1] < its[0]);
  REQUIRE(its[2] == 0);
}

// Chord Newton (ShootingSolver::SeedJacobian): the orbit at E2 from the orbit
// at E1 as guess, its Jacobian assembled from the E1 orbit's monodromy,
// reaches the orbit plain Newton reaches (both to -nnm_snes_atol) without a
// fresh Jacobian; a seed whose Jacobian is singular (a zero monodromy: its
// beta column vanishes) fails the chord, and the solve is repeated by Newton.
// Symplectic route and the pivoting LU, as the codim-2 curves use them.
TEST_CASE_METHOD(NonlinearChain14, "chord Newton from a nearby orbit's monodromy reaches Newton's orbit; a singular seed falls back to Newton", "[orbits]")
{
  const PetscInt N = lat.N();
  LinearModes modes;
  PCHK(modes.Compute(lat, LinearModesOptions()));
  ScopedOptions sym{{"-nnm_ts_type", "symsplit"}};
  PeriodicFlow flow;
  auto fx_flow = Effects(lat);
  PCHK(flow.Setup(*fx_flow, FlowOptions()));
  OwnedVec z, X1, X, Xn, zT;
  OwnedMat S, S0;
  PCHK(lat.CreateStateVector(z.out()));
  PCHK(VecDuplicate(z, zT.out()));
  TopModeState(lat, modes, 0.2, z);
  EnergyParts e;
  PCHK(Effects(lat)->Energy(z, &e));
  const PetscReal E1 = e.Total(), E2 = 1.05 * E1;
  Shooting s;
  PCHK(s.Setup(flow, ShootingOptions()));
  s.SetEnergyStartSolver(false); // the pivoting LU, as for codim-2 kinds 3 and 5
  REQUIRE(s.Seedable());
  PCHK(s.CreateUnknowns(X1.out()));
  PCHK(VecDuplicate(X1, X.out()));
  PCHK(VecDuplicate(X1, Xn.out()));
  bool ok;
  PetscInt its;
  PCHK(s.Pack(z, 2 * PETSC_PI / modes.Omega()[N - 1], 0.0, X1));
  PCHK(s.SetEnergyConstraint(z, E1));
  PCHK(s.Solve(X1, &ok, &its));
  REQUIRE(ok);
  PetscReal T1, b1;
  PCHK(s.Unpack(X1, z, &T1, &b1));
  PCHK(flow.CreateSensitivityMatrix(S.out()));
  PCHK(flow.IntegrateWithMonodromy(z, T1, flow.FloquetBeta(b1), zT, S)); // the E1 orbit's monodromy (as a codim-2 test takes it)
  // three solves of the E2 orbit from the E1 orbit: Newton, chord, chord from a singular seed
  PetscInt jac[3], iters[3];
  PetscReal diff[3];
  PCHK(MatDuplicate(S, MAT_DO_NOT_COPY_VALUES, S0.out()));
  PCHK(MatZeroEntries(S0));
  for (int r = 0; r < 3; r++) {
    PCHK(VecCopy(X1, X));
    PCHK(s.SetEnergyConstraint(z, E2));
    if (r > 0) PCHK(s.SeedJacobian(X, r == 1 ? S.get() : S0.get()));
    const PetscInt j0 = s.JacobianEvaluations();
    PCHK(s.Solve(X, &ok, &iters[r]));
    REQUIRE(ok);
    jac[r] = s.JacobianEvaluations() - j0;
    if (r == 0) PCHK(VecCopy(X, Xn));
    PetscReal nx;
    PCHK(VecNorm(Xn, NORM_INFINITY, &nx));
    PCHK(VecAXPY(X, -1.0, Xn));
    PCHK(VecNorm(X, NORM_INFINITY, &diff[r]));
    diff[r] /= nx;
  }
  INFO("E1 " << E1 << ": Newton " << iters[0] << " its, " << jac[0] << " Jacobians; chord " << iters[1] << " its, " << jac[1] << " Jacobians, |X - X_newton| "
             << diff[1] << "; singular seed " << iters[2] << " its, " << jac[2] << " Jacobians, " << diff[2]);
  REQUIRE(jac[0] >= 1);
  REQUIRE(jac[1] == 0);          // the chord converged on the seed alone
  REQUIRE(iters[1] >= iters[0]); // (linearly: at least as many iterations)
  REQUIRE(diff[1] <= 1e-10);     // the same orbit (both to the SNES atol)
  REQUIRE(jac[2] == jac[0]);     // the failed chord, then Newton from the guess as in the first solve
  REQUIRE(diff[2] <= 1e-10);
}
