#include "orbits/variational_symplectic.hpp"
#include "core/cost.hpp"
#include "core/log.hpp"
#include "orbits/period_ts.hpp"
#include "timeint/ts_symsplit.hpp"

namespace nltopo {

namespace {
PetscErrorCode SymVarAcceleration(TS, PetscReal, Vec Y, PetscScalar *A, void *ctx)
{
  PetscFunctionBeginUser;
  CostCountEvaluations(1);
  PetscCall(static_cast<SymplecticVariationalFlow *>(ctx)->Acceleration(Y, A));
  PetscFunctionReturn(0);
}

// The first-order form [q' = p, p' = A(q)] (what any TS would integrate; the
// symsplit type reads the acceleration directly).
PetscErrorCode SymVarRhs(TS ts, PetscReal, Vec Y, Vec F, void *ctx)
{
  const PetscScalar *y;
  PetscScalar *f;
  PetscInt nl;
  PetscFunctionBeginUser;
  PetscCall(VecGetLocalSize(Y, &nl));
  PetscCall(VecGetArrayRead(Y, &y));
  PetscCall(VecGetArray(F, &f));
  for (PetscInt k = 0; k < nl / 2; k++) f[k] = y[nl / 2 + k];
  PetscCall(VecRestoreArrayRead(Y, &y));
  PetscCall(VecRestoreArray(F, &f));
  PetscCall(static_cast<SymplecticVariationalFlow *>(ctx)->Acceleration(Y, f + nl / 2));
  PetscFunctionReturn(0);
}
} // namespace

PetscErrorCode SymplecticVariationalFlow::Setup(const EffectList &fx, PetscInt ncol, PetscInt steps)
{
  const Lattice &lat = fx.Lat();
  const PetscInt xs = lat.OwnedStart(), xm = lat.OwnedCount();
  PetscFunctionBeginUser;
  PetscCall(fx.RequireConservative("the symplectic periodic-orbit flow"));
  PetscCall(fx.RequirePositionOnly("the symplectic periodic-orbit flow"));
  fx_ = &fx;
  lat_ = &lat;
  ncol_ = ncol;
  bs_ = 1 + ncol;
  steps_ = steps;
  PetscCall(VecCreateMPI(lat.Comm(), 2 * bs_ * xm, PETSC_DETERMINE, Y_.out()));
  if (!lat.Serial()) { // the q blocks of sites xs-1 (last of the left rank) and xs+xm (first of the right one)
    const PetscInt *ranges;
    PetscMPIInt rank, size;
    PetscCallMPI(MPI_Comm_rank(lat.Comm(), &rank));
    PetscCallMPI(MPI_Comm_size(lat.Comm(), &size));
    PetscCall(VecGetOwnershipRanges(Y_, &ranges));
    std::vector<PetscInt> from, to;
    if (xs > 0) {
      const PetscInt start = ranges[rank - 1] + bs_ * ((ranges[rank] - ranges[rank - 1]) / (2 * bs_) - 1); // its q half holds its sites' blocks
      for (PetscInt c = 0; c < bs_; c++) from.push_back(start + c), to.push_back(c);
    }
    if (xs + xm < lat.N())
      for (PetscInt c = 0; c < bs_; c++) from.push_back(ranges[rank + 1] + c), to.push_back(bs_ + c);
    IS isf, ist;
    PetscCall(VecCreateSeq(PETSC_COMM_SELF, 2 * bs_, ghost_.out()));
    PetscCall(ISCreateGeneral(PETSC_COMM_SELF, (PetscInt)from.size(), from.data(), PETSC_COPY_VALUES, &isf));
    PetscCall(ISCreateGeneral(PETSC_COMM_SELF, (PetscInt)to.size(), to.data(), PETSC_COPY_VALUES, &ist));
    PetscCall(VecScatterCreate(Y_, isf, ghost_, ist, to_ghost_.out()));
    PetscCall(ISDestroy(&isf));
    PetscCall(ISDestroy(&ist));
  }
  PetscCall(CreatePeriodTS(lat.Comm(), TSSYMSPLIT, SymVarRhs, this, ts_.out()));
  PetscCall(TSSetAcceleration(ts_, SymVarAcceleration, this));
  PetscCall(TSSetFromOptions(ts_));
  u_.assign(lat.N(), 0.0);
  a_.assign(lat.N(), 0.0);
  kd_.assign(lat.N(), 0.0);
  kb_.assign(lat.N() + 1, 0.0);
  A_.assign(bs_ * xm, 0.0);
  PetscFunctionReturn(0);
}

PetscErrorCode SymplecticVariationalFlow::Acceleration(Vec Y, PetscScalar *A)
{
  const PetscScalar *q, *g = NULL;
  const PetscInt xs = lat_->OwnedStart(), xm = lat_->OwnedCount(), N = lat_->N(), nc = ncol_, bs = bs_;
  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(Log().variational, 0, 0, 0, 0));
  if (to_ghost_) {
    PetscCall(VecScatterBegin(to_ghost_, Y, ghost_, INSERT_VALUES, SCATTER_FORWARD));
    PetscCall(VecScatterEnd(to_ghost_, Y, ghost_, INSERT_VALUES, SCATTER_FORWARD));
    PetscCall(VecGetArrayRead(ghost_, &g));
  }
  PetscCall(VecGetArrayRead(Y, &q)); // the q half: site blocks (u_i, W_u,i)
  for (PetscInt k = 0; k < xm; k++) u_[xs + k] = q[bs * k];
  if (g && xs > 0) u_[xs - 1] = g[0];
  if (g && xs + xm < N) u_[xs + xm] = g[bs];
  PetscCall(fx_->Acceleration(0, u_.data(), NULL, a_.data()));
  const PetscScalar *kb = kb_.data() + 1; // kb[b]: K_T(b, b+1), 0 outside the chain
  fx_->Stiffness(u_.data(), kd_.data(), kb_.data() + 1);
  for (PetscInt k = 0; k < xm; k++) {
    const PetscInt i = xs + k;
    const PetscScalar c[3] = {kb[i - 1], kd_[i], kb[i]}; // row i of K_T
    const PetscScalar *W = q + bs * k + 1;
    const PetscScalar *Wl = i == 0 ? W : (k > 0 ? W - bs : g + 1); // c[0] = 0 at the chain's ends
    const PetscScalar *Wr = i == N - 1 ? W : (k < xm - 1 ? W + bs : g + bs + 1);
    PetscScalar *Ak = A + bs * k;
    Ak[0] = a_[i];
    PetscScalar *AW = Ak + 1;
    const PetscScalar c0 = c[0], c1 = c[1], c2 = c[2];
    for (PetscInt j = 0; j < nc; j++) AW[j] = -(c0 * Wl[j] + c1 * W[j] + c2 * Wr[j]);
    if (s_ != 0) AW[nc - 1] += 2 * s_ * a_[i]; // the T source (header)
  }
  PetscCall(VecRestoreArrayRead(Y, &q));
  if (g) PetscCall(VecRestoreArrayRead(ghost_, &g));
  PetscCall(PetscLogFlops(6.0 * nc * xm));
  PetscCall(PetscLogEventEnd(Log().variational, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

PetscErrorCode SymplecticVariationalFlow::Integrate(Vec z0, PetscReal T, PetscReal beta, Vec dz, PetscReal s_beta, PetscReal s_T, Vec zT, Mat S, Vec w)
{
  const PetscScalar *z, *dza = NULL;
  PetscScalar *y;
  const PetscInt xs = lat_->OwnedStart(), xm = lat_->OwnedCount(), nc = ncol_, bs = bs_, half = bs_ * xm;
  PetscFunctionBeginUser;
  PetscCheck(dz ? nc == 1 : (s_beta == 1 && s_T == 0), lat_->Comm(), PETSC_ERR_PLIB, "symplectic variational flow: %" PetscInt_FMT " columns for this use", nc);
  s_ = dz ? s_T / T : 0.0;
  PetscCall(VecGetArrayRead(z0, &z));
  if (dz) PetscCall(VecGetArrayRead(dz, &dza));
  PetscCall(VecGetArray(Y_, &y));
  PetscCall(PetscArrayzero(y, 2 * half));
  for (PetscInt k = 0; k < xm; k++) {
    PetscScalar *q = y + bs * k, *p = y + half + bs * k;
    q[0] = z[k];
    p[0] = z[xm + k];
    if (dza) {
      q[1] = dza[k];
      p[1] = dza[xm + k] + s_ * z[xm + k]; // P = W_v + s v
    } else {                               // identity on the state columns
      q[1 + lat_->StateIndexU(xs + k)] = 1.0;
      p[1 + lat_->StateIndexV(xs + k)] = 1.0;
    }
  }
  PetscCall(VecRestoreArray(Y_, &y));
  if (dz) PetscCall(VecRestoreArrayRead(dz, &dza));
  PetscCall(VecRestoreArrayRead(z0, &z));

  PetscCall(SolvePeriod(ts_, Y_, T, steps_, "variational"));

  // B_beta at the end: z + beta T grad E(z), derivative I + beta T Hess E, Hess E = diag(K_T(u), I).
  const PetscReal sT = s_;
  s_ = 0;
  PetscCall(Acceleration(Y_, A_.data())); // a(u_T) and -K_T(u_T) W_u
  const PetscScalar *ya;
  PetscScalar *zt;
  const PetscReal bT = beta * T;
  PetscCall(VecGetArrayRead(Y_, &ya));
  PetscCall(VecGetArray(zT, &zt));
  for (PetscInt k = 0; k < xm; k++) {
    const PetscScalar a = A_[bs * k], v = ya[half + bs * k];
    zt[k] = ya[bs * k] - bT * a;
    zt[xm + k] = v + bT * v;
  }
  PetscCall(VecRestoreArray(zT, &zt));
  if (S) {
    PetscScalar *s;
    PetscInt lda;
    PetscCall(MatDenseGetLDA(S, &lda));
    PetscCall(MatDenseGetArrayWrite(S, &s));
    for (PetscInt k = 0; k < xm; k++) {
      const PetscScalar *Wu = ya + bs * k + 1, *Wv = ya + half + bs * k + 1, *AW = A_.data() + bs * k + 1;
      for (PetscInt c = 0; c < nc; c++) {
        s[k + c * lda] = Wu[c] - bT * AW[c];
        s[xm + k + c * lda] = (1 + bT) * Wv[c];
      }
      s[k + nc * lda] = -T * A_[bs * k]; // the beta column: T grad E(z_T)
      s[xm + k + nc * lda] = T * ya[half + bs * k];
    }
    PetscCall(MatDenseRestoreArrayWrite(S, &s));
  }
  if (w) {
    PetscScalar *wd;
    const PetscReal g = s_beta * T + beta * sT * T; // along grad E(z_T): d(beta T)
    PetscCall(VecGetArray(w, &wd));
    for (PetscInt k = 0; k < xm; k++) {
      const PetscScalar a = A_[bs * k], v = ya[half + bs * k];
      const PetscScalar Wu = ya[bs * k + 1], Wv = ya[half + bs * k + 1] - sT * v;
      wd[k] = Wu - bT * A_[bs * k + 1] - g * a;
      wd[xm + k] = (1 + bT) * Wv + g * v;
    }
    PetscCall(VecRestoreArray(w, &wd));
  }
  PetscCall(VecRestoreArrayRead(Y_, &ya));
  PetscFunctionReturn(0);
}

PetscErrorCode SymplecticVariationalFlow::IntegrateBlock(Vec z0, PetscReal T, PetscReal beta, const std::vector<Vec> &dz, Vec zT, const std::vector<Vec> &w)
{
  const PetscInt xm = lat_->OwnedCount(), nc = ncol_, bs = bs_, half = bs_ * xm;
  const PetscReal bT = beta * T;
  const PetscScalar *z, *ya;
  PetscScalar *y, *zt;
  PetscFunctionBeginUser;
  PetscCheck((PetscInt)dz.size() == nc && (PetscInt)w.size() == nc, lat_->Comm(), PETSC_ERR_PLIB,
             "symplectic variational flow: %zu start vectors and %zu results for a block of %" PetscInt_FMT " columns", dz.size(), w.size(), nc);
  s_ = 0; // no T source: P = W_v
  PetscCall(VecGetArrayRead(z0, &z));
  PetscCall(VecGetArray(Y_, &y));
  for (PetscInt k = 0; k < xm; k++) {
    y[bs * k] = z[k];
    y[half + bs * k] = z[xm + k];
  }
  for (PetscInt j = 0; j < nc; j++) { // column j of every site block
    const PetscScalar *d;
    PetscCall(VecGetArrayRead(dz[j], &d));
    for (PetscInt k = 0; k < xm; k++) {
      y[bs * k + 1 + j] = d[k];
      y[half + bs * k + 1 + j] = d[xm + k];
    }
    PetscCall(VecRestoreArrayRead(dz[j], &d));
  }
  PetscCall(VecRestoreArray(Y_, &y));
  PetscCall(VecRestoreArrayRead(z0, &z));

  PetscCall(SolvePeriod(ts_, Y_, T, steps_, "variational"));

  PetscCall(Acceleration(Y_, A_.data())); // a(u_T) and -K_T(u_T) W_u: B_beta and its derivative (Integrate)
  PetscCall(VecGetArrayRead(Y_, &ya));
  PetscCall(VecGetArray(zT, &zt));
  for (PetscInt k = 0; k < xm; k++) {
    const PetscScalar v = ya[half + bs * k];
    zt[k] = ya[bs * k] - bT * A_[bs * k];
    zt[xm + k] = v + bT * v;
  }
  PetscCall(VecRestoreArray(zT, &zt));
  for (PetscInt j = 0; j < nc; j++) {
    PetscScalar *wd;
    PetscCall(VecGetArray(w[j], &wd));
    for (PetscInt k = 0; k < xm; k++) {
      wd[k] = ya[bs * k + 1 + j] - bT * A_[bs * k + 1 + j];
      wd[xm + k] = (1 + bT) * ya[half + bs * k + 1 + j];
    }
    PetscCall(VecRestoreArray(w[j], &wd));
  }
  PetscCall(VecRestoreArrayRead(Y_, &ya));
  PetscFunctionReturn(0);
}

} // namespace nltopo
