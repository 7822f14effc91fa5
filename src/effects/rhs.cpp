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

PetscErrorCode Rhs::Evaluate(PetscReal t, Vec z, Vec f)
{
  const PetscInt xm = lat_.OwnedCount(), xs = lat_.OwnedStart();
  const PetscScalar *za, *u;
  PetscScalar *fa;
  Vec ul;
  PetscFunctionBeginUser;
  count_.rhs++;
  PetscCall(VecGetArray(f, &fa));
  PetscCall(lat_.GetGhostedU(z, &ul, &u));
  PetscCall(PetscLogEventBegin(Log().rhs_linear, 0, 0, 0, 0));
  count_.linear++;
  // Linear coupling, z' = L z = [v, -K u]: a stencil over the bond rule of K
  // (one pass, no matrix traversal: the hot loop of every forced run).
  PetscCall(VecGetArrayRead(z, &za));
  PetscCall(PetscArraycpy(fa, za + xm, xm));
  PetscCall(VecRestoreArrayRead(z, &za));
  PetscScalar *a = fa + xm - xs; // v' of site i at a[i]
  lat_.LinearAcceleration(u, a);
  PetscCall(PetscLogFlops(5.0 * xm));
  PetscCall(PetscLogEventEnd(Log().rhs_linear, 0, 0, 0, 0));
  PetscCall(AddLocalEffects(t, u, a));
  PetscCall(lat_.RestoreGhostedU(z, &ul, &u));
  PetscCall(VecRestoreArray(f, &fa));
  PetscFunctionReturn(0);
}

PetscErrorCode Rhs::Momentum(PetscReal t, Vec q, Vec pdot)
{
  const PetscScalar *u;
  PetscScalar *pa;
  Vec ul;
  PetscFunctionBeginUser;
  count_.rhs++;
  PetscCall(VecGetArray(pdot, &pa));
  PetscCall(lat_.GetGhostedU(q, &ul, &u));
  PetscScalar *a = pa - lat_.OwnedStart();
  PetscCall(PetscLogEventBegin(Log().rhs_linear, 0, 0, 0, 0));
  count_.linear++;
  lat_.LinearAcceleration(u, a);
  PetscCall(PetscLogFlops(5.0 * lat_.OwnedCount()));
  PetscCall(PetscLogEventEnd(Log().rhs_linear, 0, 0, 0, 0));
  PetscCall(AddLocalEffects(t, u, a));
  PetscCall(lat_.RestoreGhostedU(q, &ul, &u));
  PetscCall(VecRestoreArray(pdot, &pa));
  PetscFunctionReturn(0);
}

} // namespace nltopo
