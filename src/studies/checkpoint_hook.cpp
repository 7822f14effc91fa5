#include "studies/checkpoint_hook.hpp"

namespace nltopo {

CheckpointHook::CheckpointHook(MPI_Comm comm, PointHook *inner, PetscReal every, std::function<PetscErrorCode()> write)
    : comm_(comm), inner_(inner), every_(every), write_(std::move(write))
{
  PetscTime(&last_);
}

PetscErrorCode CheckpointHook::Point(Vec z0, PetscReal T, PetscReal beta, Vec dz0)
{
  PetscFunctionBeginUser;
  if (inner_) PetscCall(inner_->Point(z0, T, beta, dz0));
  if (every_ <= 0) PetscFunctionReturn(0);
  PetscLogDouble now;
  PetscCall(PetscTime(&now));
  int due = now - last_ >= every_;
  PetscCallMPI(MPI_Bcast(&due, 1, MPI_INT, 0, comm_)); // rank 0's clock decides for all
  if (!due) PetscFunctionReturn(0);
  PetscCall(write_());
  PetscCall(PetscTime(&last_));
  PetscFunctionReturn(0);
}

} // namespace nltopo
