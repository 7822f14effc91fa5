// Lattice against model.md: K entry by entry, the state operator, cubic force
// vs finite differences of the energy, tangent stiffness vs finite differences
// of the force.
#include "effects/rhs.hpp"
#include "helpers.hpp"
#include <cmath>

using namespace nltopo;
using namespace nltopo::test;

// model.md "Bonds", written independently of LatticeParams::Stiff, 1-based.
static PetscReal SpecBond(const LatticeParams &p, PetscInt i /*1-based bond joining i, i+1*/)
{
  const PetscReal k1 = p.k * (1 + p.gamma), k2 = p.k * (1 - p.gamma);
  const PetscInt Nc = p.cells;
  switch (p.layout) {
  case Layout::Left: return i % 2 ? k2 : k1;
  case Layout::Right: return i % 2 ? k1 : k2;
  default:
    if (i <= 2 * Nc) return i % 2 ? k2 : k1;
    return i % 2 ? k1 : k2;
  }
}

TEST_CASE("K is the spec's matrix entry by entry", "[lattice]")
{
  for (Layout layout : {Layout::Interface, Layout::Left, Layout::Right})
    for (PetscInt Nc : {1, 2, 3, 25}) {
      LatticeParams p;
      p.cells = Nc;
      p.layout = layout;
      Lattice lat;
      PCHK(lat.Setup(PETSC_COMM_WORLD, p));
      const PetscInt N = lat.N();
      REQUIRE(N == (layout == Layout::Interface ? 4 * Nc + 2 : 2 * Nc));
      PetscInt lo, hi;
      PCHK(MatGetOwnershipRange(lat.K(), &lo, &hi));
      for (PetscInt r = lo; r < hi; r++)
        for (PetscInt c = 0; c < N; c++) {
          PetscScalar v;
          PCHK(MatGetValues(lat.K(), 1, &r, 1, &c, &v));
          PetscReal expect = 0;
          if (r == c) expect = 3.0; // k_hat = k1 + k2 + gamma0 for every site
          else if (c == r + 1) expect = -SpecBond(p, r + 1);
          else if (c == r - 1) expect = -SpecBond(p, c + 1);
          INFO("layout " << LayoutName(layout) << " Nc " << Nc << " entry (" << r + 1 << "," << c + 1 << ")");
          REQUIRE(std::abs(v - expect) < 1e-15);
        }
    }
}

TEST_CASE("interface site m has a stiff bond on each side; 51 stiff and 50 soft bonds", "[lattice][serial]")
{
  LatticeParams p;
  const PetscInt m = p.InterfaceSite(); // 0-based: model.md's site 51
  REQUIRE(m == 50);
  REQUIRE(p.Stiff(m - 1));
  REQUIRE(p.Stiff(m));
  PetscInt stiff = 0;
  for (PetscInt b = 0; b < p.N() - 1; b++) stiff += p.Stiff(b);
  REQUIRE(stiff == 51);
  REQUIRE(p.N() - 1 - stiff == 50);
}

TEST_CASE("state operator L z = [v, -K u]", "[lattice]")
{
  LatticeParams p;
  p.cells = 3;
  Lattice lat;
  PCHK(lat.Setup(PETSC_COMM_WORLD, p));
  const PetscInt N = lat.N();
  OwnedVec z, f, u, Ku;
  PCHK(lat.CreateStateVector(z.out()));
  PCHK(VecDuplicate(z, f.out()));
  PCHK(DMCreateGlobalVector(lat.SiteDM(), u.out()));
  PCHK(VecDuplicate(u, Ku.out()));
  const auto uv = Pseudo(N, 1), vv = Pseudo(N, 2);
  SetState(lat, uv, vv, z);
  Scatter(uv, u);
  OwnedMat L; // the state Jacobian at rest
  PCHK(lat.CreateStateMatrix(L.out()));
  PCHK(Effects(lat)->AssembleStateJacobian(NULL, L));
  PCHK(MatMult(L, z, f));
  PCHK(MatMult(lat.K(), u, Ku));
  const auto kv = Gather(Ku);
  std::vector<PetscReal> fu, fv;
  GetState(lat, f, &fu, &fv);
  for (PetscInt i = 0; i < N; i++) {
    REQUIRE(fu[i] == Approx(vv[i]).margin(1e-15));
    REQUIRE(fv[i] == Approx(-kv[i]).margin(1e-14));
  }
}

