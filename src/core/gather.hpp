#pragma once
// A distributed vector copied to std::vector: on every rank, or on rank 0 only
// (other ranks get an empty vector). For small vectors (N ~ 10^2..10^4).
#include <petscvec.h>
#include <petscsys.h>
#include <string>
#include <vector>

namespace nltopo {

PetscErrorCode GatherVec(Vec v, bool to_all, std::vector<PetscReal> *out);

// Rank 0's vector (its size included) to every rank.
template <typename T> PetscErrorCode BroadcastFromRoot(MPI_Comm comm, MPI_Datatype type, std::vector<T> *v)
{
  PetscFunctionBeginUser;
  PetscInt n = (PetscInt)v->size();
  PetscCallMPI(MPI_Bcast(&n, 1, MPIU_INT, 0, comm));
  v->resize(n);
  if (n) PetscCallMPI(MPI_Bcast(v->data(), (PetscMPIInt)n, type, 0, comm));
  PetscFunctionReturn(0);
}

// Rank 0's strings to every rank.
PetscErrorCode BroadcastStrings(MPI_Comm comm, std::vector<std::string> *v);

} // namespace nltopo
