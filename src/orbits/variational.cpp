#include "orbits/variational.hpp"
#include "core/cost.hpp"
#include "orbits/period_ts.hpp"
#include "core/log.hpp"
#include <petscdmda.h>

namespace nltopo {

namespace {
PetscErrorCode VarRhs(TS ts, PetscReal t, Vec Y, Vec F, void *ctx)
{
  PetscFunctionBeginUser;
  CostCountEvaluations(1);
  PetscCall(static_cast<VariationalFlow *>(ctx)->Rhs(t, Y, F));
  PetscFunctionReturn(0);
}
} // namespace

PetscErrorCode VariationalFlow::Setup(const EffectList &fx, PetscInt ncol, PetscInt steps)
{
  const Lattice &lat = fx.Lat();
  const PetscInt *lx;
  PetscMPIInt size;
  PetscFunctionBeginUser;
  PetscCall(fx.RequireConservative("the periodic-orbit flow"));
  fx_ = &fx;
  lat_ = &lat;
  ncol_ = ncol;
  dof_ = 2 + 2 * ncol;
  steps_ = steps;
  PetscCallMPI(MPI_Comm_size(lat.Comm(), &size));
  PetscCall(DMDAGetOwnershipRanges(lat.SiteDM(), &lx, NULL, NULL));
  std::vector<PetscInt> l(lx, lx + size);
  PetscCall(DMDACreate1d(lat.Comm(), DM_BOUNDARY_NONE, lat.N(), dof_, 1, l.data(), da_.out()));
  PetscCall(DMSetUp(da_));
  PetscCall(DMCreateGlobalVector(da_, Y_.out()));
  PetscCall(CreatePeriodTS(lat.Comm(), TSRK, VarRhs, this, ts_.out())); // the rk route's variational flow (-nnm_ts_type rk)
  PetscCall(TSSetFromOptions(ts_));
  u_.assign(lat.N(), 0.0);
  a_.assign(lat.N(), 0.0);
  kd_.assign(lat.N(), 0.0);
  kb_.assign(lat.N() + 1, 0.0);
  PetscFunctionReturn(0);
}

PetscErrorCode VariationalFlow::Rhs(PetscReal t, Vec Y, Vec F)
{
  Vec Yl;
  const PetscScalar *y;
  PetscScalar *f;
  PetscInt gxs, gxm;
  const PetscInt xs = lat_->OwnedStart(), xm = lat_->OwnedCount(), N = lat_->N(), nc = ncol_, d = dof_;
  const PetscReal b = beta_, sb = src_beta_, sf = src_f_;
  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(Log().variational, 0, 0, 0, 0));
  if (lat_->Serial()) { // one rank: the global array holds every neighbour (no ghost copy of Y)
    Yl = Y;
    gxs = 0;
    gxm = N;
  } else {
    PetscCall(DMGetLocalVector(da_, &Yl));
    PetscCall(DMGlobalToLocalBegin(da_, Y, INSERT_VALUES, Yl));
    PetscCall(DMGlobalToLocalEnd(da_, Y, INSERT_VALUES, Yl));
    PetscCall(DMDAGetGhostCorners(da_, &gxs, NULL, NULL, &gxm, NULL, NULL));
  }
  PetscCall(VecGetArrayRead(Yl, &y));
  PetscCall(VecGetArray(F, &f));
  const PetscScalar *yb = y - d * gxs; // block of site i at yb + d i
  for (PetscInt i = gxs; i < gxs + gxm; i++) u_[i] = yb[d * i];
  PetscCall(fx_->Acceleration(t, u_.data(), NULL, a_.data()));
  const PetscScalar *kb = kb_.data() + 1; // kb[b]: K_T(b, b+1), 0 outside the chain
  fx_->Stiffness(u_.data(), kd_.data(), kb_.data() + 1);
  for (PetscInt i = xs; i < xs + xm; i++) {
    const PetscScalar *yi = yb + d * i;
    PetscScalar *fi = f + d * (i - xs);
    const PetscScalar du = yi[1], dv = a_[i];
    fi[0] = du - b * dv;
    fi[1] = dv + b * du;
    const PetscScalar c[3] = {kb[i - 1], kd_[i], kb[i]}; // row i of K_T
    const PetscScalar *Wu = yi + 2, *Wv = yi + 2 + nc;
    const PetscScalar *Wl = i > 0 ? yb + d * (i - 1) + 2 : Wu; // neighbours' Wu (unused at the ends: c = 0)
    const PetscScalar *Wr = i < N - 1 ? yb + d * (i + 1) + 2 : Wu;
    PetscScalar *Fu = fi + 2, *Fv = fi + 2 + nc;
    for (PetscInt k = 0; k < nc; k++) {
      const PetscScalar pu = Wv[k], pv = -(c[0] * Wl[k] + c[1] * Wu[k] + c[2] * Wr[k]);
      Fu[k] = pu - b * pv;
      Fv[k] = pv + b * pu;
    }
    Fu[nc - 1] += sb * (-dv) + sf * fi[0]; // d f_beta / d beta = grad E = [-a, v]; f_beta / T
    Fv[nc - 1] += sb * du + sf * fi[1];
  }
  PetscCall(VecRestoreArray(F, &f));
  PetscCall(VecRestoreArrayRead(Yl, &y));
  if (Yl != Y) PetscCall(DMRestoreLocalVector(da_, &Yl));
  PetscCall(PetscLogFlops(8.0 * nc * xm));
  PetscCall(PetscLogEventEnd(Log().variational, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

PetscErrorCode VariationalFlow::Integrate(Vec z0, PetscReal T, PetscReal beta, Vec dz, PetscReal s_beta, PetscReal s_T, Vec zT, Mat S, Vec w)
{
  const PetscScalar *z, *dza = NULL;
  PetscScalar *y;
  const PetscInt xs = lat_->OwnedStart(), xm = lat_->OwnedCount(), nc = ncol_, d = dof_;
  PetscFunctionBeginUser;
  PetscCheck(dz ? nc == 1 : (s_beta == 1 && s_T == 0), lat_->Comm(), PETSC_ERR_PLIB, "variational flow: %" PetscInt_FMT " columns for this use", nc);
  beta_ = beta;
  src_beta_ = s_beta;
  src_f_ = s_T / T;
  PetscCall(VecGetArrayRead(z0, &z));
  if (dz) PetscCall(VecGetArrayRead(dz, &dza));
  PetscCall(VecGetArray(Y_, &y));
  for (PetscInt k = 0; k < xm; k++) {
    PetscScalar *yi = y + d * k;
    const PetscInt i = xs + k;
    yi[0] = z[k];
    yi[1] = z[xm + k];
    PetscCall(PetscArrayzero(yi + 2, 2 * nc));
    if (dza) {
      yi[2] = dza[k];
      yi[2 + nc] = dza[xm + k];
    } else { // identity on the state columns
      yi[2 + lat_->StateIndexU(i)] = 1.0;
      yi[2 + nc + lat_->StateIndexV(i)] = 1.0;
    }
  }
  PetscCall(VecRestoreArray(Y_, &y));
  if (dz) PetscCall(VecRestoreArrayRead(dz, &dza));
  PetscCall(VecRestoreArrayRead(z0, &z));

  PetscCall(SolvePeriod(ts_, Y_, T, steps_, "variational"));

  const PetscScalar *ya;
  PetscScalar *zt;
  PetscCall(VecGetArrayRead(Y_, &ya));
  PetscCall(VecGetArray(zT, &zt));
  for (PetscInt k = 0; k < xm; k++) {
    zt[k] = ya[d * k];
    zt[xm + k] = ya[d * k + 1];
  }
  PetscCall(VecRestoreArray(zT, &zt));
  if (S) {
    PetscScalar *s;
    PetscInt lda;
    PetscCall(MatDenseGetLDA(S, &lda));
    PetscCall(MatDenseGetArrayWrite(S, &s));
    for (PetscInt k = 0; k < xm; k++) {
      const PetscScalar *yi = ya + d * k;
      for (PetscInt c = 0; c < nc; c++) {
        s[k + c * lda] = yi[2 + c];
        s[xm + k + c * lda] = yi[2 + nc + c];
      }
    }
    PetscCall(MatDenseRestoreArrayWrite(S, &s));
  }
  if (w) { // the one tangent column
    PetscScalar *wd;
    PetscCall(VecGetArray(w, &wd));
    for (PetscInt k = 0; k < xm; k++) {
      wd[k] = ya[d * k + 2];
      wd[xm + k] = ya[d * k + 3];
    }
    PetscCall(VecRestoreArray(w, &wd));
  }
  PetscCall(VecRestoreArrayRead(Y_, &ya));
  PetscFunctionReturn(0);
}

} // namespace nltopo