TEST_CASE("the linear-coupling effect (stencil) equals the assembled L z", "[lattice][effects]")
{
  for (Layout layout : {Layout::Interface, Layout::Left, Layout::Right}) {
    LatticeParams p;
    p.cells = 4;
    p.layout = layout;
    p.Gamma = 0; // linear scene: the RHS is the linear effect alone
    Lattice lat;
    PCHK(lat.Setup(PETSC_COMM_WORLD, p));
    OwnedVec z, f, g;
    PCHK(lat.CreateStateVector(z.out()));
    PCHK(VecDuplicate(z, f.out()));
    PCHK(VecDuplicate(z, g.out()));
    SetState(lat, Pseudo(lat.N(), 11), Pseudo(lat.N(), 12), z);
    auto fx_rhs = Effects(lat);
    Rhs rhs(*fx_rhs);
    PCHK(rhs.Evaluate(0.0, z, f));
    OwnedMat L;
    PCHK(lat.CreateStateMatrix(L.out()));
    PCHK(fx_rhs->AssembleStateJacobian(NULL, L));
    PCHK(MatMult(L, z, g));
    PCHK(VecAXPY(g, -1.0, f));
    PetscReal err;
    PCHK(VecNorm(g, NORM_INFINITY, &err));
    REQUIRE(err < 1e-14);
  }
}

// Acceleration a(u) = -(K u + f_NL(u)) from the effects-composed RHS at v = 0.
static std::vector<PetscReal> Acceleration(const Lattice &lat, const std::vector<PetscReal> &u)
{
  Vec z, f;
  lat.CreateStateVector(&z);
  VecDuplicate(z, &f);
  SetState(lat, u, std::vector<PetscReal>(lat.N(), 0.0), z);
  auto fx_rhs = Effects(lat);
  Rhs rhs(*fx_rhs);
  rhs.Evaluate(0.0, z, f);
  std::vector<PetscReal> fu, a;
  GetState(lat, f, &fu, &a);
  VecDestroy(&z);
  VecDestroy(&f);
  return a;
}

static PetscReal PotentialEnergy(const Lattice &lat, const std::vector<PetscReal> &u)
{
  Vec z;
  lat.CreateStateVector(&z);
  SetState(lat, u, std::vector<PetscReal>(lat.N(), 0.0), z);
  EnergyParts e;
  Effects(lat)->Energy(z, &e);
  VecDestroy(&z);
  return e.linear + e.quartic;
}

TEST_CASE("cubic force equals minus the gradient of the energy (central differences)", "[lattice]")
{
  for (Layout layout : {Layout::Interface, Layout::Left, Layout::Right}) {
    LatticeParams p;
    p.cells = 3;
    p.layout = layout;
    p.Gamma = 2.0;
    Lattice lat;
    PCHK(lat.Setup(PETSC_COMM_WORLD, p));
    const PetscInt N = lat.N();
    auto u = Pseudo(N, 7);
    const auto a = Acceleration(lat, u);
    const PetscReal h = 1e-5;
    for (PetscInt j = 0; j < N; j++) {
      auto up = u, um = u;
      up[j] += h;
      um[j] -= h;
      const PetscReal grad = (PotentialEnergy(lat, up) - PotentialEnergy(lat, um)) / (2 * h);
      REQUIRE(a[j] == Approx(-grad).epsilon(1e-7).margin(1e-8));
    }
  }
}

TEST_CASE("tangent stiffness and state Jacobian equal central differences of the force", "[lattice]")
{
  LatticeParams p;
  p.cells = 2;
  p.Gamma = 1.5;
  Lattice lat;
  PCHK(lat.Setup(PETSC_COMM_WORLD, p));
  const PetscInt N = lat.N();
  const auto u = Pseudo(N, 3);
  OwnedVec uv, z;
  OwnedMat KT, A;
  PCHK(DMCreateGlobalVector(lat.SiteDM(), uv.out()));
  Scatter(u, uv);
  PCHK(DMCreateMatrix(lat.SiteDM(), KT.out()));
  PCHK(Effects(lat)->AssembleTangentStiffness(uv, KT));
  PCHK(lat.CreateStateVector(z.out()));
  SetState(lat, u, std::vector<PetscReal>(N, 0.0), z);
  PCHK(lat.CreateStateMatrix(A.out()));
  PCHK(Effects(lat)->AssembleStateJacobian(z, A));
  const PetscReal h = 1e-6;
  for (PetscInt j = 0; j < N; j++) {
    auto up = u, um = u;
    up[j] += h;
    um[j] -= h;
    const auto ap = Acceleration(lat, up), am = Acceleration(lat, um);
    PetscInt lo, hi;
    PCHK(MatGetOwnershipRange(KT, &lo, &hi));
    for (PetscInt i = lo; i < hi; i++) {
      const PetscReal fd = -(ap[i] - am[i]) / (2 * h); // K_T = -da/du
      PetscScalar kt, aij;
      const PetscInt ri = lat.StateIndexV(i), cj = lat.StateIndexU(j);
      PCHK(MatGetValues(KT, 1, &i, 1, &j, &kt));
      PCHK(MatGetValues(A, 1, &ri, 1, &cj, &aij));
      REQUIRE(kt == Approx(fd).epsilon(1e-6).margin(1e-7));
      REQUIRE(aij == Approx(-fd).epsilon(1e-6).margin(1e-7));
      // u' = v block: identity
      const PetscInt ru = lat.StateIndexU(i), cv = lat.StateIndexV(j);
      PetscScalar one;
      PCHK(MatGetValues(A, 1, &ru, 1, &cv, &one));
      REQUIRE(one == (i == j ? 1.0 : 0.0));
    }
  }
}
