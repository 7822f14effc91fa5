// The finite-time Lyapunov exponent (stability/lyapunov.hpp) against known
// truth: on the linear lattice the tangent map is the bounded flow of its
// modes, so lambda T stays bounded as the window T grows; on a strongly
// nonlinear (chaotic) state, lambda equals the separation rate of the orbit
// and a twin displaced by 1e-9 along the same start vector, integrated by the
// same scheme, while the separation stays linear.
#include "helpers.hpp"
#include "effects/effect.hpp"
#include "orbits/flow.hpp"
#include "stability/lyapunov.hpp"
#include <cmath>

using namespace nltopo;
using namespace nltopo::test;

namespace {
// The state with displacement a (-1)^n e^{-|n - m| / 4} around the interface, at rest.
void Bump(const Lattice &lat, PetscReal a, Vec z)
{
  const PetscInt N = lat.N(), m = N / 2;
  std::vector<PetscReal> u(N), v(N, 0.0);
  for (PetscInt n = 0; n < N; n++) u[n] = a * (n % 2 ? -1 : 1) * std::exp(-std::abs((double)(n - m)) / 4);
  SetState(lat, u, v, z);
}
} // namespace

TEST_CASE("finite-time Lyapunov exponent: bounded growth on the linear lattice", "[lyapunov]")
{
  LatticeParams p;
  p.Gamma = 0; // linear
  p.cells = 10;
  Lattice lat;
  PCHK(lat.Setup(PETSC_COMM_WORLD, p));
  EffectList fx(lat);
  PCHK(BuildLatticeEffects(lat, &fx));
  OwnedVec z;
  PCHK(lat.CreateStateVector(z.out()));
  Bump(lat, 1.0, z);
  PetscReal prev = 0;
  for (PetscReal T : {100.0, 400.0, 1600.0}) {
    LyapunovResult r;
    PCHK(FiniteTimeLyapunov(fx, z, T, 10, 0.1, &r));
    INFO("T = " << T << ": lambda = " << r.exponent << ", lambda T = " << r.exponent * T << ", intervals " << r.intervals);
    REQUIRE(r.intervals == (PetscInt)(T / 10));
    // |w(t)| <= cond of the modal basis (symplectic, elliptic modes): lambda T bounded, lambda -> 0 like 1 / T
    REQUIRE(std::abs(r.exponent * T) < 3);
    if (prev > 0) REQUIRE(std::abs(r.exponent) < prev);
    prev = std::abs(r.exponent) + 1e-300;
  }
}

TEST_CASE("finite-time Lyapunov exponent: the separation rate of a twin orbit", "[lyapunov]")
{
  LatticeParams p; // cubic 0.5: at large amplitude the interface motion is chaotic
  p.cells = 10;
  Lattice lat;
  PCHK(lat.Setup(PETSC_COMM_WORLD, p));
  EffectList fx(lat);
  PCHK(BuildLatticeEffects(lat, &fx));
  OwnedVec z, z2, zT, zT2;
  PCHK(lat.CreateStateVector(z.out()));
  PCHK(VecDuplicate(z, z2.out()));
  PCHK(VecDuplicate(z, zT.out()));
  PCHK(VecDuplicate(z, zT2.out()));
  Bump(lat, 3.0, z);
  const PetscReal T = 150, dt = 0.02, eps = 1e-9; // eps: far above the rounding the orbit accumulates (~1e-13 after the growth)
  LyapunovResult r;
  PCHK(FiniteTimeLyapunov(fx, z, T, 5, dt, &r));
  INFO("lambda = " << r.exponent << " (first half " << r.half << "), lambda T = " << r.exponent * T);
  REQUIRE(r.exponent * T > 3); // grown by e^3 and more (the linear lattice: e^0.07 at any T, above)
  // the twin along the route's start vector (the same: a fixed unit vector), one integration of T in the same steps
  FlowOptions fo;
  fo.steps = (PetscInt)std::lround(T / dt);
  PeriodicFlow flow;
  PCHK(flow.Setup(fx, fo));
  { // the start vector: the route's (LyapunovStartValue of the natural state index, unit norm)
    const PetscInt N = lat.N();
    std::vector<PetscReal> u(N), v(N);
    for (PetscInt i = 0; i < N; i++) u[i] = LyapunovStartValue(i), v[i] = LyapunovStartValue(N + i);
    SetState(lat, u, v, z2);
    PetscReal nv;
    PCHK(VecNormalize(z2, &nv));
    PCHK(VecAYPX(z2, eps, z)); // z2 = z + eps v
  }
  PCHK(flow.Integrate(z, T, 0.0, zT));
  PCHK(flow.Integrate(z2, T, 0.0, zT2));
  PetscReal d;
  PCHK(VecAXPY(zT2, -1.0, zT));
  PCHK(VecNorm(zT2, NORM_2, &d));
  const PetscReal twin = std::log(d / eps) / T;
  INFO("twin separation rate " << twin << ", |dz(T)| = " << d);
  REQUIRE(d < 1e-4); // still linear
  REQUIRE(r.exponent == Approx(twin).epsilon(1e-3));
}
