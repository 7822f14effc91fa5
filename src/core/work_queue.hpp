#pragma once
// Dynamic load balance for ensembles of independent runs: a shared counter on
// rank 0 (an MPI-3 window, atomic fetch-and-add) hands out the next item to
// whichever rank asks first, so a rank that drew cheap runs takes more of them.
#include <petscsys.h>

namespace nltopo {

class WorkQueue {
public:
  ~WorkQueue();
  // Collective on comm: items 0..count-1.
  PetscErrorCode Create(MPI_Comm comm, PetscInt count);
  // The next item (*item = -1 once all are handed out). Not collective.
  PetscErrorCode Next(PetscInt *item);

private:
  MPI_Win win_ = MPI_WIN_NULL;
  long *counter_ = nullptr;
  PetscInt count_ = 0;
};

} // namespace nltopo
