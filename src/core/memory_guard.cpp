#include "core/memory_guard.hpp"
#include <unistd.h>

namespace nltopo {

double PhysicalMemoryBytes()
{
  const long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGE_SIZE);
  return pages > 0 && page > 0 ? (double)pages * (double)page : 0.0;
}

PetscErrorCode CheckMemory(MPI_Comm comm, double bytes_this_rank, const char *what)
{
  double worst, total;
  PetscMPIInt size;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_size(PETSC_COMM_WORLD, &size));
  PetscCallMPI(MPIU_Allreduce(&bytes_this_rank, &worst, 1, MPI_DOUBLE, MPI_MAX, comm));
  total = worst * size; // every rank of the run on this one machine (the worst case)
  const double mem = PhysicalMemoryBytes();
  PetscCheck(mem <= 0 || total <= 0.9 * mem, comm, PETSC_ERR_USER, "%s needs about %.3g GB (%d rank(s) x %.3g GB), more than this machine's %.3g GB of memory",
             what, total / 1e9, (int)size, worst / 1e9, mem / 1e9);
  PetscFunctionReturn(0);
}

} // namespace nltopo
