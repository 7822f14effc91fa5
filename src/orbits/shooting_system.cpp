#include "orbits/shooting_system.hpp"
#include "core/gather.hpp"
#include "core/memory_guard.hpp"
#include "core/signals.hpp"
#include <cmath>

namespace nltopo {

namespace {
PetscErrorCode ShootShellMult(Mat A, Vec x, Vec y)
{
  ShootingSystem *s;
  PetscFunctionBeginUser;
  PetscCall(MatShellGetContext(A, &s));
  PetscCall(s->ShellMult(x, y));
  PetscFunctionReturn(0);
}
} // namespace

PetscErrorCode ShootingSystem::Setup(PeriodicFlow &flow)
{
  PetscFunctionBeginUser;
  flow_ = &flow;
  lat_ = &flow.Lat();
  PetscCallMPI(MPI_Comm_rank(lat_->Comm(), &rank_));
  PetscCallMPI(MPI_Comm_size(lat_->Comm(), &size_));
  n_ = 2 * lat_->N();
  nlocx_ = 2 * lat_->OwnedCount() + (rank_ == size_ - 1 ? 2 : 0);
  PetscCall(lat_->CreateStateVector(z_.out()));
  for (OwnedVec *v : {&zT_, &fref_, &zref_, &g_, &w_, &zlin_, &fT_}) PetscCall(VecDuplicate(z_, v->out()));
  PetscCall(CreateUnknowns(tan_.out()));
  PetscCall(VecDuplicate(tan_, Xpred_.out()));
  PetscCall(VecDuplicate(tan_, work_.out()));
  PetscFunctionReturn(0);
}

PetscErrorCode ShootingSystem::CreateUnknowns(Vec *X) const
{
  PetscFunctionBeginUser;
  PetscCall(VecCreateMPI(lat_->Comm(), nlocx_, n_ + 2, X));
  PetscFunctionReturn(0);
}

// X's state entries have the state vector's global indices; T and beta are 2N, 2N+1 (last rank).
PetscErrorCode ShootingSystem::Pack(Vec z, PetscReal T, PetscReal beta, Vec X) const
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

PetscErrorCode ShootingSystem::Unpack(Vec X, Vec z, PetscReal *T, PetscReal *beta) const
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

PetscErrorCode ShootingSystem::CopyBorder(Vec x, Vec y) const
{
  PetscFunctionBeginUser;
  if (rank_ == size_ - 1) {
    const PetscInt m = 2 * lat_->OwnedCount();
    const PetscScalar *xa;
    PetscScalar *ya;
    PetscCall(VecGetArrayRead(x, &xa));
    PetscCall(VecGetArray(y, &ya));
    ya[m] = xa[m];
    ya[m + 1] = xa[m + 1];
    PetscCall(VecRestoreArray(y, &ya));
    PetscCall(VecRestoreArrayRead(x, &xa));
  }
  PetscFunctionReturn(0);
}

PetscErrorCode ShootingSystem::StateNorm(Vec X, PetscReal *norm) const
{
  const PetscScalar *x;
  PetscReal loc = 0, zz;
  PetscFunctionBeginUser;
  PetscCall(VecGetArrayRead(X, &x));
  for (PetscInt k = 0; k < 2 * lat_->OwnedCount(); k++) loc += x[k] * x[k]; // the z0 rows
  PetscCall(VecRestoreArrayRead(X, &x));
  PetscCall(MPIU_Allreduce(&loc, &zz, 1, MPIU_REAL, MPIU_SUM, lat_->Comm()));
  *norm = std::sqrt(zz);
  PetscFunctionReturn(0);
}

PetscErrorCode ShootingSystem::InDomain(Vec X, PetscBool *ok)
{
  PetscReal T, beta;
  PetscFunctionBeginUser;
  PetscCall(Unpack(X, w_, &T, &beta));
  *ok = T > 0 ? PETSC_TRUE : PETSC_FALSE;
  PetscFunctionReturn(0);
}

PetscErrorCode ShootingSystem::SetPhaseReference(Vec zref)
{
  PetscFunctionBeginUser;
  PetscCall(VecCopy(zref, zref_));
  PetscCall(flow_->Field(zref_, fref_));
  PetscFunctionReturn(0);
}

PetscErrorCode ShootingSystem::SetTargetConstraint(Vec zref, Constraint kind, PetscReal target)
{
  PetscFunctionBeginUser;
  PetscCall(SetPhaseReference(zref));
  kind_ = kind;
  target_ = target;
  PetscFunctionReturn(0);
}

PetscErrorCode ShootingSystem::SetArclengthConstraint(Vec zref, Vec tangent, Vec Xpred)
{
  PetscFunctionBeginUser;
  PetscCall(SetPhaseReference(zref));
  PetscCall(VecCopy(tangent, tan_));
  PetscCall(VecCopy(Xpred, Xpred_));
  kind_ = Constraint::Arclength;
  PetscFunctionReturn(0);
}

PetscErrorCode ShootingSystem::Residual(Vec X, Vec F)
{
  PetscReal T, beta, p, c;
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
    c = e.Total() - target_;
  } else if (kind_ == Constraint::Period) {
    c = T - target_;
  } else {
    PetscCall(VecWAXPY(work_, -1.0, Xpred_, X));
    PetscCall(VecDot(tan_, work_, &c));
  }
  PetscCall(SetRows(zT_, z_, p, c, F));
  PetscFunctionReturn(0);
}

