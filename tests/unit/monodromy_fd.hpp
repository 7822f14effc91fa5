#pragma once
// Central differences of the periodic-orbit flow, the known truth its
// monodromy and tangent columns are checked against (test_orbits.cpp,
// test_orbits_symplectic.cpp).
#include "helpers.hpp"
#include "orbits/flow.hpp"
#include <cmath>

namespace nltopo::test {

// Every column of S = [dz(T)/dz0 | dz(T)/dbeta] at (u, v, T, beta) against the
// central difference (step h) of flow.Integrate: *maxerr = max |S - FD|,
// *maxval = max |S| over the 2N state columns and the beta column.
inline void MonodromyAgainstFD(const Lattice &lat, PeriodicFlow &flow, const std::vector<PetscReal> &u, const std::vector<PetscReal> &v, PetscReal T,
                               PetscReal beta, Mat S, PetscReal h, PetscReal *maxerr, PetscReal *maxval)
{
  const PetscInt N = lat.N(), n = 2 * N;
  OwnedVec zp, zm;
  PCHK(lat.CreateStateVector(zp.out()));
  PCHK(VecDuplicate(zp, zm.out()));
  *maxerr = *maxval = 0;
  for (PetscInt j = 0; j <= n; j++) { // columns: initial conditions, then beta
    std::vector<PetscReal> up = u, um = u, vp = v, vm = v;
    PetscReal bp = beta, bm = beta;
    if (j < N) up[j] += h, um[j] -= h;
    else if (j < n) vp[j - N] += h, vm[j - N] -= h;
    else bp += h, bm -= h;
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
      *maxerr = std::max(*maxerr, std::abs(sc[i] - fd[i]));
      *maxval = std::max(*maxval, std::abs(sc[i]));
    }
  }
}

// |w - ref|_inf / |ref|_inf (w is overwritten with w - ref).
inline PetscReal RelativeDifference(Vec w, Vec ref)
{
  PetscReal e, r;
  PCHK(VecAXPY(w, -1.0, ref));
  PCHK(VecNorm(w, NORM_INFINITY, &e));
  PCHK(VecNorm(ref, NORM_INFINITY, &r));
  return e / r;
}

} // namespace nltopo::test
