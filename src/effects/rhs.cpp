#include "effects/rhs.hpp"
#include "core/log.hpp"
#include <petscdmda.h>

namespace nltopo {

Rhs::Rhs(const Lattice &lat, const ToneBurst *forcing) : lat_(lat), forcing_(forcing && forcing->Present() ? forcing : nullptr), cubic_(lat.HasCubic())
{
  MPI_Comm_size(lat.Comm(), &size_);
}

// Cubic bonds and forcing on raw arrays. x holds displacements with stride
// dof (u at offset 0); f receives accelerations at offset dof-1.
PetscErrorCode Rhs::AddLocalEffects(PetscReal t, DM dm, Vec x, Vec f, PetscInt dof)
{
  PetscScalar *fa;
  const PetscInt xs = lat_.OwnedStart();
  PetscFunctionBeginUser;
  if (!cubic_ && !forcing_) PetscFunctionReturn(0);
  PetscCall(VecGetArray(f, &fa));
  PetscScalar *fbase = fa - dof * xs;
  if (cubic_) {
    PetscCall(PetscLogEventBegin(Log().rhs_cubic, 0, 0, 0, 0));
    count_.cubic++;
    const PetscScalar *xa;
    if (size_ == 1) { // one rank: the global array already holds every neighbour
      PetscCall(VecGetArrayRead(x, &xa));
      lat_.AddCubicAcceleration(xa, dof, fbase + dof - 1, dof);
      PetscCall(VecRestoreArrayRead(x, &xa));
    } else {
      Vec xl;
      PetscInt gxs;
      PetscCall(DMGetLocalVector(dm, &xl));
      PetscCall(DMGlobalToLocalBegin(dm, x, INSERT_VALUES, xl));
      PetscCall(DMGlobalToLocalEnd(dm, x, INSERT_VALUES, xl));
      PetscCall(DMDAGetGhostCorners(dm, &gxs, NULL, NULL, NULL, NULL, NULL));
      PetscCall(VecGetArrayRead(xl, &xa));
      lat_.AddCubicAcceleration(xa - dof * gxs, dof, fbase + dof - 1, dof);
      PetscCall(VecRestoreArrayRead(xl, &xa));
      PetscCall(DMRestoreLocalVector(dm, &xl));
    }
    PetscCall(PetscLogFlops(10.0 * lat_.OwnedCount()));
    PetscCall(PetscLogEventEnd(Log().rhs_cubic, 0, 0, 0, 0));
  }
  if (forcing_) {
    PetscCall(PetscLogEventBegin(Log().rhs_forcing, 0, 0, 0, 0));
    count_.forcing++;
    forcing_->Add(t, fbase, dof, dof - 1);
    PetscCall(PetscLogEventEnd(Log().rhs_forcing, 0, 0, 0, 0));
  }
  PetscCall(VecRestoreArray(f, &fa));
  PetscFunctionReturn(0);
}

PetscErrorCode Rhs::Evaluate(PetscReal t, Vec z, Vec f)
{
  PetscFunctionBeginUser;
  count_.rhs++;
  PetscCall(PetscLogEventBegin(Log().rhs_linear, 0, 0, 0, 0));
  count_.linear++;
  PetscCall(MatMult(lat_.L(), z, f));
  PetscCall(PetscLogEventEnd(Log().rhs_linear, 0, 0, 0, 0));
  PetscCall(AddLocalEffects(t, lat_.StateDM(), z, f, 2));
  PetscFunctionReturn(0);
}

PetscErrorCode Rhs::Momentum(PetscReal t, Vec q, Vec pdot)
{
  PetscFunctionBeginUser;
  count_.rhs++;
  PetscCall(PetscLogEventBegin(Log().rhs_linear, 0, 0, 0, 0));
  count_.linear++;
  PetscCall(MatMult(lat_.K(), q, pdot));
  PetscCall(VecScale(pdot, -1.0));
  PetscCall(PetscLogEventEnd(Log().rhs_linear, 0, 0, 0, 0));
  PetscCall(AddLocalEffects(t, lat_.SiteDM(), q, pdot, 1));
  PetscFunctionReturn(0);
}

} // namespace nltopo
