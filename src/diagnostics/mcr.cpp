#include "diagnostics/mcr.hpp"

namespace nltopo {

PetscErrorCode Mcr(Vec u, PetscReal *mcr)
{
  const PetscScalar *a;
  PetscInt n;
  PetscReal loc[2] = {0, 0}, g[2];
  PetscFunctionBeginUser;
  PetscCall(VecGetLocalSize(u, &n));
  PetscCall(VecGetArrayRead(u, &a));
  for (PetscInt i = 0; i < n; i++) {
    const PetscReal s = a[i] * a[i];
    loc[0] += s * s;
    loc[1] += s;
  }
  PetscCall(VecRestoreArrayRead(u, &a));
  PetscCall(MPIU_Allreduce(loc, g, 2, MPIU_REAL, MPIU_SUM, PetscObjectComm((PetscObject)u)));
  *mcr = g[1] > 0 ? g[0] / (g[1] * g[1]) : 0;
  PetscFunctionReturn(0);
}

} // namespace nltopo
