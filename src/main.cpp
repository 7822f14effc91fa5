// nltopo: strongly nonlinear topological lattices on PETSc/SLEPc.
// Thin driver: initialise, run the -study from the registry, finalise.
#include "core/errors.hpp"
#include "core/option_help.hpp"
#include "core/options_input.hpp"
#include "core/signals.hpp"
#include "studies/registry.hpp"
#include <slepcsys.h>
#include <hdf5.h>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <strings.h>

static const char help[] = "nltopo: nonlinear SSH interface lattice (see README.md). Use -study <name> with -options_file options/<scene>.opts.\n";

static int Run(int argc, char **argv);

// MPI starts first, and every rank leaves through MPI_Finalize, whose fence
// keeps each rank alive until all have reported: mpiexec kills the others as
// soon as one rank exits non-zero, so a rank that exits early could cut off
// rank 0's one line (a refusal before PETSc starts) or its clean-up.
int main(int argc, char **argv)
{
  if (MPI_Init(&argc, &argv) != MPI_SUCCESS) return 1;
  const int rc = Run(argc, argv);
  MPI_Finalize();
  return rc;
}

static int Run(int argc, char **argv)
{
  std::setvbuf(stdout, NULL, _IOLBF, 0); // progress lines reach a pipe or a file as they are printed
  if (argc == 1) {                       // no argument: usage, nothing written
    int rank;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    if (!rank) std::fputs(nltopo::UsageText().c_str(), stdout);
    return 0;
  }
  for (int i = 1; i < argc; i++)
    if (!std::strcmp(argv[i], "-version") || !std::strcmp(argv[i], "--version")) { // before PETSc, which would print its own banner
      int rank;
      MPI_Comm_rank(MPI_COMM_WORLD, &rank);
      if (!rank) std::fputs(nltopo::VersionText().c_str(), stdout);
      return 0;
    }
  // -help (or -h) is nltopo's listing unless followed by "petsc": taken out
  // before PETSc starts, which would print its generic block first
  for (int i = 1; i < argc; i++)
    if (!strcasecmp(argv[i], "-help") || !strcasecmp(argv[i], "-h")) {
      const bool petsc = i + 1 < argc && !strcasecmp(argv[i + 1], "petsc"); // PETSc's own listing: drop the word, keep -help
      if (!petsc) nltopo::SetOwnHelp(true);
      const int drop = petsc ? i + 1 : i;
      for (int j = drop; j + 1 < argc; j++) argv[j] = argv[j + 1];
      argv[--argc] = nullptr;
      if (petsc) break;
      i--;
    }
  if (!nltopo::PreflightArguments(argc, argv)) return 1;
  std::signal(SIGXFSZ, SIG_IGN); // a file-size limit (ulimit -f) is a failed write with one line, not a kill
  const PetscErrorCode started = SlepcInitialize(&argc, &argv, NULL, help);
  nltopo::RemoveSpooledOptionsFiles(); // PETSc has read its copies of the pipes (core/options_input.hpp)
  if (started) return 1;
  PetscPushErrorHandler(nltopo::OneLineErrorHandler, NULL);
  H5Eset_auto2(H5E_DEFAULT, NULL, NULL); // HDF5's stack dumps off: every failure gets nltopo's one line
  nltopo::InstallStopSignalHandlers();   // SIGINT, SIGTERM, SIGHUP: stop at the next safe point; SIGPIPE ignored
  PetscErrorCode ierr = nltopo::RunStudyFromOptions(PETSC_COMM_WORLD);
  int sig = nltopo::StopSignalSeen();
  if (nltopo::IsInterrupt(ierr) && !nltopo::InterruptReported())
    PetscFPrintf(PETSC_COMM_WORLD, PETSC_STDERR, "nltopo: interrupted by %s; no output written\n", nltopo::SignalName(sig ? sig : 15));
  if (!ierr) { // a signal after the last safe point: the output is complete, the exit status still says "stopped by a signal"
    if (nltopo::InterruptRequested(PETSC_COMM_WORLD, &sig)) sig = 0;
    if (sig)
      PetscFPrintf(PETSC_COMM_WORLD, PETSC_STDERR, "nltopo: %s arrived after the last safe point; the run finished and its output is complete\n",
                   nltopo::SignalName(sig));
  }
  PetscPopErrorHandler();
  PetscErrorCode fin = SlepcFinalize();
  nltopo::IgnoreBrokenPipe();                                                     // (PetscFinalize reset it to the default: MPI_Finalize may still write)
  if (nltopo::IsInterrupt(ierr) || (!ierr && sig)) return 128 + (sig ? sig : 15); // the shell's convention for "stopped by signal n"
  return (ierr || fin) ? 1 : 0;
}
