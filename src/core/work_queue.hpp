#pragma once
// Dynamic load balance for ensembles of independent runs: a shared counter on
// rank 0 (an MPI-3 window, atomic fetch-and-add) hands out the next item to
// whichever rank asks first, so a rank that drew cheap runs takes more of them.
#include <petscsys.h>
#include <vector>

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

namespace nltopo {

// Runs item(i, out) for i = 0..count-1 spread over the ranks of comm by a
// WorkQueue (each item on one rank), and gathers the count x width results
// (out points at width values) on every rank. Items must be independent runs
// on PETSC_COMM_SELF. An item's error aborts every rank (one line first).
template <typename Item>
PetscErrorCode RunDistributed(MPI_Comm comm, PetscInt count, PetscInt width, Item item, std::vector<PetscReal> *results)
{
  WorkQueue queue;
  std::vector<PetscReal> mine((size_t)count * width, 0.0);
  PetscInt i;
  PetscFunctionBeginUser;
  PetscCall(queue.Create(comm, count));
  for (;;) {
    PetscCallAbort(comm, queue.Next(&i));
    if (i < 0) break;
    PetscCallAbort(comm, item(i, mine.data() + (size_t)i * width));
  }
  results->assign(mine.size(), 0.0);
  PetscCallMPI(MPI_Allreduce(mine.data(), results->data(), (PetscMPIInt)mine.size(), MPIU_REAL, MPIU_SUM, comm)); // each entry from one rank
  PetscFunctionReturn(0);
}

} // namespace nltopo
