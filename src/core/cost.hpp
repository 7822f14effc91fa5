#pragma once
// The cost card every output carries (/cost, written by OutputFile::Commit):
// for each time integrator the run used (TS prefixes -sim_ and -nnm_), its
// type and accuracy, and the work: solves, steps, rejected steps and force
// (right-hand side) evaluations; the wall time; and an error estimate where the
// study has one. Every TSSolve of nltopo goes through Simulate or SolvePeriod,
// which record it here; one helper, whatever the study.
#include <petscts.h>
#include <string>

namespace nltopo {

// Force evaluations of the solve in progress (the period flows' kernels count
// theirs here; Simulate passes its own count to CostRecordSolve).
void CostCountEvaluations(PetscInt n);
// After a TSSolve: type, accuracy, steps, rejections and evaluations (evals < 0:
// the ones counted since the last record). Counted once per TS communicator
// (its rank 0), so that a sum over all ranks is the work done.
PetscErrorCode CostRecordSolve(TS ts, PetscInt evals);
// Steps and force evaluations recorded on this rank so far (the work of a
// stretch of a study: the difference of two calls; rank 0 of each TS counts).
void CostTotals(PetscInt *steps, PetscInt *evals);
// The study's own accuracy statement, written with the card (NaN: none).
void CostSetErrorEstimate(PetscReal value, const char *what);
// Sums every rank's ledger onto rank 0 of PETSC_COMM_WORLD (collective); for a
// study whose output is written by rank 0 alone (the sweep).
PetscErrorCode CostReduceWorld();
// Writes /cost (attributes) on the viewer; sums over comm first unless
// CostReduceWorld has done it (collective on the viewer's communicator).
PetscErrorCode WriteCostCard(PetscViewer v, PetscReal wall_seconds);

} // namespace nltopo
