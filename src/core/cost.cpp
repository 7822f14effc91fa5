#include "core/cost.hpp"
#include "io/output.hpp"
#include <cmath>
#include <cstring>
#include <limits>

namespace nltopo {

namespace {

const char *const kPrefixes[2] = {"sim_", "nnm_"};

struct Entry {
  std::string integrator, accuracy; // of the first solve; "(several)" when later solves differ
  PetscInt solves = 0, steps = 0, rejected = 0, evals = 0;
  PetscReal dt_min = PETSC_MAX_REAL, dt_max = 0;
};

struct Ledger {
  Entry e[2];
  PetscInt pending = 0; // evaluations counted since the last record
  bool reduced = false;
  PetscReal error = std::numeric_limits<PetscReal>::quiet_NaN();
  std::string error_what = "none";
} g;

std::string OptionOr(const char *prefix, const char *name, const char *def)
{
  char v[128];
  PetscBool set = PETSC_FALSE;
  const std::string key = std::string("-") + prefix + name;
  if (PetscOptionsGetString(NULL, NULL, key.c_str(), v, sizeof(v), &set) || !set) return def;
  return v;
}

} // namespace

void CostCountEvaluations(PetscInt n) { g.pending += n; }

PetscErrorCode CostRecordSolve(TS ts, PetscInt evals)
{
  const char *prefix;
  TSType type;
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
  Entry &e = g.e[k];
  PetscCall(TSGetType(ts, &type));
  PetscCall(TSGetStepNumber(ts, &steps));
  PetscCall(TSGetStepRejections(ts, &rejected));
  PetscCall(TSGetAdapt(ts, &adapt));
  PetscCall(TSAdaptGetType(adapt, &atype));
  std::string integrator = type, accuracy;
  if (!std::strcmp(type, "symsplit")) integrator += " " + OptionOr(prefix, "ts_symsplit_scheme", "bm4");
  else if (!std::strcmp(type, "rkn")) integrator += " " + OptionOr(prefix, "ts_rkn_scheme", "dep86");
  else if (!std::strcmp(type, TSRK)) {
    TSRKType rk;
    PetscCall(TSRKGetType(ts, &rk));
    integrator += std::string(" ") + rk;
  }
  const bool fixed = !std::strcmp(type, "symsplit") || !std::strcmp(type, TSBASICSYMPLECTIC) || !std::strcmp(atype, TSADAPTNONE);
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

static PetscErrorCode Reduce(MPI_Comm comm)
{
  PetscInt n[8];
  PetscReal lo[2], hi[2];
  PetscFunctionBeginUser;
  for (int k = 0; k < 2; k++) {
    n[4 * k] = g.e[k].solves, n[4 * k + 1] = g.e[k].steps, n[4 * k + 2] = g.e[k].rejected, n[4 * k + 3] = g.e[k].evals;
    lo[k] = g.e[k].dt_min, hi[k] = g.e[k].dt_max;
  }
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, n, 8, MPIU_INT, MPI_SUM, comm));
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, lo, 2, MPIU_REAL, MPI_MIN, comm));
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, hi, 2, MPIU_REAL, MPI_MAX, comm));
  for (int k = 0; k < 2; k++) {
    g.e[k].solves = n[4 * k], g.e[k].steps = n[4 * k + 1], g.e[k].rejected = n[4 * k + 2], g.e[k].evals = n[4 * k + 3];
    g.e[k].dt_min = lo[k], g.e[k].dt_max = hi[k];
  }
  PetscFunctionReturn(0);
}

PetscErrorCode CostReduceWorld()
{
  PetscFunctionBeginUser;
  PetscCall(Reduce(PETSC_COMM_WORLD));
  g.reduced = true;
  PetscFunctionReturn(0);
}

PetscErrorCode WriteCostCard(PetscViewer v, PetscReal wall_seconds)
{
  PetscFunctionBeginUser;
  Ledger saved = g;
  MPI_Comm comm = PetscObjectComm((PetscObject)v);
  if (!g.reduced) PetscCall(Reduce(comm));
  // rank 0 of a TS's communicator recorded its strings; the attributes are
  // written collectively and must be the same on every rank
  for (int k = 0; k < 2; k++)
    for (std::string *str : {&g.e[k].integrator, &g.e[k].accuracy}) {
      char buf[256] = "";
      PetscCall(PetscStrncpy(buf, str->c_str(), sizeof(buf)));
      PetscCallMPI(MPI_Bcast(buf, sizeof(buf), MPI_CHAR, 0, comm));
      *str = buf;
    }
  const char *grp = "/cost";
  PetscCall(WriteAttr(v, grp, "wall_seconds", wall_seconds));
  for (int k = 0; k < 2; k++) {
    const Entry &e = g.e[k];
    if (!e.solves) continue;
    const std::string p = std::string(kPrefixes[k]); // sim_..., nnm_...
    // the first solve's integrator (rank 0 of the output's communicator)
    PetscCall(WriteAttr(v, grp, (p + "integrator").c_str(), e.integrator.c_str()));
    PetscCall(WriteAttr(v, grp, (p + "accuracy").c_str(), e.accuracy.c_str()));
    PetscCall(WriteAttr(v, grp, (p + "solves").c_str(), e.solves));
    PetscCall(WriteAttr(v, grp, (p + "steps").c_str(), e.steps));
    PetscCall(WriteAttr(v, grp, (p + "rejected_steps").c_str(), e.rejected));
    PetscCall(WriteAttr(v, grp, (p + "force_evaluations").c_str(), e.evals));
    if (e.dt_max > 0) {
      PetscCall(WriteAttr(v, grp, (p + "dt_min").c_str(), e.dt_min));
      PetscCall(WriteAttr(v, grp, (p + "dt_max").c_str(), e.dt_max));
    }
  }
  PetscCall(WriteAttr(v, grp, "error_estimate", g.error));
  PetscCall(WriteAttr(v, grp, "error_estimate_of", g.error_what.c_str()));
  g = saved; // a checkpoint's card does not consume the ledger
  PetscFunctionReturn(0);
}

} // namespace nltopo
