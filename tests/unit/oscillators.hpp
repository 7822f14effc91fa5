#pragma once
// Test problems for nltopo's second-order TS types (symsplit, rkn): the
// harmonic and the Duffing oscillator on PETSC_COMM_SELF, with their exact
// solutions (the Duffing one Jacobi-elliptic), and a short forced lattice run.
#include "helpers.hpp"
#include "timeint/simulation.hpp"
#include <petscts.h>
#include <cmath>
#include <initializer_list>
#include <utility>

namespace nltopo::test {

// u'' = -u - eps u^3 for every position of z = [u..., v...] (PETSC_COMM_SELF).
struct Oscillator {
  PetscReal eps = 0;
  PetscInt calls = 0;
};

inline PetscErrorCode OscAcceleration(TS, PetscReal, Vec z, PetscScalar *a, void *ctx)
{
  auto *o = static_cast<Oscillator *>(ctx);
  const PetscScalar *x;
  PetscInt n;
  PetscFunctionBeginUser;
  PetscCall(VecGetLocalSize(z, &n));
  PetscCall(VecGetArrayRead(z, &x));
  for (PetscInt i = 0; i < n / 2; i++) a[i] = -x[i] - o->eps * x[i] * x[i] * x[i];
  PetscCall(VecRestoreArrayRead(z, &x));
  o->calls++;
  PetscFunctionReturn(0);
}

inline PetscErrorCode OscRhs(TS, PetscReal, Vec z, Vec f, void *ctx)
{
  auto *o = static_cast<Oscillator *>(ctx);
  const PetscScalar *x;
  PetscScalar *y;
  PetscInt n;
  PetscFunctionBeginUser;
  PetscCall(VecGetLocalSize(z, &n));
  PetscCall(VecGetArrayRead(z, &x));
  PetscCall(VecGetArray(f, &y));
  for (PetscInt i = 0; i < n / 2; i++) {
    y[i] = x[n / 2 + i];
    y[n / 2 + i] = -x[i] - o->eps * x[i] * x[i] * x[i];
  }
  PetscCall(VecRestoreArray(f, &y));
  PetscCall(VecRestoreArrayRead(z, &x));
  PetscFunctionReturn(0);
}

// Jacobi sn, cn, dn (x | m) by the arithmetic-geometric mean (Abramowitz & Stegun 16.4).
inline void JacobiSnCnDn(double x, double m, double *sn, double *cn, double *dn)
{
  double a[32], c[32], b = std::sqrt(1 - m), phi[32];
  a[0] = 1;
  c[0] = std::sqrt(m);
  int n = 0;
  while (std::abs(c[n]) > 1e-17 && n < 30) {
    a[n + 1] = 0.5 * (a[n] + b);
    c[n + 1] = 0.5 * (a[n] - b);
    b = std::sqrt(a[n] * b);
    n++;
  }
  phi[n] = std::ldexp(1.0, n) * a[n] * x;
  for (int k = n; k > 0; k--) phi[k - 1] = 0.5 * (phi[k] + std::asin(c[k] / a[k] * std::sin(phi[k])));
  *sn = std::sin(phi[0]);
  *cn = std::cos(phi[0]);
  *dn = n > 0 ? std::cos(phi[0]) / std::cos(phi[1] - phi[0]) : 1;
}

// u'' = -u - eps u^3, u(0) = A, v(0) = 0 (eps = 0 or 1): for eps = 1
// u = A cn(w t | m), v = -A w sn dn, w^2 = 1 + A^2, m = A^2 / (2 (1 + A^2)).
inline void OscillatorExact(double eps, double A, double t, double *u, double *v)
{
  if (eps == 0) {
    *u = A * std::cos(t);
    *v = -A * std::sin(t);
    return;
  }
  const double w = std::sqrt(1 + A * A);
  double sn, cn, dn;
  JacobiSnCnDn(w * t, A * A / (2 * (1 + A * A)), &sn, &cn, &dn);
  *u = A * cn;
  *v = -A * w * sn * dn;
}

// The state [u0, v0] of one oscillator.
inline Vec OscillatorState(PetscReal u0, PetscReal v0)
{
  Vec z;
  PCHK(VecCreateSeq(PETSC_COMM_SELF, 2, &z));
  PCHK(VecSetValue(z, 0, u0, INSERT_VALUES));
  PCHK(VecSetValue(z, 1, v0, INSERT_VALUES));
  PCHK(VecAssemblyBegin(z));
  PCHK(VecAssemblyEnd(z));
  return z;
}

// The paper-default lattice on comm forced at the insulated frequency (site 52,
// S = 0.2, a 5-period burst) to E* = 1 for 300 time units, with the given
// -sim_ts_* options set for this run only.
inline SimulationResult ShortForcedRun(MPI_Comm comm, std::initializer_list<std::pair<const char *, const char *>> ts_options)
{
  LatticeParams p;
  Lattice lat;
  PCHK(lat.Setup(comm, p));
  ToneBurstOptions fo;
  fo.profile = ForceProfile::Site;
  fo.omega = std::sqrt(3.0);
  fo.site = 51;
  fo.amplitude = 0.2;
  fo.energy = 1;
  fo.tau_periods = 5;
  fo.t0_taus = 2;
  ToneBurst burst;
  PCHK(burst.Setup(lat, fo, nullptr));
  SimulationOptions so;
  so.t_final = 300;
  so.sample_dt = 0;
  so.progress = 0;
  SimulationResult r;
  for (const auto &o : ts_options) PCHK(PetscOptionsSetValue(NULL, o.first, o.second));
  PCHK(Simulate(*Effects(lat, &burst), so, NULL, NULL, &r));
  for (const auto &o : ts_options) PCHK(PetscOptionsClearValue(NULL, o.first));
  return r;
}

} // namespace nltopo::test
