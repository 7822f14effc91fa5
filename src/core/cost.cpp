#include "core/cost.hpp"
#include "core/ts_traits.hpp"
#include <algorithm>
#include <cstring>
#include <limits>

namespace nltopo {

namespace {

const char *const kPrefixes[2] = {"sim_", "nnm_"};

struct Ledger {
  CostEntry e[2] = {};
  PetscInt pending = 0; // evaluations counted since the last record
  bool reduced = false;
  PetscReal error = std::numeric_limits<PetscReal>::quiet_NaN();
  std::string error_what = "none";
} g;

} // namespace

void CostCountEvaluations(PetscInt n) { g.pending += n; }

PetscErrorCode CostRecordSolve(TS ts, PetscInt evals)
{
  const char *prefix;
  const TSTraits *tr;
  TSAdapt adapt;
  TSAdaptType atype;
  PetscInt steps, rejected;
  PetscReal rtol, atol;
  PetscMPIInt rank;
  PetscFunctionBeginUser;
  const PetscInt counted = g.pending;
  g.pending = 0;
  PetscCallMPI(MPI_Comm_rank(PetscObjectComm((PetscObject)ts), &rank));
  if (rank) PetscFunctionReturn(0);
  PetscCall(TSGetOptionsPrefix(ts, &prefix));
  int k = -1;
  for (int i = 0; i < 2; i++)
    if (prefix && !std::strcmp(prefix, kPrefixes[i])) k = i;
  if (k < 0) PetscFunctionReturn(0); // a TS of another prefix (none in nltopo)
  CostEntry &e = g.e[k];
  PetscCall(TSGetTraits(ts, &tr));
  PetscCall(TSGetStepNumber(ts, &steps));
  PetscCall(TSGetStepRejections(ts, &rejected));
  PetscCall(TSGetAdapt(ts, &adapt));
  PetscCall(TSAdaptGetType(adapt, &atype));
  std::string integrator, accuracy;
  PetscCall(TSGetIntegratorName(ts, &integrator));
  const bool fixed = tr->fixed_step || !std::strcmp(atype, TSADAPTNONE);
  if (fixed) accuracy = "fixed step";
  else {
    char buf[96];
    PetscCall(TSGetTolerances(ts, &atol, NULL, &rtol, NULL));
    PetscCall(PetscSNPrintf(buf, sizeof(buf), "rtol %g, atol %g", (double)rtol, (double)atol));
    accuracy = buf;
  }
  if (!e.solves) e.integrator = integrator, e.accuracy = accuracy;
  else if (e.integrator != integrator || e.accuracy != accuracy) e.integrator = "(several)", e.accuracy = "(several)";
  if (fixed && steps > 0) {
    PetscReal dt;
    PetscCall(TSGetTimeStep(ts, &dt));
    e.dt_min = std::min(e.dt_min, dt), e.dt_max = std::max(e.dt_max, dt);
  }
  e.solves++;
  e.steps += steps;
  e.rejected += rejected;
  e.evals += evals >= 0 ? evals : counted;
  PetscFunctionReturn(0);
}

void CostTotals(PetscInt *steps, PetscInt *evals)
{
  *steps = g.e[0].steps + g.e[1].steps;
  *evals = g.e[0].evals + g.e[1].evals;
}

void CostSetErrorEstimate(PetscReal value, const char *what)
{
  g.error = value;
  g.error_what = what;
}

static PetscErrorCode Reduce(MPI_Comm comm, CostEntry *e)
{
  PetscInt n[8];
  PetscReal lo[2], hi[2];
  PetscFunctionBeginUser;
  for (int k = 0; k < 2; k++) {
    n[4 * k] = e[k].solves, n[4 * k + 1] = e[k].steps, n[4 * k + 2] = e[k].rejected, n[4 * k + 3] = e[k].evals;
    lo[k] = e[k].dt_min, hi[k] = e[k].dt_max;
  }
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, n, 8, MPIU_INT, MPI_SUM, comm));
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, lo, 2, MPIU_REAL, MPI_MIN, comm));
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, hi, 2, MPIU_REAL, MPI_MAX, comm));
  for (int k = 0; k < 2; k++) {
    e[k].solves = n[4 * k], e[k].steps = n[4 * k + 1], e[k].rejected = n[4 * k + 2], e[k].evals = n[4 * k + 3];
    e[k].dt_min = lo[k], e[k].dt_max = hi[k];
  }
  PetscFunctionReturn(0);
}

PetscErrorCode CostReduceWorld()
{
  PetscFunctionBeginUser;
  PetscCall(Reduce(PETSC_COMM_WORLD, g.e));
  g.reduced = true;
  PetscFunctionReturn(0);
}

PetscErrorCode CostCardOn(MPI_Comm comm, CostCard *card)
{
  CostEntry e[2] = {g.e[0], g.e[1]};
  PetscFunctionBeginUser;
  if (!g.reduced) PetscCall(Reduce(comm, e));
  // rank 0 of a TS's communicator recorded its strings; the attributes are
  // written collectively and must be the same on every rank
  for (int k = 0; k < 2; k++)
    for (std::string *str : {&e[k].integrator, &e[k].accuracy}) {
      char buf[256] = "";
      PetscCall(PetscStrncpy(buf, str->c_str(), sizeof(buf)));
      PetscCallMPI(MPI_Bcast(buf, sizeof(buf), MPI_CHAR, 0, comm));
      *str = buf;
    }
  card->entries.clear();
  for (int k = 0; k < 2; k++) {
    e[k].prefix = kPrefixes[k];
    card->entries.push_back(e[k]);
  }
  card->error = g.error;
  card->error_what = g.error_what;
  PetscFunctionReturn(0);
}

void CostReset() { g = Ledger(); }

} // namespace nltopo
