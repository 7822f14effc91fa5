// The integrator table (core/ts_traits.hpp) against what each type does: for
// every row, a TS of that type solves one step of the harmonic oscillator
// u'' = -u; the cost card records "<type> <scheme>" with the scheme the type's
// own public getter reports (TSRKGetType, TSRknGetScheme, ...), defaults and
// schemes chosen through options alike; an explicit type needs no Jacobian; a
// type that rolls back returns to the step start; a type on the acceleration
// kernel calls it; a fixed-step type's card says so. A type missing from the
// table is refused in one line naming the option. One rank (PETSC_COMM_SELF).
#include "helpers.hpp"
#include "core/cost.hpp"
#include "core/ts_traits.hpp"
#include "timeint/ts_rkn.hpp"
#include "timeint/ts_symsplit.hpp"
#include <cmath>
#include <cstring>
#include <map>
#include <string>

using namespace nltopo;
using namespace nltopo::test;

namespace {

// u'' = -u as z = [u, v]
PetscErrorCode Rhs(TS, PetscReal, Vec z, Vec f, void *)
{
  const PetscScalar *x;
  PetscScalar *y;
  PetscFunctionBeginUser;
  PetscCall(VecGetArrayRead(z, &x));
  PetscCall(VecGetArray(f, &y));
  y[0] = x[1];
  y[1] = -x[0];
  PetscCall(VecRestoreArray(f, &y));
  PetscCall(VecRestoreArrayRead(z, &x));
  PetscFunctionReturn(0);
}

PetscErrorCode Jacobian(TS, PetscReal, Vec, Mat A, Mat, void *)
{
  PetscFunctionBeginUser;
  PetscCall(MatSetValue(A, 0, 0, 0.0, INSERT_VALUES)); // the diagonal too: implicit types shift it
  PetscCall(MatSetValue(A, 1, 1, 0.0, INSERT_VALUES));
  PetscCall(MatSetValue(A, 0, 1, 1.0, INSERT_VALUES));
  PetscCall(MatSetValue(A, 1, 0, -1.0, INSERT_VALUES));
  PetscCall(MatAssemblyBegin(A, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(A, MAT_FINAL_ASSEMBLY));
  PetscFunctionReturn(0);
}

PetscErrorCode PositionRate(TS, PetscReal, Vec p, Vec qdot, void *) { return VecCopy(p, qdot); }

PetscErrorCode MomentumRate(TS, PetscReal, Vec q, Vec pdot, void *)
{
  PetscFunctionBeginUser;
  PetscCall(VecCopy(q, pdot));
  PetscCall(VecScale(pdot, -1.0));
  PetscFunctionReturn(0);
}

PetscErrorCode Acceleration(TS, PetscReal, Vec z, PetscScalar *a, void *ctx)
{
  const PetscScalar *x;
  PetscFunctionBeginUser;
  PetscCall(VecGetArrayRead(z, &x));
  a[0] = -x[0];
  PetscCall(VecRestoreArrayRead(z, &x));
  ++*static_cast<int *>(ctx);
  PetscFunctionReturn(0);
}

// The scheme each type's own public getter reports ("" for a type with one
// scheme). Every row of the table must be listed here.
using Getter = PetscErrorCode (*)(TS, const char **);
const std::map<std::string, Getter> &PublicGetters()
{
  static const std::map<std::string, Getter> m = {
      {TSRK, [](TS ts, const char **s) { return TSRKGetType(ts, s); }},
      {TSSSP, [](TS ts, const char **s) { return TSSSPGetType(ts, s); }},
      {TSBASICSYMPLECTIC, [](TS ts, const char **s) { return TSBasicSymplecticGetType(ts, s); }},
      {TSARKIMEX, [](TS ts, const char **s) { return TSARKIMEXGetType(ts, s); }},
      {TSROSW, [](TS ts, const char **s) { return TSRosWGetType(ts, s); }},
      {TSIRK, [](TS ts, const char **s) { return TSIRKGetType(ts, s); }},
      {TSEIMEX, nullptr},
      {TSRKN, TSRknGetScheme},
      {TSSYMSPLIT, TSSymSplitGetScheme},
      {TSEULER, nullptr},
      {TSBEULER, nullptr},
      {TSCN, nullptr},
      {TSTHETA, nullptr},
      {TSALPHA, nullptr},
      {TSBDF, nullptr},
  };
  return m;
}

struct StepResult {
  std::string card_integrator, card_accuracy, getter_scheme;
  PetscReal rollback_error = -1; // |z - z0| after TSRollBack; -1: TSRollBack refused
  bool interpolated = false;     // TSInterpolate inside the step worked
  int accelerations = 0;         // calls of the acceleration kernel
};

// One step of u'' = -u from (1, 0) with a TS of the row's type (prefix sim_,
// so the cost ledger records it), the Jacobian only for implicit types.
void OneStep(const TSTraits &row, StepResult *r)
{
  TS ts;
  Vec z;
  Mat J = NULL;
  IS is_u, is_v;
  PCHK(VecCreateSeq(PETSC_COMM_SELF, 2, &z));
  PCHK(VecSetValue(z, 0, 1.0, INSERT_VALUES));
  PCHK(VecSetValue(z, 1, 0.0, INSERT_VALUES));
  PCHK(VecAssemblyBegin(z));
  PCHK(VecAssemblyEnd(z));
  PCHK(TSCreate(PETSC_COMM_SELF, &ts));
  PCHK(TSSetOptionsPrefix(ts, "sim_"));
  PCHK(TSSetProblemType(ts, TS_NONLINEAR));
  PCHK(TSSetType(ts, row.type));
  PCHK(TSSetRHSFunction(ts, NULL, Rhs, NULL));
  if (!row.explicit_step) {
    PCHK(MatCreateSeqAIJ(PETSC_COMM_SELF, 2, 2, 2, NULL, &J)); // AIJ as the lattice's state matrix (irk needs it)
    PCHK(TSSetRHSJacobian(ts, J, J, Jacobian, NULL));
    SNES snes;
    KSP ksp;
    PC pc;
    PCHK(TSGetSNES(ts, &snes));
    PCHK(SNESGetKSP(snes, &ksp));
    PCHK(KSPGetPC(ksp, &pc));
    PCHK(PCSetType(pc, PCNONE)); // irk's stage matrix has no ilu
  }
  if (row.split_rhs) {
    PCHK(ISCreateStride(PETSC_COMM_SELF, 1, 0, 1, &is_u));
    PCHK(ISCreateStride(PETSC_COMM_SELF, 1, 1, 1, &is_v));
    PCHK(TSRHSSplitSetIS(ts, "position", is_u));
    PCHK(TSRHSSplitSetIS(ts, "momentum", is_v));
    PCHK(TSRHSSplitSetRHSFunction(ts, "position", NULL, PositionRate, NULL));
    PCHK(TSRHSSplitSetRHSFunction(ts, "momentum", NULL, MomentumRate, NULL));
    PCHK(ISDestroy(&is_u));
    PCHK(ISDestroy(&is_v));
  }
  PCHK(TSSetAcceleration(ts, Acceleration, &r->accelerations));
  PCHK(TSSetTimeStep(ts, 0.05));
  PCHK(TSSetMaxTime(ts, 1.0));
  PCHK(TSSetMaxSteps(ts, 1));
  PCHK(TSSetExactFinalTime(ts, TS_EXACTFINALTIME_MATCHSTEP));
  PCHK(TSSetFromOptions(ts));
  PCHK(TSSolve(ts, z));
  CostReset();
  PCHK(CostRecordSolve(ts, 0));
  CostCard card;
  PCHK(CostCardOn(PETSC_COMM_SELF, &card));
  REQUIRE(card.entries.size() == 2);
  REQUIRE(card.entries[0].prefix == "sim_");
  CHECK(card.entries[0].solves == 1);
  r->card_integrator = card.entries[0].integrator;
  r->card_accuracy = card.entries[0].accuracy;
  const auto g = PublicGetters().find(row.type);
  REQUIRE(g != PublicGetters().end()); // a new row needs its getter (or nullptr) above
  if (g->second) {
    const char *s = nullptr;
    PCHK(g->second(ts, &s));
    REQUIRE(s);
    r->getter_scheme = s;
  }
  {
    PetscReal t0, t1;
    Vec zi;
    PCHK(TSGetPrevTime(ts, &t0));
    PCHK(TSGetTime(ts, &t1));
    PCHK(VecDuplicate(z, &zi));
    PetscPushErrorHandler(PetscReturnErrorHandler, NULL);
    r->interpolated = TSInterpolate(ts, 0.5 * (t0 + t1), zi) == 0;
    const PetscErrorCode rb = TSRollBack(ts);
    PetscPopErrorHandler();
    if (!rb) {
      const PetscScalar *x;
      PCHK(VecGetArrayRead(z, &x));
      r->rollback_error = std::hypot(x[0] - 1.0, x[1]);
      PCHK(VecRestoreArrayRead(z, &x));
    }
    PCHK(VecDestroy(&zi));
  }
  CostReset();
  PCHK(TSDestroy(&ts));
  PCHK(MatDestroy(&J));
  PCHK(VecDestroy(&z));
}

void CheckRow(const TSTraits &row)
{
  INFO("-sim_ts_type " << row.type);
  StepResult r;
  OneStep(row, &r);
  const std::string expect = r.getter_scheme.empty() ? std::string(row.type) : std::string(row.type) + " " + r.getter_scheme;
  CHECK(r.card_integrator == expect);
  CHECK((row.scheme_getter != nullptr) == !r.getter_scheme.empty());
  if (row.fixed_step) CHECK(r.card_accuracy == "fixed step");
  if (row.rolls_back) CHECK((r.rollback_error >= 0 && r.rollback_error < 1e-12));
  else CHECK(r.rollback_error == -1);
  if (row.interpolant_order > 0) CHECK(r.interpolated);
  CHECK((r.accelerations > 0) == row.acceleration);
  CHECK(row.position_only == (row.acceleration || row.split_rhs));
}

} // namespace

TEST_CASE("integrator table: every type's card names the scheme its getter reports, and the traits hold", "[traits]")
{
  REQUIRE(TSTraitsCount() == PublicGetters().size());
  for (size_t i = 0; i < TSTraitsCount(); i++) CheckRow(TSTraitsAt(i));
}

TEST_CASE("integrator table: schemes chosen through options reach the card; rkn's default is dep64", "[traits]")
{
  const TSTraits *rkn = TSTraitsFind(TSRKN), *split = TSTraitsFind(TSSYMSPLIT), *rk = TSTraitsFind(TSRK);
  REQUIRE((rkn && split && rk));
  StepResult r;
  OneStep(*rkn, &r);
  CHECK(r.card_integrator == "rkn dep64"); // the pair rkn runs with no -sim_ts_rkn_scheme
  for (const char *pair : {"dep86", "dep1210"}) {
    ScopedOptions o({{"-sim_ts_rkn_scheme", pair}});
    StepResult p;
    OneStep(*rkn, &p);
    CHECK(p.card_integrator == std::string("rkn ") + pair);
    CHECK(p.getter_scheme == pair);
  }
  {
    ScopedOptions o({{"-sim_ts_symsplit_scheme", "bm6"}});
    StepResult p;
    OneStep(*split, &p);
    CHECK(p.card_integrator == "symsplit bm6");
  }
  {
    ScopedOptions o({{"-sim_ts_rk_type", "8vr"}});
    StepResult p;
    OneStep(*rk, &p);
    CHECK(p.card_integrator == "rk 8vr");
  }
}

TEST_CASE("integrator table: a type it lacks is refused in one line naming the option", "[traits]")
{
  CHECK(TSTraitsFind(TSMPRK) == nullptr);
  CHECK(std::strcmp(TSDefaultType("sim_"), TSRK) == 0);
  CHECK(TSTraitsFind(TSDefaultType("nnm_")) != nullptr);
  CHECK(TSDefaultType("other_") == nullptr);
  TS ts;
  const TSTraits *tr = nullptr;
  PCHK(TSCreate(PETSC_COMM_SELF, &ts));
  PCHK(TSSetOptionsPrefix(ts, "sim_"));
  PCHK(TSSetType(ts, TSMPRK));
  PetscPushErrorHandler(PetscReturnErrorHandler, NULL);
  const PetscErrorCode ierr = TSGetTraits(ts, &tr);
  PetscPopErrorHandler();
  REQUIRE(ierr != 0);
  const char *text = nullptr;
  char *specific = nullptr;
  PetscErrorMessage(ierr, &text, &specific);
  REQUIRE(specific);
  const std::string msg = specific;
  CHECK(msg.find("-sim_ts_type mprk: not in nltopo's integrator table (rk, ") == 0);
  CHECK(msg.find('\n') == std::string::npos);
  PCHK(TSDestroy(&ts));
}
