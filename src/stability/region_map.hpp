#pragma once
// The tangent map of a truncated region of the lattice around the interface,
// integrated densely from the tangent stiffness K_T(u(t)) recorded along one
// orbit integration (the localized route, stability/floquet_localized.hpp, and
// the exterior route, stability/floquet_exterior.hpp).
//
// The region's sites lo..hi couple to nothing outside it (the neighbours
// beyond its ends are held at rest: K_T's diagonal keeps their bonds). The
// map is the symplectic splitting of the orbit's flow (-nnm_ts_symsplit_scheme,
// its steps per period) applied to the tangent equations
//   xi'' = -K_T(u(t)) xi - c(n) xi'
// with the damping c of the region (zero: the plain tangent map), as an exact
// factor exp(-c h) on the tangent momentum after every step.
#include "orbits/flow.hpp"
#include "stability/floquet_localized.hpp"
#include "timeint/symsplit_schemes.hpp"
#include <vector>

namespace nltopo {

// K_T of the region at every stage of one period (every rank), and the
// scheme: rec[e * 2n + s] = K_T(lo + s, lo + s), rec[e * 2n + n + s] =
// K_T(lo + s, lo + s + 1), e the evaluation of the acceleration (0 at the
// start, then one after every drift). Collective.
PetscErrorCode RecordStiffness(PeriodicFlow &flow, Vec z0, PetscReal T, const LocalizedRegion &reg, std::vector<PetscReal> *rec,
                               const symsplit::Scheme **sch);

// K_T at u = 0 (the linear lattice's K, perturbations included) on every
// site and bond: kd[i] = K(i, i), kb[b] = K(b, b + 1), b = 0 .. N - 2; every
// rank. Collective.
PetscErrorCode LinearStiffness(const PeriodicFlow &flow, std::vector<PetscReal> *kd, std::vector<PetscReal> *kb);

// The region map (2n x 2n, column-major, region layout [u_lo..u_hi,
// v_lo..v_hi]) on rank 0 (empty elsewhere), its columns shared among the
// ranks. rec: the stiffness rows as RecordStiffness writes them, stride
// values apart per evaluation (2n: recorded; 0: one row for every stage, a
// time-independent K_T). Collective.
PetscErrorCode RegionMapOnRoot(MPI_Comm comm, const LocalizedRegion &reg, const std::vector<PetscReal> &rec, PetscInt stride, const symsplit::Scheme &sch,
                               PetscInt steps, PetscReal T, std::vector<PetscReal> *a);

} // namespace nltopo
