#pragma once
// Resource guard: before a large allocation, compare an estimate of the bytes
// this rank will hold with the machine's physical memory and refuse with one
// line giving the estimate, instead of swapping or being killed mid-run.
#include <petscsys.h>

namespace nltopo {

// Physical memory of this node in bytes (sysconf).
double PhysicalMemoryBytes();

// Fails (collectively on comm) when the largest per-rank estimate, times the
// ranks sharing this node, exceeds the physical memory. what names the data
// and the options that size it, e.g. "/simulate/u (-lattice_cells, -sim_t_final / -sim_sample_dt)".
PetscErrorCode CheckMemory(MPI_Comm comm, double bytes_this_rank, const char *what);

} // namespace nltopo
