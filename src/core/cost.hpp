#pragma once
// The cost ledger behind the card every output carries (/cost, written by
// io/cost_card.hpp at OutputFile::Commit): for each time integrator the run
// used (TS prefixes -sim_ and -nnm_), its type and scheme and its accuracy,
// and the work: solves, steps, rejected steps and force (right-hand side)
// evaluations; the wall time; and an error estimate where the study has one.
// Every TSSolve of nltopo goes through Simulate or SolvePeriod, which record it
// here; one helper, whatever the study.
#include <petscts.h>
#include <string>
#include <vector>

namespace nltopo {

// Force evaluations of the solve in progress (the period flows' kernels count
// theirs here; Simulate passes its own count to CostRecordSolve).
void CostCountEvaluations(PetscInt n);
// After a TSSolve: type and scheme (the integrator table, core/ts_traits.hpp),
// accuracy, steps, rejections and evaluations (evals < 0: the ones counted
// since the last record). Counted once per TS communicator (its rank 0), so
// that a sum over all ranks is the work done.
PetscErrorCode CostRecordSolve(TS ts, PetscInt evals);
// Steps and force evaluations recorded on this rank so far (the work of a
// stretch of a study: the difference of two calls; rank 0 of each TS counts).
void CostTotals(PetscInt *steps, PetscInt *evals);
// The study's own accuracy statement, written with the card (NaN: none).
void CostSetErrorEstimate(PetscReal value, const char *what);
// Sums every rank's ledger onto rank 0 of PETSC_COMM_WORLD (collective); for a
// study whose output is written by rank 0 alone (the sweep).
PetscErrorCode CostReduceWorld();

// One TS prefix's line of the card.
struct CostEntry {
  std::string prefix;               // "sim_", "nnm_"
  std::string integrator, accuracy; // of the first solve; "(several)" when later solves differ
  PetscInt solves = 0, steps = 0, rejected = 0, evals = 0;
  PetscReal dt_min = PETSC_MAX_REAL, dt_max = 0; // fixed-step solves' steps (dt_max 0: none)
};
struct CostCard {
  std::vector<CostEntry> entries; // every prefix, in the card's order (solves 0: unused)
  PetscReal error;
  std::string error_what;
};
// The card as it is written on comm: the ledger summed over comm unless
// CostReduceWorld has done it, rank 0's strings on every rank (collective).
// The ledger itself is left as it was (a checkpoint's card does not consume it).
PetscErrorCode CostCardOn(MPI_Comm comm, CostCard *card);
// Empties the ledger (a test that records solves of its own).
void CostReset();

} // namespace nltopo
