#include "core/gather.hpp"
#include "core/handle.hpp"

namespace nltopo {

PetscErrorCode GatherVec(Vec v, bool to_all, std::vector<PetscReal> *out)
{
  OwnedVecScatter sc;
  OwnedVec s;
  const PetscScalar *a;
  PetscInt n;
  PetscFunctionBeginUser;
  if (to_all) PetscCall(VecScatterCreateToAll(v, sc.out(), s.out()));
  else PetscCall(VecScatterCreateToZero(v, sc.out(), s.out()));
  PetscCall(VecScatterBegin(sc, v, s, INSERT_VALUES, SCATTER_FORWARD));
  PetscCall(VecScatterEnd(sc, v, s, INSERT_VALUES, SCATTER_FORWARD));
  PetscCall(VecGetLocalSize(s, &n));
  PetscCall(VecGetArrayRead(s, &a));
  out->assign(a, a + n);
  PetscCall(VecRestoreArrayRead(s, &a));
  PetscFunctionReturn(0);
}

} // namespace nltopo
