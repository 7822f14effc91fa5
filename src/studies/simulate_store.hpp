#pragma once
// The -sim_store_u* block of -study simulate (studies/simulate_study.cpp):
// what of the run /simulate keeps. -study workprecision reads it too and
// ignores it, so that a simulate options file can be its base scene.
#include <petscsys.h>

namespace nltopo {

struct SimulateStoreOptions {
  PetscBool store_u = PETSC_TRUE; // /simulate/u
  PetscInt stride = 1;            // every this many sites
};
PetscErrorCode SimulateStoreOptionsFromOptions(MPI_Comm comm, SimulateStoreOptions *o);

} // namespace nltopo
