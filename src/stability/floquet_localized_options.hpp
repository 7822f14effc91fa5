#pragma once
// The options of the localized Floquet route (stability/floquet_localized.hpp),
// a member of FloquetMfOptions (-floquet_mf_which localized).
#include <petscsys.h>

namespace nltopo {

struct LocalizedOptions {
  PetscInt window = 40;           // undamped cells on each side of the interface cell (-floquet_loc_window)
  PetscInt ramp = 40;             // cells of the ramp from 0 to the full damping (-floquet_loc_ramp)
  PetscInt pad = 0;               // cells at the full damping beyond the ramp; -1: to the lattice's ends (-floquet_loc_pad)
  PetscReal damping = 1;          // c, per unit time (-floquet_loc_damping)
  PetscBool resolve = PETSC_TRUE; // -floquet_loc_resolve: solve again with the window halved, delta raised to the change of the leading |mu|
  PetscBool check = PETSC_FALSE;  // -floquet_loc_check: W and c halved and doubled at every orbit, delta raised to the change
  // the exterior route (stability/floquet_exterior.hpp): the finite lattice's own multipliers where the orbit is localized
  PetscBool exterior = PETSC_FALSE; // -floquet_loc_exterior
  PetscInt exterior_cells = 60;     // -floquet_loc_exterior_cells: cells each side of the interface cell in the region where M - M_lin is integrated
  PetscReal exterior_tol = 1e-12;   // -floquet_loc_exterior_tol: entries of M - M_lin below this times max |M| are outside the window
  PetscReal exterior_arc = 0;       // -floquet_loc_exterior_arc: radius around each scan point within which the poles are kept exactly (0: 10 pi / N, at most 0.1)
};
PetscErrorCode LocalizedOptionsFromOptions(MPI_Comm comm, LocalizedOptions *o);

} // namespace nltopo
