// nltopo: strongly nonlinear topological lattices on PETSc/SLEPc.
// Thin driver: initialise, run the -study from the registry, finalise.
#include "core/errors.hpp"
#include "studies/registry.hpp"
#include <slepcsys.h>
#include <hdf5.h>
#include <csignal>

static const char help[] = "nltopo: nonlinear SSH interface lattice (see README.md). Use -study <name> with -options_file options/<scene>.opts.\n";

int main(int argc, char **argv)
{
  if (!nltopo::PreflightArguments(argc, argv)) return 1;
  std::signal(SIGXFSZ, SIG_IGN); // a file-size limit (ulimit -f) is a failed write with one line, not a kill
  if (SlepcInitialize(&argc, &argv, NULL, help)) return 1;
  PetscPushErrorHandler(nltopo::OneLineErrorHandler, NULL);
  H5Eset_auto2(H5E_DEFAULT, NULL, NULL); // HDF5's stack dumps off: every failure gets nltopo's one line
  PetscErrorCode ierr = nltopo::RunStudyFromOptions(PETSC_COMM_WORLD);
  PetscPopErrorHandler();
  PetscErrorCode fin = SlepcFinalize();
  return (ierr || fin) ? 1 : 0;
}
