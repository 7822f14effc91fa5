#include "effects/rhs.hpp"
#include <cstring>

namespace nltopo {

Rhs::Rhs(const EffectList &fx) : fx_(fx), calls_(fx.AllOn()), needs_v_(fx.VelocityDependent())
{
  for (size_t k = 0; k < fx.Size(); k++)
    if (!std::strcmp(fx.At(k).Name(), "forcing")) forcing_ = (PetscInt)k;
}

EffectCounters Rhs::Counters() const
{
  EffectCounters c;
  c.rhs = rhs_;
  for (size_t k = 0; k < fx_.Size(); k++) {
    const char *n = fx_.At(k).Name();
    PetscInt *slot = !std::strcmp(n, "linear")    ? &c.linear
                     : !std::strcmp(n, "cubic")   ? &c.cubic
                     : !std::strcmp(n, "forcing") ? &c.forcing
                     : !std::strcmp(n, "damping") ? &c.damping
                                                  : nullptr;
    if (slot) *slot = calls_.count[k];
  }
  return c;
}

PetscErrorCode Rhs::Accelerate(PetscReal t, Vec x, PetscScalar *a)
{
  const Lattice &lat = fx_.Lat();
  const PetscScalar *u, *xa = NULL, *v = NULL;
  Vec ul;
  PetscFunctionBeginUser;
  PetscCall(lat.GetGhostedU(x, &ul, &u));
  if (needs_v_) { // the v half of the state x, by global site
    PetscInt n;
    PetscCall(VecGetLocalSize(x, &n));
    PetscCheck(n == 2 * lat.OwnedCount(), lat.Comm(), PETSC_ERR_ARG_WRONG, "a velocity-dependent effect needs the whole state [u, v]");
    PetscCall(VecGetArrayRead(x, &xa));
    v = xa + lat.OwnedCount() - lat.OwnedStart();
  }
  PetscCall(fx_.Acceleration(t, u, v, a, &calls_));
  if (xa) PetscCall(VecRestoreArrayRead(x, &xa));
  PetscCall(lat.RestoreGhostedU(x, &ul, &u));
  PetscFunctionReturn(0);
}

PetscErrorCode Rhs::Evaluate(PetscReal t, Vec z, Vec f)
{
  const PetscInt xm = fx_.Lat().OwnedCount(), xs = fx_.Lat().OwnedStart();
  const PetscScalar *za;
  PetscScalar *fa;
  PetscFunctionBeginUser;
  rhs_++;
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
  rhs_++;
  PetscCall(Accelerate(t, x, a - fx_.Lat().OwnedStart()));
  PetscFunctionReturn(0);
}

PetscErrorCode Rhs::Momentum(PetscReal t, Vec q, Vec pdot)
{
  PetscScalar *pa;
  PetscFunctionBeginUser;
  rhs_++;
  PetscCall(VecGetArray(pdot, &pa));
  PetscCall(Accelerate(t, q, pa - fx_.Lat().OwnedStart()));
  PetscCall(VecRestoreArray(pdot, &pa));
  PetscFunctionReturn(0);
}

} // namespace nltopo
