#include "core/work_queue.hpp"

namespace nltopo {

WorkQueue::~WorkQueue()
{
  if (win_ != MPI_WIN_NULL) MPI_Win_free(&win_);
}

PetscErrorCode WorkQueue::Create(MPI_Comm comm, PetscInt count)
{
  PetscMPIInt rank;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  count_ = count;
  PetscCallMPI(MPI_Win_allocate(rank ? 0 : sizeof(long), sizeof(long), MPI_INFO_NULL, comm, &counter_, &win_));
  if (!rank) *counter_ = 0;
  PetscCallMPI(MPI_Barrier(comm)); // the counter is zero before anyone draws
  PetscFunctionReturn(0);
}

PetscErrorCode WorkQueue::FetchAdd(long add, long *got)
{
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Win_lock(MPI_LOCK_SHARED, 0, 0, win_));
  PetscCallMPI(MPI_Fetch_and_op(&add, got, MPI_LONG, 0, 0, MPI_SUM, win_));
  PetscCallMPI(MPI_Win_unlock(0, win_));
  PetscFunctionReturn(0);
}

PetscErrorCode WorkQueue::Next(PetscInt *item)
{
  long got = 0;
  PetscFunctionBeginUser;
  PetscCall(FetchAdd(1, &got));
  *item = got < count_ ? (PetscInt)got : -1;
  PetscFunctionReturn(0);
}

PetscErrorCode WorkQueue::Stop()
{
  long got = 0;
  PetscFunctionBeginUser;
  PetscCall(FetchAdd(1L << 40, &got)); // far past any count: every later fetch-and-add gives -1
  PetscFunctionReturn(0);
}

} // namespace nltopo
