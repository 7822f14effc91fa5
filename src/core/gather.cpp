#include "core/gather.hpp"

namespace nltopo {

PetscErrorCode GatherVec(Vec v, bool to_all, std::vector<PetscReal> *out)
{
  VecScatter sc;
  Vec s;
  const PetscScalar *a;
  PetscInt n;
  PetscFunctionBeginUser;
  if (to_all) PetscCall(VecScatterCreateToAll(v, &sc, &s));
  else PetscCall(VecScatterCreateToZero(v, &sc, &s));
  PetscCall(VecScatterBegin(sc, v, s, INSERT_VALUES, SCATTER_FORWARD));
  PetscCall(VecScatterEnd(sc, v, s, INSERT_VALUES, SCATTER_FORWARD));
  PetscCall(VecGetLocalSize(s, &n));
  PetscCall(VecGetArrayRead(s, &a));
  out->assign(a, a + n);
  PetscCall(VecRestoreArrayRead(s, &a));
  PetscCall(VecScatterDestroy(&sc));
  PetscCall(VecDestroy(&s));
  PetscFunctionReturn(0);
}

} // namespace nltopo