// y = [a - b; p; c]: the state rows from state vectors, the phase and constraint rows.
PetscErrorCode ShootingSystem::SetRows(Vec a, Vec b, PetscReal p, PetscReal c, Vec y) const
{
  PetscScalar *yv;
  const PetscScalar *av, *bv;
  const PetscInt m = 2 * lat_->OwnedCount();
  PetscFunctionBeginUser;
  PetscCall(VecGetArray(y, &yv));
  PetscCall(VecGetArrayRead(a, &av));
  PetscCall(VecGetArrayRead(b, &bv));
  for (PetscInt k = 0; k < m; k++) yv[k] = av[k] - bv[k];
  PetscCall(VecRestoreArrayRead(b, &bv));
  PetscCall(VecRestoreArrayRead(a, &av));
  if (rank_ == size_ - 1) {
    yv[m] = p;
    yv[m + 1] = c;
  }
  PetscCall(VecRestoreArray(y, &yv));
  PetscFunctionReturn(0);
}

PetscErrorCode CheckDenseJacobianMemory(MPI_Comm comm, PetscInt sites, PetscInt local_rows)
{
  const double M = 2.0 * (double)sites + 2.0;
  PetscFunctionBeginUser;
  // Dense-pattern AIJ (12 bytes per entry) plus the sensitivity matrix and MUMPS's factor.
  PetscCall(CheckMemory(comm, 4.0 * 12.0 * M * (double)local_rows, "the dense shooting Jacobian (2N = -lattice_cells x 4; -nnm_jacobian mf avoids it)"));
  PetscFunctionReturn(0);
}

PetscErrorCode ShootingSystem::CreateDenseJacobian(Mat *J)
{
  MPI_Comm comm = lat_->Comm();
  const PetscInt M = n_ + 2;
  PetscFunctionBeginUser;
  PetscCall(CheckDenseJacobianMemory(comm, lat_->N(), nlocx_));
  if (!S_) PetscCall(flow_->CreateSensitivityMatrix(S_.out()));
  PetscCall(MatCreateAIJ(comm, nlocx_, nlocx_, M, M, nlocx_, NULL, M - nlocx_, NULL, J)); // dense pattern
  PetscFunctionReturn(0);
}

PetscErrorCode ShootingSystem::CreateShellJacobian(Mat *J)
{
  const PetscInt M = n_ + 2;
  PetscFunctionBeginUser;
  PetscCall(MatCreateShell(lat_->Comm(), nlocx_, nlocx_, M, M, this, J));
  PetscCall(MatShellSetOperation(*J, MATOP_MULT, (void (*)(void))ShootShellMult));
  PetscFunctionReturn(0);
}

// Both Jacobians: the state at X and the gathered phase row f(z_ref)^T and
// constraint row (grad E(z0)^T, e_T^T or the tangent).
PetscErrorCode ShootingSystem::GatherBorderRows(Vec X, PetscReal *T, PetscReal *beta)
{
  PetscFunctionBeginUser;
  PetscCall(CheckInterrupt(lat_->Comm())); // a stop signal ends the solve here (core/signals.hpp)
  PetscCall(Unpack(X, z_, T, beta));
  if (kind_ == Constraint::Energy) PetscCall(flow_->GradEnergy(z_, g_));
  PetscCall(GatherVec(fref_, true, &fr_));
  if (kind_ == Constraint::Energy) PetscCall(GatherVec(g_, true, &cr_));
  else if (kind_ == Constraint::Period) {
    PetscCallCXX(cr_.assign(n_ + 2, 0.0));
    cr_[n_] = 1.0; // d(T - T_target)/dX
  } else PetscCall(GatherVec(tan_, true, &cr_));
  PetscFunctionReturn(0);
}

