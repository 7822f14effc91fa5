#include "stability/branch_switch.hpp"
#include <cmath>

namespace nltopo {

namespace {

// One point of the start branch: orbit X's record (z0 row on rank 0).
PetscErrorCode AppendStartPoint(Shooting &shoot, Vec X, Vec z, PetscInt its, Branch *b)
{
  BranchPoint p;
  PetscFunctionBeginUser;
  PetscCall(OrbitPoint(shoot, X, z, &p));
  p.newton_its = its;
  PetscCall(AppendPoint(shoot.Flow().Lat(), z, p, b));
  PetscFunctionReturn(0);
}

} // namespace

PetscInt SwitchedPeriodMultiple(EventKind k) { return k == EventKind::BranchPoint ? 1 : k == EventKind::PeriodDoubling ? 2 : 0; }

PetscErrorCode StartSwitchedBranch(Shooting &shoot, Vec Xs, const BifurcationEvent &e, PetscReal step, PetscInt sign, Branch *start, bool *pinned,
                                   PetscReal *away)
{
  const Lattice &lat = shoot.Flow().Lat();
  MPI_Comm comm = lat.Comm();
  OwnedVec X1, t, Xpred, zs, z1, phi, d;
  bool ok;
  PetscInt its;
  PetscFunctionBeginUser;
  *start = Branch();
  *pinned = false;
  const PetscInt m = SwitchedPeriodMultiple(e.kind);
  PetscCheck(m > 0, comm, PETSC_ERR_SUP, "-cont_switch follows branch points (kind 2) and period doublings (kind 3); this event is a %s", EventKindName(e.kind));
  PetscCheck(shoot.Flow().PeriodMultiple() % m == 0, comm, PETSC_ERR_PLIB, "-cont_switch: the family born at a %s is integrated with period multiple %" PetscInt_FMT ", not a multiple of %" PetscInt_FMT,
             EventKindName(e.kind), shoot.Flow().PeriodMultiple(), m);
  PetscCheck(e.vector.size() == (size_t)(2 * lat.N()), comm, PETSC_ERR_PLIB, "-cont_switch: the event has no critical eigenvector");
  for (OwnedVec *v : {&X1, &t, &Xpred, &d}) PetscCall(VecDuplicate(Xs, v->out()));
  PetscCall(lat.CreateStateVector(zs.out()));
  PetscCall(VecDuplicate(zs, z1.out()));
  PetscCall(VecDuplicate(zs, phi.out()));
  PetscReal Ts, bs, zn;
  PetscCall(shoot.Unpack(Xs, zs, &Ts, &bs));
  PetscCall(VecNorm(zs, NORM_2, &zn));
  // X* as an orbit of the new family: the parent's orbit traversed m times
  OwnedVec Xm;
  PetscCall(VecDuplicate(Xs, Xm.out()));
  PetscCall(shoot.Pack(zs, m * Ts, bs, Xm));
  // X1: pinned at eps along (phi, 0, 0)
  PetscCall(StateFromRow(lat, e.vector.data(), phi));
  PetscCall(shoot.Pack(phi, 0.0, 0.0, t));
  const PetscReal eps = sign * step * zn;
  PetscCall(VecWAXPY(Xpred, eps, t, Xm));
  PetscCall(shoot.SetArclengthConstraint(zs, t, Xpred));
  PetscCall(VecCopy(Xpred, X1));
  PetscCall(shoot.Solve(X1, &ok, &its));
  *pinned = ok;
  if (!ok) PetscFunctionReturn(0);
  // the share of the first step along phi
  PetscReal T1, b1, dz, along;
  PetscCall(shoot.Unpack(X1, z1, &T1, &b1));
  PetscCall(VecWAXPY(d, -1.0, Xm, X1));
  PetscCall(VecAXPY(z1, -1.0, zs));
  PetscCall(VecNorm(z1, NORM_2, &dz));
  PetscCall(VecDot(z1, phi, &along));
  *away = dz > 0 ? std::abs(along) / dz : 0;
  // the two points and the next step (the resume state of orbits/continuation.hpp)
  PetscCall(AppendStartPoint(shoot, Xm, zs, 0, start));
  PetscCall(AppendStartPoint(shoot, X1, z1, its, start));
  PetscReal ds;
  PetscCall(VecNormalize(d, &ds));
  PetscReal dT, db;
  std::vector<PetscReal> row;
  PetscCall(shoot.Unpack(d, z1, &dT, &db));
  PetscCall(AppendStateRow(lat, z1, &row));
  if (!row.empty()) row.push_back(dT), row.push_back(db);
  start->next_tangent = std::move(row);
  start->next_ds = ds;
  PetscFunctionReturn(0);
}

} // namespace nltopo
