#pragma once
// Dynamic load balance for ensembles of independent runs: a shared counter on
// rank 0 (an MPI-3 window, atomic fetch-and-add) hands out the next item to
// whichever rank asks first, so a rank that drew cheap runs takes more of them.
#include "core/errors.hpp"
#include "core/signals.hpp"
#include <petscsys.h>
#include <algorithm>
#include <vector>

namespace nltopo {

class WorkQueue {
public:
  ~WorkQueue();
  // Collective on comm: items 0..count-1.
  PetscErrorCode Create(MPI_Comm comm, PetscInt count);
  // The next item (*item = -1 once all are handed out, or after a Stop). Not collective.
  PetscErrorCode Next(PetscInt *item);
  // No more items for anyone (a stop signal, a failure): every later Next gives -1. Not collective.
  PetscErrorCode Stop();

private:
  PetscErrorCode FetchAdd(long add, long *got); // atomic add on rank 0's counter, its previous value in *got
  MPI_Win win_ = MPI_WIN_NULL;
  long *counter_ = nullptr;
  PetscInt count_ = 0;
};

// Runs item(i, out) for i = 0..count-1 spread over the ranks of comm by a
// WorkQueue (each item on one rank), and gathers the count x width results
// (out points at width values) on every rank; done[i] = 1 for the items run.
// Items must be independent runs on PETSC_COMM_SELF.
// - An item's error stops every rank after its current item, and all ranks
//   then fail together with that item's message (the lowest failing rank's).
// - A stop signal (core/signals.hpp) stops drawing items; the items done are
//   gathered as usual and, unless every item was done, the silent
//   PETSC_ERR_SIG is returned, so that the caller can write them as partial output.
template <typename Item>
PetscErrorCode RunDistributed(MPI_Comm comm, PetscInt count, PetscInt width, Item item, std::vector<PetscReal> *results, std::vector<PetscInt> *done)
{
  WorkQueue queue;
  std::vector<PetscReal> mine((size_t)count * width, 0.0);
  std::vector<PetscInt> ran(count, 0);
  PetscErrorCode failed = 0;
  char msg[1024] = "";
  PetscInt i;
  PetscFunctionBeginUser;
  PetscCall(queue.Create(comm, count));
  for (;;) {
    if (StopSignalLocal()) { // stop drawing; the other ranks stop after their current item
      PetscCall(queue.Stop());
      break;
    }
    PetscCall(queue.Next(&i));
    if (i < 0) break;
    PetscErrorCode ierr = 0;
    PetscCall(CaptureError([&]() { return item(i, mine.data() + (size_t)i * width); }, &ierr, msg, sizeof(msg)));
    if (ierr) { // a stop signal (the item is dropped) or a failure
      if (!IsInterrupt(ierr)) failed = ierr;
      PetscCall(queue.Stop());
      break;
    }
    ran[i] = 1;
  }
  PetscCall(FailTogether(comm, failed, msg));
  results->assign(mine.size(), 0.0);
  PetscCallMPI(MPI_Allreduce(mine.data(), results->data(), (PetscMPIInt)mine.size(), MPIU_REAL, MPIU_SUM, comm)); // each entry from one rank
  done->assign(count, 0);
  PetscCallMPI(MPI_Allreduce(ran.data(), done->data(), (PetscMPIInt)count, MPIU_INT, MPI_SUM, comm));
  if (std::count(done->begin(), done->end(), 0)) PetscCall(CheckInterrupt(comm)); // a signal after the last item changes nothing
  PetscFunctionReturn(0);
}

} // namespace nltopo
