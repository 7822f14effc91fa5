// Catch2 main under MPI with SLEPc initialised (guide section h): Catch's own
// arguments come before "--", PETSc's after it. Every rank runs every test in
// the same order; only rank 0 reports; the exit code is the max over ranks.
#define CATCH_CONFIG_RUNNER
#include "core/log.hpp"
#include "studies/registry.hpp"
#include "timeint/ts_rkn.hpp"
#include "timeint/ts_symsplit.hpp"
#include <catch2/catch.hpp>
#include <cstring>
#include <slepcsys.h>

int main(int argc, char **argv)
{
  int split = argc;
  for (int i = 1; i < argc; i++)
    if (!std::strcmp(argv[i], "--")) {
      split = i;
      break;
    }
  int pc = split < argc ? argc - split : 1;
  char **pv = split < argc ? argv + split : argv;
  if (SlepcInitialize(&pc, &pv, NULL, NULL)) return 1;
  if (nltopo::LogRegister() || nltopo::TSSymSplitRegister() || nltopo::TSRknRegister()) return 1;
  nltopo::RegisterStudyContracts(); // the output schemas and compared option prefixes, as nltopo registers them
  PetscMPIInt rank;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  Catch::Session session;
  if (int rc = session.applyCommandLine(split, argv)) {
    SlepcFinalize();
    return rc;
  }
  if (rank) session.configData().outputFilename = "/dev/null"; // rank 0 reports
  int fails = session.run(), any = 0;
  MPI_Allreduce(&fails, &any, 1, MPI_INT, MPI_MAX, PETSC_COMM_WORLD);
  SlepcFinalize();
  return any ? 1 : 0;
}