PetscErrorCode ShootingSystem::Linearise(Vec X)
{
  PetscFunctionBeginUser;
  njac_++;
  PetscCall(GatherBorderRows(X, &Tlin_, &blin_));
  PetscCall(VecCopy(z_, zlin_));
  PetscFunctionReturn(0);
}

PetscErrorCode ShootingSystem::AssembleJacobian(Vec X, Mat J)
{
  PetscReal T, beta;
  PetscFunctionBeginUser;
  njac_++;
  PetscCall(GatherBorderRows(X, &T, &beta));
  PetscCall(flow_->IntegrateWithMonodromy(z_, T, beta, zT_, S_));
  PetscCall(flow_->EvalRhs(T, zT_, fT_)); // dz(T)/dT = f_beta(z(T))
  PetscCall(FillJacobian(S_, J));
  PetscFunctionReturn(0);
}

PetscErrorCode ShootingSystem::AssembleJacobianFrom(Vec X, Mat S, Mat J)
{
  PetscReal T, beta;
  PetscFunctionBeginUser;
  PetscCall(GatherBorderRows(X, &T, &beta));
  PetscCall(flow_->Integrate(z_, T, beta, zT_));
  PetscCall(flow_->EvalRhs(T, zT_, fT_));
  PetscCall(FillJacobian(S, J));
  PetscFunctionReturn(0);
}

PetscErrorCode ShootingSystem::FillJacobian(Mat S, Mat J)
{
  PetscFunctionBeginUser;
  const PetscScalar *s, *ft;
  PetscInt lda, rs;
  const PetscInt m = 2 * lat_->OwnedCount(), M = n_ + 2;
  std::vector<PetscInt> cols;
  std::vector<PetscScalar> row;
  PetscCallCXX(cols.resize(M));
  PetscCallCXX(row.resize(M));
  for (PetscInt c = 0; c < M; c++) cols[c] = c;
  PetscCall(MatZeroEntries(J));
  PetscCall(VecGetOwnershipRange(z_, &rs, NULL));
  PetscCall(MatDenseGetLDA(S, &lda));
  PetscCall(MatDenseGetArrayRead(S, &s));
  PetscCall(VecGetArrayRead(fT_, &ft));
  for (PetscInt k = 0; k < m; k++) {
    const PetscInt r = rs + k;
    for (PetscInt c = 0; c < n_; c++) row[c] = s[k + c * lda] - (r == c ? 1.0 : 0.0);
    row[n_] = ft[k];
    row[n_ + 1] = s[k + n_ * lda];
    PetscCall(MatSetValues(J, 1, &r, M, cols.data(), row.data(), INSERT_VALUES));
  }
  PetscCall(VecRestoreArrayRead(fT_, &ft));
  PetscCall(MatDenseRestoreArrayRead(S, &s));
  PetscCall(SetBorderRows(J));
  PetscCall(MatAssemblyBegin(J, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(J, MAT_FINAL_ASSEMBLY));
  PetscFunctionReturn(0);
}

// Rows 2N (phase: f(z_ref)^T) and 2N+1 (constraint) of the assembled Jacobian,
// from the gathered fr_ and cr_.
PetscErrorCode ShootingSystem::SetBorderRows(Mat J)
{
  const PetscInt M = n_ + 2;
  PetscFunctionBeginUser;
  if (rank_ == size_ - 1) {
    std::vector<PetscInt> cols;
    std::vector<PetscScalar> row;
    PetscCallCXX(cols.resize(M));
    PetscCallCXX(row.assign(M, 0.0));
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

// y = J x at the linearisation point: one tangent-linear integration for the
// state rows (T column included), the gathered rows for the phase and constraint.
PetscErrorCode ShootingSystem::ShellMult(Vec x, Vec y)
{
  PetscReal dT, db;
  const PetscScalar *xv;
  PetscInt rs;
  PetscFunctionBeginUser;
  PetscCall(CheckInterrupt(lat_->Comm())); // a stop signal ends the solve here (core/signals.hpp)
  nlin_++;
  PetscCall(Unpack(x, g_, &dT, &db));                                               // g_ as scratch for dz
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
  PetscCall(SetRows(w_, g_, glob[0], glob[1], y)); // state rows: w - dz = (M - I) dz + the T and beta columns
  PetscFunctionReturn(0);
}

} // namespace nltopo
