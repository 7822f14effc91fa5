#include "diagnostics/rms_window.hpp"
#include "timeint/ts_rkn.hpp"
#include <cmath>

namespace nltopo {

PetscErrorCode RmsWindow::GaussStep(PetscReal t, bool *done)
{
  PetscReal tp;
  PetscFunctionBeginUser;
  PetscCall(TSGetPrevTime(interp_, &tp));
  *done = t_prev_ >= tp - 1e-12 * (1 + std::abs(tp)) && t > t_prev_; // [t_prev, t] inside the last step
  if (!*done) PetscFunctionReturn(0);
  if (!zs_) PetscCall(fx_.Lat().CreateStateVector(zs_.out()));
  const PetscReal h = t - t_prev_, x = std::sqrt(15.0) / 10, node[3] = {0.5 - x, 0.5, 0.5 + x}, w[3] = {5.0 / 18, 8.0 / 18, 5.0 / 18};
  const PetscInt n = fx_.Lat().OwnedCount();
  for (int q = 0; q < 3; q++) {
    const PetscScalar *a;
    EnergyParts eq;
    PetscCall(TSRknInterpolatePositions(interp_, std::max(t_prev_, tp) + node[q] * h, zs_)); // the kinetic part of eq is not used
    PetscCall(fx_.Energy(zs_, &eq));
    PetscCall(VecGetArrayRead(zs_, &a));
    for (PetscInt k = 0; k < n; k++) acc_u2_[k] += w[q] * h * a[k] * a[k];
    PetscCall(VecRestoreArrayRead(zs_, &a));
    acc_nl_ += w[q] * h * eq.quartic;
    acc_lin_ += w[q] * h * eq.linear;
  }
  PetscFunctionReturn(0);
}

PetscErrorCode RmsWindow::Step(PetscReal t, Vec z, const EnergyParts &e, PetscReal *start)
{
  const PetscScalar *a;
  const PetscInt n = fx_.Lat().OwnedCount();
  PetscFunctionBeginUser;
  if (!open_ && t + 1e-12 < *start) PetscFunctionReturn(0);
  if (!open_) {
    PetscCall(VecGetArrayRead(z, &a));
    open_ = true;
    *start = t;
    acc_nl_ = acc_lin_ = 0;
    u2_prev_.assign(n, 0.0);
    acc_u2_.assign(n, 0.0);
    for (PetscInt k = 0; k < n; k++) u2_prev_[k] = a[k] * a[k];
  } else {
    const PetscReal h = 0.5 * (t - t_prev_);
    bool gauss = false;
    if (interp_) PetscCall(GaussStep(t, &gauss));
    PetscCall(VecGetArrayRead(z, &a));
    for (PetscInt k = 0; k < n; k++) {
      const PetscReal u2 = a[k] * a[k];
      if (!gauss) acc_u2_[k] += h * (u2 + u2_prev_[k]);
      u2_prev_[k] = u2;
    }
    if (!gauss) {
      acc_nl_ += h * (e.quartic + nl_prev_);
      acc_lin_ += h * (e.linear + lin_prev_);
    }
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
  PetscFunctionBeginUser;
  PetscCall(VecGetArray(rms, &a));
  if (len > 0) {
    for (PetscInt k = 0; k < n; k++) a[k] = std::sqrt(acc_u2_[k] / len);
  } else { // zero-length window: the final displacement
    for (PetscInt k = 0; k < n; k++) a[k] = std::sqrt(u2_prev_[k]);
  }
  PetscCall(VecRestoreArray(rms, &a));
  *nl_ratio = acc_lin_ > 0 ? acc_nl_ / acc_lin_ : (lin_prev_ > 0 ? nl_prev_ / lin_prev_ : 0);
  PetscFunctionReturn(0);
}

} // namespace nltopo
