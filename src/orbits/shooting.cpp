#include "orbits/shooting.hpp"
#include "core/memory_guard.hpp"
#include "core/gather.hpp"
#include "core/log.hpp"
#include "core/signals.hpp"
#include <algorithm>
#include <cmath>

namespace nltopo {

static const char *const kJacobianNames[] = {"dense", "mf"};
static const char *const kMfPcNames[] = {"none", "linear", "averaged", "parametric"};

PetscErrorCode ShootingOptionsFromOptions(MPI_Comm comm, ShootingOptions *o)
{
  PetscInt j = static_cast<PetscInt>(o->jacobian), pc = static_cast<PetscInt>(o->mf_pc);
  PetscFunctionBeginUser;
  PetscOptionsBegin(comm, "nnm_", "Shooting Newton (SNES options: -nnm_snes_*, -nnm_ksp_*, -nnm_pc_*)", NULL);
  PetscBool start_set;
  PetscCall(PetscOptionsEList("-jacobian", "Shooting Jacobian: dense (monodromy by forward sensitivities) or mf (one tangent-linear integration per product); -nnm_snes_mf for finite differences",
                              NULL, kJacobianNames, 2, kJacobianNames[j], &j, NULL));
  PetscCall(PetscOptionsInt("-start_dense_max",
                            "Largest 2N for which the first orbit of a branch uses the dense SVD start solver (-nnm_start_*); default 4000 for the "
                            "dense Jacobian, 0 for mf (its preconditioner already treats the edge-mode direction exactly)",
                            NULL, o->start_dense_max, &o->start_dense_max, &start_set));
  if (!start_set && j == static_cast<PetscInt>(ShootingJacobian::MatrixFree)) o->start_dense_max = 0;
  PetscCall(PetscOptionsEList("-mf_pc",
                              "Preconditioner of the mf shooting Jacobian: linear (exact inverse of M_lin - I of the linear lattice, O(N) per "
                              "application), averaged (the same with K replaced by the orbit's time-averaged tangent stiffness), parametric (averaged "
                              "plus the orbit's 2 omega parametric term on the band modes near omega, rotating-wave approximation) or none (plain GMRES)",
                              NULL, kMfPcNames, 4, kMfPcNames[pc], &pc, NULL));
  PetscCall(PetscOptionsReal("-mf_pc_parametric_weight",
                             "Scale in (0, 1] of the 2 omega term in -nnm_mf_pc parametric; below 1 it keeps the block regular along the orbit's own phase "
                             "direction (1 makes GMRES break down at converged orbits)",
                             NULL, o->parametric_weight, &o->parametric_weight, NULL));
  PetscCall(PetscOptionsReal("-orbit_rtol",
                             "Newton also stops once |z(T) - z0| <= this times |z0| (0: only -nnm_snes_atol and -nnm_snes_rtol); for branches whose "
                             "amplitude grows by decades, where one absolute tolerance is too tight at the top or too loose at the bottom",
                             NULL, o->orbit_rtol, &o->orbit_rtol, NULL));
  PetscOptionsEnd();
  PetscCheck(o->start_dense_max >= 0 && o->start_dense_max <= 20000, comm, PETSC_ERR_USER, "-nnm_start_dense_max must lie in [0, 20000], got %" PetscInt_FMT,
             o->start_dense_max);
  PetscCheck(o->orbit_rtol >= 0 && o->orbit_rtol < 1, comm, PETSC_ERR_USER, "-nnm_orbit_rtol %g: must lie in [0, 1)", (double)o->orbit_rtol);
  PetscCheck(o->parametric_weight > 0 && o->parametric_weight <= 1, comm, PETSC_ERR_USER, "-nnm_mf_pc_parametric_weight %g: must lie in (0, 1]",
             (double)o->parametric_weight);
  o->jacobian = static_cast<ShootingJacobian>(j);
  o->mf_pc = static_cast<MatrixFreePC>(pc);
  PetscFunctionReturn(0);
}

namespace {
// A Newton iterate with T <= 0 (a failing step far from the branch) is outside
// the domain: SNES stops with DIVERGED_FUNCTION_DOMAIN and the continuation
// rejects the step, instead of integrating backwards or failing at SetPeriod.
PetscErrorCode ShootResidual(SNES snes, Vec X, Vec F, void *ctx)
{
  PetscBool ok;
  PetscFunctionBeginUser;
  PetscCall(static_cast<Shooting *>(ctx)->InDomain(X, &ok));
  if (!ok) {
    PetscCall(SNESSetFunctionDomainError(snes));
    PetscFunctionReturn(0);
  }
  PetscCall(static_cast<Shooting *>(ctx)->Residual(X, F));
  PetscFunctionReturn(0);
}
PetscErrorCode ShootJacobian(SNES snes, Vec X, Mat A, Mat P, void *ctx)
{
  PetscBool ok;
  PetscFunctionBeginUser;
  PetscCall(static_cast<Shooting *>(ctx)->InDomain(X, &ok));
  if (!ok) {
    PetscCall(SNESSetJacobianDomainError(snes));
    PetscFunctionReturn(0);
  }
  PetscCall(static_cast<Shooting *>(ctx)->Jacobian(X, P));
  if (A != P) {
    PetscCall(MatAssemblyBegin(A, MAT_FINAL_ASSEMBLY));
    PetscCall(MatAssemblyEnd(A, MAT_FINAL_ASSEMBLY));
  }
  PetscFunctionReturn(0);
}
PetscErrorCode ShootConverged(SNES snes, PetscInt it, PetscReal xnorm, PetscReal snorm, PetscReal fnorm, SNESConvergedReason *reason, void *ctx)
{
  PetscFunctionBeginUser;
  PetscCall(static_cast<Shooting *>(ctx)->Converged(snes, it, xnorm, snorm, fnorm, reason));
  PetscFunctionReturn(0);
}
PetscErrorCode ShootPCApply(PC pc, Vec r, Vec x)
{
  void *s;
  PetscFunctionBeginUser;
  PetscCall(PCShellGetContext(pc, &s));
  PetscCall(static_cast<Shooting *>(s)->PCApply(r, x));
  PetscFunctionReturn(0);
}
PetscErrorCode ShootShellMult(Mat A, Vec x, Vec y)
{
  Shooting *s;
  PetscFunctionBeginUser;
  PetscCall(MatShellGetContext(A, &s));
  PetscCall(s->ShellMult(x, y));
  PetscFunctionReturn(0);
}
} // namespace

PetscErrorCode Shooting::Setup(PeriodicFlow &flow, const ShootingOptions &o)
{
  MPI_Comm comm;
  KSP ksp;
  PC pc;
  PetscFunctionBeginUser;
  flow_ = &flow;
  lat_ = &flow.Lat();
  opt_ = o;
  comm = lat_->Comm();
  PetscCallMPI(MPI_Comm_rank(comm, &rank_));
  PetscCallMPI(MPI_Comm_size(comm, &size_));
  n_ = 2 * lat_->N();
  nlocx_ = 2 * lat_->OwnedCount() + (rank_ == size_ - 1 ? 2 : 0);
  PetscCall(lat_->CreateStateVector(z_.out()));
  for (OwnedVec *v : {&zT_, &fref_, &zref_, &g_, &w_, &zlin_, &fT_}) PetscCall(VecDuplicate(z_, v->out()));
  PetscCall(CreateUnknowns(tan_.out()));
  PetscCall(VecDuplicate(tan_, Xpred_.out()));
  PetscCall(VecDuplicate(tan_, work_.out()));
  PetscCall(VecDuplicate(tan_, F_.out()));
  PetscCall(SNESCreate(comm, snes_.out()));
  PetscCall(SNESSetOptionsPrefix(snes_, "nnm_"));
  PetscCall(SNESSetFunction(snes_, F_, ShootResidual, this));
  PetscCall(SNESGetKSP(snes_, &ksp));
  PetscCall(KSPGetPC(ksp, &pc));
  // The assembled (dense-pattern) Jacobian: the dense route, and the start
  // solver of every route while 2N is small enough to hold it.
  const PetscInt M = n_ + 2;
  if (o.jacobian == ShootingJacobian::Dense || n_ <= o.start_dense_max) {
    // Dense-pattern AIJ (12 bytes per entry) plus the sensitivity matrix and MUMPS's factor.
    PetscCall(CheckMemory(comm, 4.0 * 12.0 * (double)M * (double)nlocx_, "the dense shooting Jacobian (2N = -lattice_cells x 4; -nnm_jacobian mf avoids it)"));
    PetscCall(flow.CreateSensitivityMatrix(S_.out()));
    PetscCall(MatCreateAIJ(comm, nlocx_, nlocx_, M, M, nlocx_, NULL, M - nlocx_, NULL, Jdense_.out())); // dense pattern
  }
  if (o.jacobian == ShootingJacobian::Dense) {
    PetscCall(SNESSetJacobian(snes_, Jdense_, Jdense_, ShootJacobian, this));
    // A pivoting LU (the bordered Jacobian has zero diagonal entries): MUMPS.
    PetscCall(KSPSetType(ksp, KSPPREONLY));
    PetscCall(PCSetType(pc, PCLU));
    PetscCall(PCFactorSetMatSolverType(pc, MATSOLVERMUMPS));
  } else {
    PetscCall(MatCreateShell(comm, nlocx_, nlocx_, M, M, this, Jshell_.out()));
    PetscCall(MatShellSetOperation(Jshell_, MATOP_MULT, (void (*)(void))ShootShellMult));
    PetscCall(SNESSetJacobian(snes_, Jshell_, Jshell_, ShootJacobian, this));
    PetscCall(KSPSetType(ksp, KSPGMRES));
    if (o.mf_pc != MatrixFreePC::None) {
      PetscCall(lin_pc_.Setup(*lat_));
      PetscCall(PCSetType(pc, PCSHELL));
      PetscCall(PCShellSetContext(pc, this));
      PetscCall(PCShellSetApply(pc, ShootPCApply));
      const char *name = o.mf_pc == MatrixFreePC::Linear     ? "exact inverse of M_lin - I (linear lattice) on the state rows, identity on the border"
                         : o.mf_pc == MatrixFreePC::Averaged ? "exact inverse of M_avg - I (linear lattice with the orbit's time-averaged tangent stiffness) on the state rows, identity on the border"
                                                             : "inverse of M_avg - I plus the rotating-wave 2 omega parametric block near the 1:1 resonance on the state rows, identity on the border";
      PetscCall(PCShellSetName(pc, name));
      PetscCall(KSPSetPCSide(ksp, PC_RIGHT)); // GMRES minimises the true residual
    } else PetscCall(PCSetType(pc, PCNONE));
    PetscCall(KSPSetTolerances(ksp, 1e-10, 1e-14, PETSC_DEFAULT, 400));
    PetscCall(KSPGMRESSetRestart(ksp, 100)); // no restarts within the iteration counts the preconditioner gives
    // Classical Gram-Schmidt loses orthogonality on the nearly singular M - I of
    // long lattices in a band; at a restart PETSc then finds the recursion's
    // residual far from the true one and stops with DIVERGED_BREAKDOWN (seen at
    // iterations 100 and 200, N = 10^4). A second pass when needed costs
    // O(k N) per iteration, nothing beside a tangent integration.
    PetscCall(KSPGMRESSetCGSRefinementType(ksp, KSP_GMRES_CGS_REFINE_IFNEEDED));
    // Inexact Newton (Eisenstat-Walker forcing terms): GMRES is converged only as far as
    // the Newton step needs. Inside the bands, where resonant modes make the
    // preconditioned operator far from the identity, the GMRES iterations per point
    // drop ~4x (steps get smaller too) and the band edge costs less (README.md, Long lattices).
    PetscCall(SNESKSPSetUseEW(snes_, PETSC_TRUE));
  }
  PetscCall(SNESSetTolerances(snes_, 1e-12, 1e-10, 1e-14, 12, PETSC_DEFAULT));
  PetscCall(SNESSetFromOptions(snes_));
  PetscCall(SNESGetTolerances(snes_, &snes_atol_, NULL, NULL, NULL, NULL));
  if (o.jacobian == ShootingJacobian::MatrixFree) {
    // No GMRES iterations beyond what Newton's own threshold asks for
    // (-nnm_snes_atol here, or -nnm_orbit_rtol |z0| once larger: Converged): a
    // linear residual below half of it makes the next |F| (linear residual +
    // O(|step|^2)) meet it. Eisenstat-Walker alone asks the last solve for a
    // relative 1e-4 or so, which near the band edge of long lattices took 100+
    // iterations to reduce a residual already at 1.4 x atol (benchmarks/README.md).
    PetscCall(PetscOptionsHasName(NULL, "nnm_", "-ksp_atol", &ksp_atol_set_));
    if (!ksp_atol_set_) PetscCall(KSPSetTolerances(ksp, PETSC_DEFAULT, 0.5 * snes_atol_, PETSC_DEFAULT, PETSC_DEFAULT));
  }
  PetscCall(SNESSetConvergenceTest(snes_, ShootConverged, this, NULL));
  PetscCall(KSPGetTolerances(ksp, &tangent_rtol_, NULL, NULL, NULL)); // before Eisenstat-Walker changes it
  PetscCall(PetscOptionsHasName(NULL, "nnm_", "-snes_mf", &snes_mf_));
  if (Jdense_) {
    // Start solver (prefix -nnm_start_) for the first orbit of a branch:
    // pseudo-inverse by SVD with tiny singular values dropped. At the linear
    // limit of the insulated branch the left-end edge mode has the same period
    // (model.md "Trap"): a near-null direction of the shooting Jacobian
    // (singular value ~1e-11 against >1e-3 for the others) that an LU would
    // follow off the branch. Dropping it keeps Newton quadratic and on the
    // insulated family; along the branch the hardening detunes the edge mode
    // and the main solver's pivoting LU is used.
    KSP kspS;
    PC pcS;
    PetscBool has;
    PetscCall(PetscOptionsHasName(NULL, "nnm_start_", "-pc_svd_zero_sing", &has));
    if (!has) PetscCall(PetscOptionsSetValue(NULL, "-nnm_start_pc_svd_zero_sing", "1e-9")); // PCSVD has no setter in 3.18
    PetscCall(SNESCreate(comm, snes_start_.out()));
    PetscCall(SNESSetOptionsPrefix(snes_start_, "nnm_start_"));
    PetscCall(SNESSetFunction(snes_start_, F_, ShootResidual, this));
    PetscCall(SNESSetJacobian(snes_start_, Jdense_, Jdense_, ShootJacobian, this));
    PetscCall(SNESGetKSP(snes_start_, &kspS));
    PetscCall(KSPSetType(kspS, KSPPREONLY));
    PetscCall(KSPGetPC(kspS, &pcS));
    PetscCall(PCSetType(pcS, PCSVD));
    PetscCall(SNESSetTolerances(snes_start_, 1e-12, 1e-10, 1e-14, 20, PETSC_DEFAULT));
    PetscCall(SNESSetFromOptions(snes_start_));
  }
  PetscFunctionReturn(0);
}

PetscErrorCode Shooting::CreateUnknowns(Vec *X) const
{
  PetscFunctionBeginUser;
  PetscCall(VecCreateMPI(lat_->Comm(), nlocx_, n_ + 2, X));
  PetscFunctionReturn(0);
}

// X's state entries have the state vector's global indices; T and beta are 2N, 2N+1 (last rank).
PetscErrorCode Shooting::Pack(Vec z, PetscReal T, PetscReal beta, Vec X) const
{
  const PetscScalar *a;
  PetscScalar *x;
  const PetscInt m = 2 * lat_->OwnedCount();
  PetscFunctionBeginUser;
  PetscCall(VecGetArrayRead(z, &a));
  PetscCall(VecGetArray(X, &x));
  PetscCall(PetscArraycpy(x, a, m));
  if (rank_ == size_ - 1) {
    x[m] = T;
    x[m + 1] = beta;
  }
  PetscCall(VecRestoreArray(X, &x));
  PetscCall(VecRestoreArrayRead(z, &a));
  PetscFunctionReturn(0);
}

PetscErrorCode Shooting::Unpack(Vec X, Vec z, PetscReal *T, PetscReal *beta) const
{
  const PetscScalar *x;
  PetscScalar *a;
  PetscReal tb[2] = {0, 0};
  const PetscInt m = 2 * lat_->OwnedCount();
  PetscFunctionBeginUser;
  PetscCall(VecGetArrayRead(X, &x));
  PetscCall(VecGetArray(z, &a));
  PetscCall(PetscArraycpy(a, x, m));
  if (rank_ == size_ - 1) {
    tb[0] = x[m];
    tb[1] = x[m + 1];
  }
  PetscCall(VecRestoreArray(z, &a));
  PetscCall(VecRestoreArrayRead(X, &x));
  PetscCallMPI(MPI_Bcast(tb, 2, MPIU_REAL, size_ - 1, lat_->Comm()));
  *T = tb[0];
  *beta = tb[1];
  PetscFunctionReturn(0);
}

PetscErrorCode Shooting::InDomain(Vec X, PetscBool *ok)
{
  PetscReal T, beta;
  PetscFunctionBeginUser;
  PetscCall(Unpack(X, w_, &T, &beta));
  *ok = T > 0 ? PETSC_TRUE : PETSC_FALSE;
  PetscFunctionReturn(0);
}

// Every constraint comes with the phase condition through z_ref.
PetscErrorCode Shooting::SetPhaseReference(Vec zref)
{
  PetscFunctionBeginUser;
  PetscCall(VecCopy(zref, zref_));
  PetscCall(flow_->Field(zref_, fref_));
  PetscFunctionReturn(0);
}

PetscErrorCode Shooting::SetEnergyConstraint(Vec zref, PetscReal energy)
{
  PetscFunctionBeginUser;
  PetscCall(SetPhaseReference(zref));
  kind_ = Constraint::Energy;
  energy_target_ = energy;
  PetscFunctionReturn(0);
}

PetscErrorCode Shooting::SetArclengthConstraint(Vec zref, Vec tangent, Vec Xpred)
{
  PetscFunctionBeginUser;
  PetscCall(SetPhaseReference(zref));
  PetscCall(VecCopy(tangent, tan_));
  PetscCall(VecCopy(Xpred, Xpred_));
  kind_ = Constraint::Arclength;
  PetscFunctionReturn(0);
}

PetscErrorCode Shooting::SetPeriodConstraint(Vec zref, PetscReal period)
{
  PetscFunctionBeginUser;
  PetscCall(SetPhaseReference(zref));
  kind_ = Constraint::Period;
  period_target_ = period;
  PetscFunctionReturn(0);
}

PetscErrorCode Shooting::Residual(Vec X, Vec F)
{
  PetscReal T, beta, p, c;
  PetscScalar *f;
  const PetscScalar *a, *b;
  const PetscInt m = 2 * lat_->OwnedCount();
  PetscFunctionBeginUser;
  PetscCall(CheckInterrupt(lat_->Comm())); // a stop signal ends the solve here (core/signals.hpp)
  nres_++;
  PetscCall(Unpack(X, z_, &T, &beta));
  PetscCall(flow_->Integrate(z_, T, beta, zT_));
  // phase condition and constraint (collective)
  PetscCall(VecWAXPY(w_, -1.0, zref_, z_));
  PetscCall(VecDot(fref_, w_, &p));
  if (kind_ == Constraint::Energy) {
    EnergyParts e;
    PetscCall(flow_->Effects().Energy(z_, &e));
    c = e.Total() - energy_target_;
  } else if (kind_ == Constraint::Period) {
    c = T - period_target_;
  } else {
    PetscCall(VecWAXPY(work_, -1.0, Xpred_, X));
    PetscCall(VecDot(tan_, work_, &c));
  }
  PetscCall(VecGetArray(F, &f));
  PetscCall(VecGetArrayRead(zT_, &a));
  PetscCall(VecGetArrayRead(z_, &b));
  for (PetscInt k = 0; k < m; k++) f[k] = a[k] - b[k];
  PetscCall(VecRestoreArrayRead(z_, &b));
  PetscCall(VecRestoreArrayRead(zT_, &a));
  if (rank_ == size_ - 1) {
    f[m] = p;
    f[m + 1] = c;
  }
  PetscCall(VecRestoreArray(F, &f));
  PetscFunctionReturn(0);
}

PetscErrorCode Shooting::Jacobian(Vec X, Mat J)
{
  PetscReal T, beta;
  PetscFunctionBeginUser;
  PetscCall(CheckInterrupt(lat_->Comm())); // a stop signal ends the solve here (core/signals.hpp)
  njac_++;
  PetscCall(Unpack(X, z_, &T, &beta));
  if (kind_ == Constraint::Energy) PetscCall(flow_->GradEnergy(z_, g_));
  PetscCall(GatherVec(fref_, true, &fr_));
  if (kind_ == Constraint::Energy) PetscCall(GatherVec(g_, true, &cr_));
  else if (kind_ == Constraint::Period) {
    cr_.assign(n_ + 2, 0.0);
    cr_[n_] = 1.0; // d(T - T_target)/dX
  } else PetscCall(GatherVec(tan_, true, &cr_));
  if (J == Jshell_.get()) { // matrix-free: remember the linearisation point
    PetscCall(VecCopy(z_, zlin_));
    Tlin_ = T;
    blin_ = beta;
    if (opt_.mf_pc == MatrixFreePC::Averaged || opt_.mf_pc == MatrixFreePC::Parametric) {
      kharm_.parametric = opt_.mf_pc == MatrixFreePC::Parametric;
      PetscCall(flow_->IntegrateAveragingStiffness(z_, T, beta, zT_, &kharm_));
      PetscCall(lin_pc_.SetStiffness(kharm_.d0, kharm_.o0));
      if (kharm_.parametric) PetscCall(lin_pc_.SetParametricTerm(kharm_.dc, kharm_.oc, kharm_.ds, kharm_.os, opt_.parametric_weight));
    } else PetscCall(flow_->Integrate(z_, T, beta, zT_));
    if (opt_.mf_pc != MatrixFreePC::None) PetscCall(lin_pc_.SetPeriod(T));
    PetscCall(MatAssemblyBegin(J, MAT_FINAL_ASSEMBLY));
    PetscCall(MatAssemblyEnd(J, MAT_FINAL_ASSEMBLY));
    PetscFunctionReturn(0);
  }
  PetscCall(flow_->IntegrateWithMonodromy(z_, T, beta, zT_, S_));
  PetscCall(flow_->EvalRhs(T, zT_, fT_)); // dz(T)/dT = f_beta(z(T))
  const PetscScalar *s, *ft;
  PetscInt lda, rs;
  const PetscInt m = 2 * lat_->OwnedCount(), M = n_ + 2;
  std::vector<PetscInt> cols(M);
  std::vector<PetscScalar> row(M);
  for (PetscInt c = 0; c < M; c++) cols[c] = c;
  PetscCall(MatZeroEntries(J));
  PetscCall(VecGetOwnershipRange(z_, &rs, NULL));
  PetscCall(MatDenseGetLDA(S_, &lda));
  PetscCall(MatDenseGetArrayRead(S_, &s));
  PetscCall(VecGetArrayRead(fT_, &ft));
  for (PetscInt k = 0; k < m; k++) {
    const PetscInt r = rs + k;
    for (PetscInt c = 0; c < n_; c++) row[c] = s[k + c * lda] - (r == c ? 1.0 : 0.0);
    row[n_] = ft[k];
    row[n_ + 1] = s[k + n_ * lda];
    PetscCall(MatSetValues(J, 1, &r, M, cols.data(), row.data(), INSERT_VALUES));
  }
  PetscCall(VecRestoreArrayRead(fT_, &ft));
  PetscCall(MatDenseRestoreArrayRead(S_, &s));
  PetscCall(SetBorderRows(J));
  PetscCall(MatAssemblyBegin(J, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(J, MAT_FINAL_ASSEMBLY));
  PetscFunctionReturn(0);
}

// Rows 2N (phase: f(z_ref)^T) and 2N+1 (constraint: grad E(z)^T or the
// tangent) of the dense Jacobian, from the gathered fr_ and cr_.
PetscErrorCode Shooting::SetBorderRows(Mat J)
{
  const PetscInt M = n_ + 2;
  PetscFunctionBeginUser;
  if (rank_ == size_ - 1) {
    std::vector<PetscInt> cols(M);
    std::vector<PetscScalar> row(M, 0.0);
    for (PetscInt c = 0; c < M; c++) cols[c] = c;
    PetscInt r = n_;
    for (PetscInt c = 0; c < n_; c++) row[c] = fr_[c];
    PetscCall(MatSetValues(J, 1, &r, M, cols.data(), row.data(), INSERT_VALUES));
    r = n_ + 1;
    for (PetscInt c = 0; c < M; c++) row[c] = c < (PetscInt)cr_.size() ? cr_[c] : 0.0;
    PetscCall(MatSetValues(J, 1, &r, M, cols.data(), row.data(), INSERT_VALUES));
  }
  PetscFunctionReturn(0);
}

PetscErrorCode Shooting::ShellMult(Vec x, Vec y)
{
  PetscReal dT, db, p = 0, c = 0;
  PetscScalar *yv;
  const PetscScalar *wv, *dv, *xv;
  const PetscInt m = 2 * lat_->OwnedCount();
  PetscInt rs;
  PetscFunctionBeginUser;
  PetscCall(CheckInterrupt(lat_->Comm())); // a stop signal ends the solve here (core/signals.hpp)
  nlin_++;
  PetscCall(Unpack(x, g_, &dT, &db)); // g_ as scratch for dz
  PetscCall(flow_->IntegrateWithTangent(zlin_, Tlin_, blin_, g_, db, dT, zT_, w_)); // the T column too
  // rows 2N, 2N+1: fref . dz and c_X . x, with the gathered rows
  PetscCall(VecGetOwnershipRange(x, &rs, NULL));
  PetscCall(VecGetArrayRead(x, &xv));
  PetscInt nloc;
  PetscCall(VecGetLocalSize(x, &nloc));
  PetscReal loc[2] = {0, 0}, glob[2];
  for (PetscInt k = 0; k < nloc; k++) {
    const PetscInt gi = rs + k;
    if (gi < n_) loc[0] += fr_[gi] * xv[k];
    if (gi < (PetscInt)cr_.size()) loc[1] += cr_[gi] * xv[k];
  }
  PetscCall(VecRestoreArrayRead(x, &xv));
  PetscCall(MPIU_Allreduce(loc, glob, 2, MPIU_REAL, MPIU_SUM, lat_->Comm()));
  p = glob[0];
  c = glob[1];
  PetscCall(VecGetArray(y, &yv));
  PetscCall(VecGetArrayRead(w_, &wv));
  PetscCall(VecGetArrayRead(g_, &dv));
  for (PetscInt k = 0; k < m; k++) yv[k] = wv[k] - dv[k];
  PetscCall(VecRestoreArrayRead(g_, &dv));
  PetscCall(VecRestoreArrayRead(w_, &wv));
  if (rank_ == size_ - 1) {
    yv[m] = p;
    yv[m + 1] = c;
  }
  PetscCall(VecRestoreArray(y, &yv));
  PetscFunctionReturn(0);
}

// State rows: (M_lin - I)^{-1}; the phase and constraint rows: identity.
PetscErrorCode Shooting::PCApply(Vec r, Vec x)
{
  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(Log().mf_pc, 0, 0, 0, 0));
  PetscCall(lin_pc_.Apply(r, x));
  if (rank_ == size_ - 1) {
    const PetscInt m = 2 * lat_->OwnedCount();
    const PetscScalar *ra;
    PetscScalar *xa;
    PetscCall(VecGetArrayRead(r, &ra));
    PetscCall(VecGetArray(x, &xa));
    xa[m] = ra[m];
    xa[m + 1] = ra[m + 1];
    PetscCall(VecRestoreArray(x, &xa));
    PetscCall(VecRestoreArrayRead(r, &ra));
  }
  PetscCall(PetscLogEventEnd(Log().mf_pc, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

PetscErrorCode Shooting::Converged(SNES snes, PetscInt it, PetscReal xnorm, PetscReal snorm, PetscReal fnorm, SNESConvergedReason *reason)
{
  PetscFunctionBeginUser;
  PetscCall(SNESConvergedDefault(snes, it, xnorm, snorm, fnorm, reason, NULL));
  if (opt_.orbit_rtol <= 0 || *reason != SNES_CONVERGED_ITERATING) PetscFunctionReturn(0);
  Vec X;
  const PetscScalar *x;
  PetscReal loc = 0, zz;
  PetscCall(SNESGetSolution(snes, &X));
  PetscCall(VecGetArrayRead(X, &x));
  for (PetscInt k = 0; k < 2 * lat_->OwnedCount(); k++) loc += x[k] * x[k]; // the z0 rows
  PetscCall(VecRestoreArrayRead(X, &x));
  PetscCall(MPIU_Allreduce(&loc, &zz, 1, MPIU_REAL, MPIU_SUM, lat_->Comm()));
  const PetscReal thr = std::max(snes_atol_, opt_.orbit_rtol * std::sqrt(zz));
  if (fnorm <= thr) {
    PetscCall(PetscInfo(snes, "|F| = %g <= -nnm_orbit_rtol |z0| = %g\n", (double)fnorm, (double)thr));
    *reason = SNES_CONVERGED_FNORM_ABS;
  } else if (opt_.jacobian == ShootingJacobian::MatrixFree && !ksp_atol_set_) {
    KSP ksp; // the next GMRES solve: no further than half of the threshold (see Setup)
    PetscCall(SNESGetKSP(snes, &ksp));
    PetscCall(KSPSetTolerances(ksp, PETSC_DEFAULT, 0.5 * thr, PETSC_DEFAULT, PETSC_DEFAULT));
  }
  PetscFunctionReturn(0);
}

PetscErrorCode Shooting::Solve(Vec X, bool *converged, PetscInt *its)
{
  SNESConvergedReason reason;
  // The first orbit of a branch (energy constraint) uses the start solver.
  SNES snes = (kind_ == Constraint::Energy) && snes_start_ ? snes_start_.get() : snes_.get();
  PetscFunctionBeginUser;
  const PetscInt j0 = njac_;
  PetscCall(SNESSolve(snes, NULL, X));
  fresh_ = njac_ > j0 && snes == snes_.get() && opt_.jacobian == ShootingJacobian::Dense && !snes_mf_;
  PetscCall(SNESGetConvergedReason(snes, &reason));
  PetscCall(SNESGetIterationNumber(snes, its));
  {
    PetscInt lits;
    PetscCall(SNESGetLinearSolveIterations(snes, &lits));
    nkrylov_ += lits;
  }
  *converged = reason > 0;
  reason_ = reason;
  if (!*converged) { // e.g. a zero pivot at a bifurcation: start the next factorisation afresh
    KSP ksp;
    PC pc;
    PetscCall(SNESGetKSP(snes, &ksp));
    PetscCall(KSPGetPC(ksp, &pc));
    PetscCall(PCReset(pc));
    fresh_ = false;
  }
  PetscFunctionReturn(0);
}

PetscErrorCode Shooting::Tangent(Vec X, Vec t_prev, Vec t)
{
  KSP ksp;
  PetscReal nrm, d;
  PetscFunctionBeginUser;
  // J t = e_last with the Jacobian of the last Newton iterate (already
  // factored; one step from the solution), or a new one at the solution when
  // Newton needed no iteration or the route is matrix-free.
  PetscCall(SNESGetKSP(snes_, &ksp));
  if (snes_mf_) { // -nnm_snes_mf: the finite-difference operator, based at the solution
    Mat A;
    PetscCall(SNESGetJacobian(snes_, &A, NULL, NULL, NULL));
    PetscCall(SNESComputeFunction(snes_, X, F_));
    PetscCall(MatMFFDSetBase(A, X, F_));
    PetscCall(KSPSetOperators(ksp, A, A));
  } else if (!fresh_) {
    Mat J = opt_.jacobian == ShootingJacobian::Dense ? Jdense_.get() : Jshell_.get();
    PetscCall(Jacobian(X, J));
    PetscCall(KSPSetOperators(ksp, J, J));
  }
  PetscCall(VecZeroEntries(work_));
  if (rank_ == size_ - 1) PetscCall(VecSetValue(work_, n_ + 1, 1.0, INSERT_VALUES));
  PetscCall(VecAssemblyBegin(work_));
  PetscCall(VecAssemblyEnd(work_));
  PetscReal rtol, atol, dtol;
  PetscInt maxit;
  PetscCall(KSPGetTolerances(ksp, &rtol, &atol, &dtol, &maxit)); // the last Eisenstat-Walker forcing term: too loose for the predictor
  PetscCall(KSPSetTolerances(ksp, tangent_rtol_, atol, dtol, maxit));
  PetscCall(KSPSolve(ksp, work_, t));
  PetscCall(KSPSetTolerances(ksp, rtol, atol, dtol, maxit));
  if (opt_.jacobian == ShootingJacobian::MatrixFree) {
    PetscInt lits;
    PetscCall(KSPGetIterationNumber(ksp, &lits));
    nkrylov_ += lits;
  }
  PetscCall(VecNormalize(t, &nrm));
  if (t_prev) {
    PetscCall(VecDot(t, t_prev, &d));
    if (d < 0) PetscCall(VecScale(t, -1.0));
  }
  PetscFunctionReturn(0);
}

} // namespace nltopo
