#pragma once
// -cont_checkpoint_seconds: a PointHook (orbits/continuation.hpp) that
// forwards every orbit to an inner hook (the Floquet columns, if any), then,
// at most every so many seconds, calls a writer with what is done so far, so
// that a long run that is killed keeps its points. Rank 0's clock decides for
// all ranks.
#include "orbits/continuation.hpp"
#include <functional>
#include <petsctime.h>

namespace nltopo {

class CheckpointHook : public PointHook {
public:
  // every <= 0: never writes (only forwards).
  CheckpointHook(MPI_Comm comm, PointHook *inner, PetscReal every, std::function<PetscErrorCode()> write);
  PetscErrorCode Point(Vec z0, PetscReal T, PetscReal beta, Vec dz0) override;

private:
  MPI_Comm comm_;
  PointHook *inner_;
  PetscReal every_;
  std::function<PetscErrorCode()> write_;
  PetscLogDouble last_ = 0;
};

} // namespace nltopo
