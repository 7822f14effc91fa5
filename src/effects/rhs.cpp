#include "effects/rhs.hpp"
#include "core/log.hpp"

namespace nltopo {

Rhs::Rhs(const Lattice &lat, const ToneBurst *forcing) : lat_(lat), forcing_(forcing && forcing->Present() ? forcing : nullptr), cubic_(lat.HasCubic()) {}

PetscErrorCode Rhs::AddLocalEffects(PetscReal t, const PetscScalar *u, PetscScalar *a)
{
  PetscFunctionBeginUser;
  if (cubic_) {
    PetscCall(PetscLogEventBegin(Log().rhs_cubic, 0, 0, 0, 0));
    count_.cubic++;
    lat_.AddCubicAcceleration(u, a);
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

PetscErrorCode Rhs::Accelerate(PetscReal t, Vec x, PetscScalar *a)
{
  const PetscScalar *u;
  Vec ul;
  PetscFunctionBeginUser;
  PetscCall(lat_.GetGhostedU(x, &ul, &u));
  PetscCall(PetscLogEventBegin(Log().rhs_linear, 0, 0, 0, 0));
  count_.linear++;
  lat_.LinearAcceleration(u, a); // -K u as a stencil over the bond rule of K
  PetscCall(PetscLogFlops(5.0 * lat_.OwnedCount()));
  PetscCall(PetscLogEventEnd(Log().rhs_linear, 0, 0, 0, 0));
  PetscCall(AddLocalEffects(t, u, a));
  PetscCall(lat_.RestoreGhostedU(x, &ul, &u));
  PetscFunctionReturn(0);
}

PetscErrorCode Rhs::Evaluate(PetscReal t, Vec z, Vec f)
{
  const PetscInt xm = lat_.OwnedCount(), xs = lat_.OwnedStart();
  const PetscScalar *za;
  PetscScalar *fa;
  PetscFunctionBeginUser;
  count_.rhs++;
  PetscCall(VecGetArray(f, &fa));
  PetscCall(VecGetArrayRead(z, &za));
  PetscCall(PetscArraycpy(fa, za + xm, xm)); // u' = v
  PetscCall(VecRestoreArrayRead(z, &za));
  PetscCall(Accelerate(t, z, fa + xm - xs)); // v' of site i at index i
  PetscCall(VecRestoreArray(f, &fa));
  PetscFunctionReturn(0);
}

PetscErrorCode Rhs::Acceleration(PetscReal t, Vec x, PetscScalar *a)
{
  PetscFunctionBeginUser;
  count_.rhs++;
  PetscCall(Accelerate(t, x, a - lat_.OwnedStart()));
  PetscFunctionReturn(0);
}

PetscErrorCode Rhs::Momentum(PetscReal t, Vec q, Vec pdot)
{
  PetscScalar *pa;
  PetscFunctionBeginUser;
  count_.rhs++;
  PetscCall(VecGetArray(pdot, &pa));
  PetscCall(Accelerate(t, q, pa - lat_.OwnedStart()));
  PetscCall(VecRestoreArray(pdot, &pa));
  PetscFunctionReturn(0);
}

} // namespace nltopo
