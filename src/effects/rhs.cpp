#include "effects/rhs.hpp"
#include "core/log.hpp"

namespace nltopo {

Rhs::Rhs(const Lattice &lat, const ToneBurst *forcing) : lat_(lat), forcing_(forcing && forcing->Present() ? forcing : nullptr), cubic_(lat.HasCubic()) {}

PetscErrorCode Rhs::AddLocalEffects(PetscReal t, Vec x, PetscScalar *a)
{
  PetscFunctionBeginUser;
  if (cubic_) {
    const PetscScalar *u;
    Vec ul;
    PetscCall(PetscLogEventBegin(Log().rhs_cubic, 0, 0, 0, 0));
    count_.cubic++;
    PetscCall(lat_.GetGhostedU(x, &ul, &u));
    lat_.AddCubicAcceleration(u, a);
    PetscCall(lat_.RestoreGhostedU(x, &ul, &u));
    PetscCall(PetscLogFlops(10.0 * lat_.OwnedCount()));
    PetscCall(PetscLogEventEnd(Log().rhs_cubic, 0, 0, 0, 0));
  }
  if (forcing_) {
    PetscCall(PetscLogEventBegin(Log().rhs_forcing, 0, 0, 0, 0));
    count_.forcing++;
    forcing_->Add(t, a);
    PetscCall(PetscLogEventEnd(Log().rhs_forcing, 0, 0, 0, 0));
  }
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
  if (cubic_ || forcing_) {
    PetscScalar *fa;
    PetscCall(VecGetArray(f, &fa));
    PetscCall(AddLocalEffects(t, z, fa + lat_.OwnedCount() - lat_.OwnedStart())); // the v' half
    PetscCall(VecRestoreArray(f, &fa));
  }
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
  if (cubic_ || forcing_) {
    PetscScalar *pa;
    PetscCall(VecGetArray(pdot, &pa));
    PetscCall(AddLocalEffects(t, q, pa - lat_.OwnedStart()));
    PetscCall(VecRestoreArray(pdot, &pa));
  }
  PetscFunctionReturn(0);
}

} // namespace nltopo
