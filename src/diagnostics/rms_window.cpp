#include "diagnostics/rms_window.hpp"
#include <algorithm>
#include <cmath>

namespace nltopo {

PetscErrorCode RmsWindow::Integrals(Vec *q)
{
  PetscFunctionBeginUser;
  if (!q_) {
    PetscCall(VecCreateMPI(fx_.Lat().Comm(), fx_.Lat().OwnedCount() + 2, PETSC_DETERMINE, q_.out()));
    PetscCall(VecZeroEntries(q_));
  }
  *q = q_;
  PetscFunctionReturn(0);
}

PetscErrorCode RmsWindow::Integrand(Vec z, Vec rate)
{
  const Lattice &lat = fx_.Lat();
  const PetscInt n = lat.OwnedCount(), xs = lat.OwnedStart();
  PetscScalar *r;
  PetscFunctionBeginUser;
  if (!open_) {
    PetscCall(VecZeroEntries(rate));
    PetscFunctionReturn(0);
  }
  carried_ = true;
  const PetscScalar *u;
  Vec ul;
  EnergyParts loc;
  PetscCall(lat.GetGhostedU(z, &ul, &u)); // indexed by global site
  PetscCall(VecGetArray(rate, &r));
  for (PetscInt k = 0; k < n; k++) r[k] = u[xs + k] * u[xs + k];
  for (size_t i = 0; i < fx_.Size(); i++) fx_.At(i).AddEnergy(u, &loc); // this rank's share
  r[n] = loc.quartic;
  r[n + 1] = loc.linear;
  PetscCall(VecRestoreArray(rate, &r));
  PetscCall(lat.RestoreGhostedU(z, &ul, &u));
  PetscFunctionReturn(0);
}

PetscErrorCode RmsWindow::AddStages(PetscReal h, PetscInt s, const PetscReal *b, const Vec *y)
{
  Vec q;
  PetscFunctionBeginUser;
  if (!open_) PetscFunctionReturn(0);
  PetscCall(Integrals(&q));
  if (!rate_) PetscCall(VecDuplicate(q, rate_.out()));
  for (PetscInt i = 0; i < s; i++) {
    if (b[i] == 0) continue;
    PetscCall(Integrand(y[i], rate_));
    PetscCall(VecAXPY(q, h * b[i], rate_));
  }
  PetscFunctionReturn(0);
}

PetscErrorCode RmsWindow::Step(PetscReal t, Vec z, const EnergyParts &e, PetscReal *start)
{
  const PetscScalar *a;
  const PetscInt n = fx_.Lat().OwnedCount();
  PetscFunctionBeginUser;
  if (!open_ && t + 1e-12 < *start) PetscFunctionReturn(0);
  PetscCall(VecGetArrayRead(z, &a));
  if (!open_) {
    open_ = true;
    carried_ = false;
    *start = t;
    acc_nl_ = acc_lin_ = 0;
    u2_prev_.assign(n, 0.0);
    du2_prev_.assign(n, 0.0);
    acc_u2_.assign(n, 0.0);
    for (PetscInt k = 0; k < n; k++) u2_prev_[k] = a[k] * a[k], du2_prev_[k] = 2 * a[k] * a[n + k];
    if (q_) PetscCall(VecZeroEntries(q_));
  } else {
    // u_i^2 by the two-point Hermite rule (its derivative 2 u_i v_i at both
    // ends: fourth order), the energies by the trapezoid
    const PetscReal h = 0.5 * (t - t_prev_), c = (t - t_prev_) * (t - t_prev_) / 12;
    for (PetscInt k = 0; k < n; k++) {
      const PetscReal u2 = a[k] * a[k], du2 = 2 * a[k] * a[n + k];
      acc_u2_[k] += h * (u2 + u2_prev_[k]) + c * (du2_prev_[k] - du2);
      u2_prev_[k] = u2;
      du2_prev_[k] = du2;
    }
    acc_nl_ += h * (e.quartic + nl_prev_);
    acc_lin_ += h * (e.linear + lin_prev_);
  }
  PetscCall(VecRestoreArrayRead(z, &a));
  t_prev_ = t;
  nl_prev_ = e.quartic;
  lin_prev_ = e.linear;
  PetscFunctionReturn(0);
}

PetscErrorCode RmsWindow::Finish(PetscReal start, Vec rms, PetscReal *nl_ratio) const
{
  PetscScalar *a;
  const PetscInt n = fx_.Lat().OwnedCount();
  const PetscReal len = t_prev_ - start;
  PetscReal nl = acc_nl_, lin = acc_lin_;
  const PetscScalar *q = NULL;
  PetscFunctionBeginUser;
  if (carried_) { // the integrator's quadrature states
    PetscCall(VecGetArrayRead(q_, &q));
    PetscReal loc[2] = {q[n], q[n + 1]}, glob[2];
    PetscCallMPI(MPIU_Allreduce(loc, glob, 2, MPIU_REAL, MPIU_SUM, fx_.Lat().Comm()));
    nl = glob[0];
    lin = glob[1];
  }
  const PetscReal *u2 = q ? q : acc_u2_.data();
  PetscCall(VecGetArray(rms, &a));
  if (len > 0) {
    for (PetscInt k = 0; k < n; k++) a[k] = std::sqrt(std::max<PetscReal>(u2[k], 0) / len);
  } else { // zero-length window: the final displacement
    for (PetscInt k = 0; k < n; k++) a[k] = std::sqrt(u2_prev_[k]);
  }
  PetscCall(VecRestoreArray(rms, &a));
  if (q) PetscCall(VecRestoreArrayRead(q_, &q));
  *nl_ratio = lin > 0 ? nl / lin : (lin_prev_ > 0 ? nl_prev_ / lin_prev_ : 0);
  PetscFunctionReturn(0);
}

} // namespace nltopo
