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

PetscErrorCode BroadcastStrings(MPI_Comm comm, std::vector<std::string> *v)
{
  std::vector<char> buf;
  std::vector<PetscInt> len;
  PetscFunctionBeginUser;
  for (const std::string &s : *v) len.push_back((PetscInt)s.size()), buf.insert(buf.end(), s.begin(), s.end());
  PetscCall(BroadcastFromRoot(comm, MPIU_INT, &len));
  PetscCall(BroadcastFromRoot(comm, MPI_CHAR, &buf));
  v->clear();
  size_t at = 0;
  for (PetscInt n : len) v->emplace_back(buf.data() + at, (size_t)n), at += (size_t)n;
  PetscFunctionReturn(0);
}

} // namespace nltopo
