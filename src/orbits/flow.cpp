#include "orbits/flow.hpp"
#include "core/cost.hpp"
#include "core/log.hpp"
#include "core/option_table.hpp"
#include "core/ts_traits.hpp"
#include "orbits/period_ts.hpp"
#include "timeint/ts_symsplit.hpp"
#include <cmath>
#include <cstring>

namespace nltopo {

static const char *const kRouteNames[] = {"variational", "tsforward"};

// The flow's -nnm_* options; the TS itself reads -nnm_ts_* (PETSc's, with nltopo's default type, core/ts_traits.hpp).
static const auto &kFlowTable = DeclareOptionTable<FlowOptions>(
    "nnm_", "Periodic-orbit flow (TS options: -nnm_ts_*; -nnm_ts_type symsplit by default, scheme bm4)", [](OptionTable<FlowOptions> &t) {
      t.Int("steps_per_period", &FlowOptions::steps, Closed(8, 1000000), "Fixed steps per period of the shooting integration (any -nnm_ts_type; default 128)")
          .Enum(
              "monodromy", &FlowOptions::route, kRouteNames, 2,
              "Monodromy: variational (state and variational equations in one structured TS) or tsforward (TSForwardSetSensitivities, needs -nnm_ts_type rk)");
    });

PetscErrorCode FlowOptionsFromOptions(MPI_Comm comm, FlowOptions *o)
{
  PetscFunctionBeginUser;
  PetscCall(kFlowTable.Read(comm, o));
  PetscFunctionReturn(0);
}

namespace {
PetscErrorCode FlowRhs(TS ts, PetscReal t, Vec z, Vec f, void *ctx)
{
  PetscFunctionBeginUser;
  CostCountEvaluations(1);
  PetscCall(static_cast<PeriodicFlow *>(ctx)->EvalRhs(t, z, f));
  PetscFunctionReturn(0);
}
PetscErrorCode FlowJacobian(TS ts, PetscReal t, Vec z, Mat A, Mat P, void *ctx)
{
  PetscFunctionBeginUser;
  PetscCall(static_cast<PeriodicFlow *>(ctx)->EvalJacobian(z, P));
  PetscFunctionReturn(0);
}
PetscErrorCode FlowJacobianP(TS ts, PetscReal t, Vec z, Mat Jp, void *ctx)
{
  PetscFunctionBeginUser;
  PetscCall(static_cast<PeriodicFlow *>(ctx)->EvalJacobianP(z, Jp));
  PetscFunctionReturn(0);
}
PetscErrorCode FlowAcceleration(TS, PetscReal t, Vec z, PetscScalar *a, void *ctx)
{
  PetscFunctionBeginUser;
  CostCountEvaluations(1);
  PetscCall(static_cast<Rhs *>(ctx)->Acceleration(t, z, a));
  PetscFunctionReturn(0);
}
PetscErrorCode FlowAverageMonitor(TS ts, PetscInt step, PetscReal t, Vec z, void *ctx)
{
  PetscFunctionBeginUser;
  PetscCall(static_cast<PeriodicFlow *>(ctx)->AccumulateStiffness(step, z));
  PetscFunctionReturn(0);
}
} // namespace

PeriodicFlow::~PeriodicFlow() = default;

PetscErrorCode PeriodicFlow::Setup(const EffectList &fx, const FlowOptions &o)
{
  const Lattice &lat = fx.Lat();
  const PetscInt n = 2 * lat.N(), nl = 2 * lat.OwnedCount();
  PetscFunctionBeginUser;
  PetscCall(fx.RequireConservative("the periodic-orbit flow (NNMs conserve the energy)"));
  fx_ = &fx;
  lat_ = &lat;
  opt_ = o;
  rhs_ = std::make_unique<Rhs>(fx);
  PetscCall(lat.CreateStateMatrix(J_.out()));
  PetscCall(MatCreateDense(lat.Comm(), nl, PETSC_DECIDE, n, 2, NULL, Jp_tlm_.out()));
  PetscCall(MatCreateDense(lat.Comm(), nl, PETSC_DECIDE, n, 2, NULL, S_tlm_.out()));
  PetscCall(CreateTS(ts_.out(), NULL));
  PetscCall(TSMonitorSet(ts_, FlowAverageMonitor, this, NULL)); // acts only inside IntegrateAveragingStiffness
  {
    // a fixed-step integrator of u'' = a(u) on the acceleration kernel (symsplit):
    // its tangent map is the same step of the augmented system (orbits/variational_symplectic.hpp)
    const TSTraits *tr;
    PetscCall(TSGetTraits(ts_, &tr));
    symplectic_ = tr->fixed_step && tr->acceleration;
  }
  if (symplectic_) {
    PetscBool type_set;
    PetscCall(PetscOptionsHasName(NULL, "nnm_", "-ts_type", &type_set));
    PetscCheck(o.route == MonodromyRoute::Variational, lat.Comm(), PETSC_ERR_USER, "-nnm_monodromy tsforward needs -nnm_ts_type rk (forward sensitivities); %s",
               type_set ? "-nnm_ts_type symsplit has its own tangent map" : "the default -nnm_ts_type is symsplit, whose tangent map is its own");
    PetscCall(TSSetAcceleration(ts_, FlowAcceleration, rhs_.get())); // beta enters after the splitting (Unfold)
  } else PetscCall(CreateTS(ts_tlm_.out(), Jp_tlm_));
  // the dense 2N x (2N + 1) TSForward set-up only when the dense monodromy is asked for (O(N^2) memory)
  PetscFunctionReturn(0);
}

PetscErrorCode PeriodicFlow::CreateTS(TS *ts, Mat jacp)
{
  TSAdapt adapt;
  TSAdaptType atype;
  PetscBool none;
  char type[64]; // -nnm_ts_type, or its code default (core/ts_traits.cpp)
  PetscFunctionBeginUser;
  // Created as the type -nnm_ts_type names, so that rk is 5dp (CreatePeriodTS)
  // unless -nnm_ts_rk_type says otherwise.
  PetscCall(PetscStrncpy(type, TSDefaultType("nnm_"), sizeof(type)));
  PetscCall(PetscOptionsGetString(NULL, "nnm_", "-ts_type", type, sizeof(type), NULL));
  PetscCall(CreatePeriodTS(lat_->Comm(), type, FlowRhs, this, ts));
  PetscCall(TSSetRHSJacobian(*ts, J_, J_, FlowJacobian, this));
  if (jacp) PetscCall(TSSetRHSJacobianP(*ts, jacp, FlowJacobianP, this));
  PetscCall(TSSetFromOptions(*ts));
  PetscCall(TSGetAdapt(*ts, &adapt));
  PetscCall(TSAdaptGetType(adapt, &atype));
  PetscCall(PetscStrcmp(atype, TSADAPTNONE, &none));
  PetscCheck(none, lat_->Comm(), PETSC_ERR_USER,
             "-nnm_ts_adapt_type must be none (fixed steps T/n): PETSc 3.18 forward sensitivities are wrong with adaptive RK; got %s", atype);
  PetscFunctionReturn(0);
}

PetscErrorCode PeriodicFlow::EvalRhs(PetscReal t, Vec z, Vec f)
{
  PetscFunctionBeginUser;
  PetscCall(rhs_->Evaluate(t, z, f));
  if (beta_ != 0) { // f + beta grad E = [f_u - beta f_v, f_v + beta f_u]
    PetscScalar *a;
    const PetscInt m = lat_->OwnedCount();
    PetscCall(VecGetArray(f, &a));
    for (PetscInt k = 0; k < m; k++) {
      const PetscScalar fu = a[k], fv = a[m + k];
      a[k] = fu - beta_ * fv;
      a[m + k] = fv + beta_ * fu;
    }
    PetscCall(VecRestoreArray(f, &a));
  }
  PetscFunctionReturn(0);
}

PetscErrorCode PeriodicFlow::EvalJacobian(Vec z, Mat A)
{
  PetscFunctionBeginUser;
  PetscCall(fx_->AssembleStateJacobian(z, A, beta_));
  PetscFunctionReturn(0);
}

PetscErrorCode PeriodicFlow::Field(Vec z, Vec f)
{
  PetscFunctionBeginUser;
  PetscCall(rhs_->Evaluate(0, z, f));
  PetscFunctionReturn(0);
}

PetscErrorCode PeriodicFlow::GradEnergy(Vec z, Vec g)
{
  PetscScalar *a;
  const PetscInt m = lat_->OwnedCount();
  PetscFunctionBeginUser;
  PetscCall(rhs_->Evaluate(0, z, g));
  PetscCall(VecGetArray(g, &a));
  for (PetscInt k = 0; k < m; k++) { // [f_u, f_v] = [v, -dV/du] -> [dV/du, v]
    const PetscScalar fu = a[k];
    a[k] = -a[m + k];
    a[m + k] = fu;
  }
  PetscCall(VecRestoreArray(g, &a));
  PetscFunctionReturn(0);
}

// d f / d beta = grad E(z): the last column of the parameter Jacobian.
PetscErrorCode PeriodicFlow::EvalJacobianP(Vec z, Mat Jp)
{
  PetscInt ncol;
  Vec g, col;
  PetscFunctionBeginUser;
  PetscCall(MatGetSize(Jp, NULL, &ncol));
  PetscCall(MatZeroEntries(Jp));
  PetscCall(VecDuplicate(z, &g));
  PetscCall(GradEnergy(z, g));
  PetscCall(MatDenseGetColumnVecWrite(Jp, ncol - 1, &col));
  PetscCall(VecCopy(g, col));
  PetscCall(MatDenseRestoreColumnVecWrite(Jp, ncol - 1, &col));
  PetscCall(VecDestroy(&g));
  PetscCall(MatAssemblyBegin(Jp, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(Jp, MAT_FINAL_ASSEMBLY));
  PetscFunctionReturn(0);
}

PetscErrorCode PeriodicFlow::Run(TS ts, Vec z0, PetscReal T, Vec zT)
{
  PetscFunctionBeginUser;
  PetscCall(VecCopy(z0, zT));
  PetscCall(SolvePeriod(ts, zT, T, Steps(), "periodic-orbit"));
  PetscFunctionReturn(0);
}

PetscErrorCode PeriodicFlow::Unfold(Vec zT, PetscReal T, PetscReal beta)
{
  PetscFunctionBeginUser;
  if (!symplectic_ || beta == 0) PetscFunctionReturn(0);
  if (!wb_) PetscCall(VecDuplicate(zT, wb_.out()));
  PetscCall(GradEnergy(zT, wb_));
  PetscCall(VecAXPY(zT, beta * T, wb_));
  PetscFunctionReturn(0);
}

PetscErrorCode PeriodicFlow::Integrate(Vec z0, PetscReal T, PetscReal beta, Vec zT)
{
  PetscFunctionBeginUser;
  beta_ = beta;
  PetscCall(Run(ts_, z0, T, zT));
  PetscCall(Unfold(zT, T, beta));
  PetscFunctionReturn(0);
}

PetscErrorCode PeriodicFlow::IntegrateAveragingStiffness(Vec z0, PetscReal T, PetscReal beta, Vec zT, StiffnessHarmonics *h)
{
  PetscFunctionBeginUser;
  const PetscInt m = lat_->OwnedCount(), mh = h->parametric ? m : 0;
  h->d0.assign(m, 0.0);
  h->o0.assign(m, 0.0);
  for (auto *v : {&h->dc, &h->oc, &h->ds, &h->os}) v->assign(mh, 0.0);
  harm_ = h;
  beta_ = beta;
  const PetscErrorCode ierr = Run(ts_, z0, T, zT);
  harm_ = nullptr;
  PetscCall(ierr);
  PetscCall(Unfold(zT, T, beta));
  PetscFunctionReturn(0);
}

// Trapezoidal weights over the samples at steps 0..n (the monitor sees every
// one); step k is at t = k T / n, so 2 w t = 4 pi k / n.
PetscErrorCode PeriodicFlow::AccumulateStiffness(PetscInt step, Vec z)
{
  const PetscScalar *u;
  Vec ul;
  PetscFunctionBeginUser;
  if (!harm_) PetscFunctionReturn(0);
  const PetscInt n = Steps();
  const PetscReal w = (step == 0 || step == n ? 0.5 : 1.0) / n;
  const PetscReal phase = 4 * PETSC_PI * step / n, wc = 2 * w * std::cos(phase), ws = 2 * w * std::sin(phase);
  const PetscInt xs = lat_->OwnedStart(), xm = lat_->OwnedCount();
  StiffnessHarmonics &h = *harm_;
  std::vector<PetscScalar> &kd = kd_, &kb = kb_; // K_T(u): owned diagonal, bonds xs-1 .. xs+xm-1
  kd.resize(xm);
  kb.resize(xm + 1);
  PetscCall(lat_->GetGhostedU(z, &ul, &u));
  fx_->Stiffness(u, kd.data() - xs, kb.data() + 1 - xs);
  for (PetscInt i = xs; i < xs + xm; i++) {
    const PetscInt k = i - xs;
    const PetscScalar c[3] = {kb[k], kd[k], kb[k + 1]}; // row i of K_T
    h.d0[k] += w * c[1];
    h.o0[k] += w * c[2];
    if (h.parametric) {
      h.dc[k] += wc * c[1];
      h.oc[k] += wc * c[2];
      h.ds[k] += ws * c[1];
      h.os[k] += ws * c[2];
    }
  }
  PetscCall(lat_->RestoreGhostedU(z, &ul, &u));
  PetscFunctionReturn(0);
}

PetscErrorCode PeriodicFlow::CreateSensitivityMatrix(Mat *S) const
{
  PetscFunctionBeginUser;
  PetscCall(MatCreateDense(lat_->Comm(), 2 * lat_->OwnedCount(), PETSC_DECIDE, 2 * lat_->N(), 2 * lat_->N() + 1, NULL, S));
  PetscFunctionReturn(0);
}

PetscErrorCode PeriodicFlow::IntegrateWithMonodromy(Vec z0, PetscReal T, PetscReal beta, Vec zT, Mat S)
{
  PetscFunctionBeginUser;
  beta_ = beta;
  if (symplectic_) {
    if (!sym_dense_) {
      sym_dense_ = std::make_unique<SymplecticVariationalFlow>();
      PetscCall(sym_dense_->Setup(*fx_, 2 * lat_->N(), Steps()));
    }
    sym_dense_->SetSteps(Steps());
    PetscCall(sym_dense_->Integrate(z0, T, beta, NULL, 1.0, 0.0, zT, S, NULL));
    PetscFunctionReturn(0);
  }
  if (opt_.route == MonodromyRoute::Variational) {
    if (!var_dense_) {
      var_dense_ = std::make_unique<VariationalFlow>();
      PetscCall(var_dense_->Setup(*fx_, 2 * lat_->N() + 1, Steps()));
    }
    var_dense_->SetSteps(Steps());
    PetscCall(var_dense_->Integrate(z0, T, beta, NULL, 1.0, 0.0, zT, S, NULL));
    PetscFunctionReturn(0);
  }
  if (!ts_mono_) {
    const PetscInt n = 2 * lat_->N();
    PetscCall(MatCreateDense(lat_->Comm(), 2 * lat_->OwnedCount(), PETSC_DECIDE, n, n + 1, NULL, Jp_mono_.out()));
    PetscCall(CreateTS(ts_mono_.out(), Jp_mono_));
  }
  PetscCall(MatZeroEntries(S));
  PetscCall(MatShift(S, 1.0)); // [I | 0]: initial-condition columns, then the beta column
  PetscCall(TSForwardSetSensitivities(ts_mono_, 2 * lat_->N() + 1, S));
  PetscCall(Run(ts_mono_, z0, T, zT));
  PetscFunctionReturn(0);
}

PetscErrorCode PeriodicFlow::IntegrateWithTangent(Vec z0, PetscReal T, PetscReal beta, Vec dz, PetscReal dbeta, PetscReal dT, Vec zT, Vec w)
{
  Vec c;
  PetscFunctionBeginUser;
  beta_ = beta;
  if (symplectic_) {
    if (!sym_tlm_) {
      sym_tlm_ = std::make_unique<SymplecticVariationalFlow>();
      PetscCall(sym_tlm_->Setup(*fx_, 1, Steps()));
    }
    sym_tlm_->SetSteps(Steps());
    PetscCall(sym_tlm_->Integrate(z0, T, beta, dz, dbeta, dT, zT, NULL, w));
    PetscFunctionReturn(0);
  }
  if (opt_.route == MonodromyRoute::Variational) {
    if (!var_tlm_) { // one column: dbeta and dT enter as sources
      var_tlm_ = std::make_unique<VariationalFlow>();
      PetscCall(var_tlm_->Setup(*fx_, 1, Steps()));
    }
    var_tlm_->SetSteps(Steps());
    PetscCall(var_tlm_->Integrate(z0, T, beta, dz, dbeta, dT, zT, NULL, w));
    PetscFunctionReturn(0);
  }
  // Column 0: the direction (dz, dbeta) combined: d/deps z(T; z0 + eps dz, beta + eps dbeta);
  // the parameter Jacobian's last column (grad E) times dbeta enters through column 1.
  PetscCall(MatZeroEntries(S_tlm_));
  PetscCall(MatDenseGetColumnVecWrite(S_tlm_, 0, &c));
  PetscCall(VecCopy(dz, c));
  PetscCall(MatDenseRestoreColumnVecWrite(S_tlm_, 0, &c));
  PetscCall(TSForwardSetSensitivities(ts_tlm_, 2, S_tlm_));
  PetscCall(Run(ts_tlm_, z0, T, zT));
  PetscCall(MatDenseGetColumnVecRead(S_tlm_, 0, &c));
  PetscCall(VecCopy(c, w));
  PetscCall(MatDenseRestoreColumnVecRead(S_tlm_, 0, &c));
  if (dbeta != 0) {
    PetscCall(MatDenseGetColumnVecRead(S_tlm_, 1, &c));
    PetscCall(VecAXPY(w, dbeta, c));
    PetscCall(MatDenseRestoreColumnVecRead(S_tlm_, 1, &c));
  }
  if (dT != 0) { // the exact flow's T-derivative
    if (!wb_) PetscCall(VecDuplicate(z0, wb_.out()));
    PetscCall(EvalRhs(T, zT, wb_));
    PetscCall(VecAXPY(w, dT, wb_));
  }
  PetscFunctionReturn(0);
}

PetscErrorCode PeriodicFlow::IntegrateWithTangents(Vec z0, PetscReal T, PetscReal beta, const std::vector<Vec> &dz, Vec zT, std::vector<Vec> &w)
{
  const PetscInt s = (PetscInt)dz.size();
  PetscFunctionBeginUser;
  PetscCheck(s > 0 && w.size() == dz.size(), lat_->Comm(), PETSC_ERR_ARG_SIZ, "IntegrateWithTangents: %zu start vectors and %zu results", dz.size(), w.size());
  if (!symplectic_) {
    for (PetscInt j = 0; j < s; j++) PetscCall(IntegrateWithTangent(z0, T, beta, dz[j], 0.0, 0.0, zT, w[j]));
    PetscFunctionReturn(0);
  }
  beta_ = beta;
  if (!sym_block_ || sym_block_cols_ != s) {
    sym_block_ = std::make_unique<SymplecticVariationalFlow>();
    PetscCall(sym_block_->Setup(*fx_, s, Steps()));
    sym_block_cols_ = s;
  }
  sym_block_->SetSteps(Steps());
  PetscCall(sym_block_->IntegrateBlock(z0, T, beta, dz, zT, w));
  PetscFunctionReturn(0);
}

} // namespace nltopo
