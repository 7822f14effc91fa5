#include "lattice/lattice.hpp"
#include "core/memory_guard.hpp"
#include "core/log.hpp"
#include <algorithm>
#include <petscdmda.h>

namespace nltopo {

PetscErrorCode Lattice::Setup(MPI_Comm comm, const LatticeParams &p)
{
  const PetscInt *lx;
  PetscFunctionBeginUser;
  PetscCall(LogRegister());
  comm_ = comm;
  p_ = p;
  const PetscInt N = p.N();
  PetscCallMPI(MPI_Comm_size(comm, &size_));
  PetscCheck(N >= size_, comm, PETSC_ERR_USER, "-lattice_cells %" PetscInt_FMT " gives N = %" PetscInt_FMT " sites, fewer than the %d MPI ranks",
             p.cells, N, (int)size_);
  // K, L, the state and work vectors: a few hundred bytes per site (N = 10^6: ~0.3 GB).
  PetscCall(CheckMemory(comm, 300.0 * (double)N / size_, "the lattice (-lattice_cells)"));
  PetscCall(DMDACreate1d(comm, DM_BOUNDARY_NONE, N, 1, 1, NULL, da_.out()));
  PetscCall(DMSetUp(da_));
  PetscCall(DMDASetFieldName(da_, 0, "u"));
  PetscCall(DMDAGetCorners(da_, &xs_, NULL, NULL, &xm_, NULL, NULL));
  PetscCall(DMDAGetOwnershipRanges(da_, &lx, NULL, NULL));
  starts_.assign(1, 0);
  for (PetscMPIInt r = 0; r < size_; r++) starts_.push_back(starts_.back() + lx[r]);
  {
    std::vector<PetscReal> bonds, diag; // O(N) on every rank, so every rank has the same realisation
    LatticeSprings(p, &bonds, &diag);
    kb_.assign(xm_ + 1, 0.0);
    for (PetscInt b = xs_ - 1; b < xs_ + xm_; b++)
      if (b >= 0 && b < N - 1) kb_[b - xs_ + 1] = bonds[b];
    kd_.assign(diag.begin() + xs_, diag.begin() + xs_ + xm_);
  }
  gb_.assign(xm_ + 1, 0.0);
  for (PetscInt b = std::max<PetscInt>(xs_ - 1, 0); b < std::min(xs_ + xm_, N - 1); b++)
    if (p.Stiff(b)) gb_[b - xs_ + 1] = p.Gamma;
  PetscCall(ISCreateStride(comm, xm_, 2 * xs_, 1, is_u_.out()));
  PetscCall(ISCreateStride(comm, xm_, 2 * xs_ + xm_, 1, is_v_.out()));

  PetscCall(DMCreateMatrix(da_, K_.out()));
  PetscCall(PetscObjectSetName((PetscObject)K_.get(), "K"));
  PetscCall(AssembleTangentStiffness(NULL, K_));
  PetscCall(CreateStateMatrix(L_.out()));
  PetscCall(PetscObjectSetName((PetscObject)L_.get(), "L"));
  PetscCall(AssembleStateJacobian(NULL, L_));
  PetscFunctionReturn(0);
}

PetscInt Lattice::OwnerCount(PetscInt site) const
{
  const auto it = std::upper_bound(starts_.begin(), starts_.end(), site) - 1;
  return *(it + 1) - *it;
}

PetscInt Lattice::StateIndexU(PetscInt site) const
{
  const auto it = std::upper_bound(starts_.begin(), starts_.end(), site) - 1;
  return *it + site; // 2 * start + (site - start)
}

PetscErrorCode Lattice::CreateStateVector(Vec *z) const
{
  PetscFunctionBeginUser;
  PetscCall(VecCreateMPI(comm_, 2 * xm_, 2 * p_.N(), z));
  PetscFunctionReturn(0);
}

PetscErrorCode Lattice::CreateStateMatrix(Mat *A) const
{
  PetscFunctionBeginUser;
  // Every row couples to u_{i-1}, u_i, u_{i+1} (one of them may be on a
  // neighbouring rank) and v_i: the pattern of L, of the state Jacobian, of the
  // unfolded Jacobian of the orbit solver, and of implicit TS shifts.
  PetscCall(MatCreateAIJ(comm_, 2 * xm_, 2 * xm_, 2 * p_.N(), 2 * p_.N(), 4, NULL, 2, NULL, A)); // a one-site rank has both neighbours off-rank
  PetscCall(MatSetOption(*A, MAT_NEW_NONZERO_ALLOCATION_ERR, PETSC_TRUE));
  PetscFunctionReturn(0);
}

PetscErrorCode Lattice::GetGhostedU(Vec x, Vec *ul, const PetscScalar **u) const
{
  PetscInt n, gxs;
  PetscFunctionBeginUser;
  *ul = NULL;
  if (size_ == 1) { // the global array holds every neighbour (u first in a state vector)
    PetscCall(VecGetArrayRead(x, u));
    PetscFunctionReturn(0);
  }
  PetscCall(VecGetLocalSize(x, &n));
  Vec xu = x;
  if (n == 2 * xm_) PetscCall(VecGetSubVector(x, is_u_, &xu)); // zero-copy: contiguous per rank
  PetscCall(DMGetLocalVector(da_, ul));
  PetscCall(DMGlobalToLocalBegin(da_, xu, INSERT_VALUES, *ul));
  PetscCall(DMGlobalToLocalEnd(da_, xu, INSERT_VALUES, *ul));
  if (xu != x) PetscCall(VecRestoreSubVector(x, is_u_, &xu));
  PetscCall(DMDAGetGhostCorners(da_, &gxs, NULL, NULL, NULL, NULL, NULL));
  PetscCall(VecGetArrayRead(*ul, u));
  *u -= gxs;
  PetscFunctionReturn(0);
}

PetscErrorCode Lattice::RestoreGhostedU(Vec x, Vec *ul, const PetscScalar **u) const
{
  PetscFunctionBeginUser;
  if (!*ul) {
    PetscCall(VecRestoreArrayRead(x, u));
    PetscFunctionReturn(0);
  }
  PetscInt gxs;
  PetscCall(DMDAGetGhostCorners(da_, &gxs, NULL, NULL, NULL, NULL, NULL));
  *u += gxs;
  PetscCall(VecRestoreArrayRead(*ul, u));
  PetscCall(DMRestoreLocalVector(da_, ul));
  PetscFunctionReturn(0);
}

void Lattice::LinearAcceleration(const PetscScalar *u, PetscScalar *a) const
{
  const PetscInt N = p_.N(), lo = std::max<PetscInt>(xs_, 1), hi = std::min(xs_ + xm_, N - 1);
  const PetscReal *kb = kb_.data() - xs_ + 1; // kb[b]: bond b
  const PetscReal *kd = kd_.data() - xs_;     // kd[i]: K(i, i)
  for (PetscInt i = lo; i < hi; i++) a[i] = kb[i - 1] * u[i - 1] - kd[i] * u[i] + kb[i] * u[i + 1];
  if (xs_ == 0) a[0] = -kd[0] * u[0] + (N > 1 ? kb[0] * u[1] : 0.0);
  if (xs_ + xm_ == N && N > 1) a[N - 1] = kb[N - 2] * u[N - 2] - kd[N - 1] * u[N - 1];
}

void Lattice::AddCubicAcceleration(const PetscScalar *u, PetscScalar *a) const
{
  // Bond b pulls site b back and site b+1 forward with F_b = Gamma_b d^3,
  // d = u_b - u_{b+1} (Gamma_b = 0 off the stiff bonds): a_i += F_{i-1} - F_i.
  // Each bond's force is formed by both its sites, so the loop has no branch
  // and vectorises (the bond list it replaced did not).
  const PetscInt N = p_.N(), lo = std::max<PetscInt>(xs_, 1), hi = std::min(xs_ + xm_, N - 1);
  const PetscReal *gb = gb_.data() - xs_ + 1; // gb[b]: bond b
  for (PetscInt i = lo; i < hi; i++) {
    const PetscScalar dl = u[i - 1] - u[i], dr = u[i] - u[i + 1];
    a[i] += gb[i - 1] * dl * dl * dl - gb[i] * dr * dr * dr;
  }
  if (xs_ == 0 && N > 1) {
    const PetscScalar d = u[0] - u[1];
    a[0] -= gb[0] * d * d * d;
  }
  if (xs_ + xm_ == N && N > 1) {
    const PetscScalar d = u[N - 2] - u[N - 1];
    a[N - 1] += gb[N - 2] * d * d * d;
  }
}

PetscErrorCode Lattice::Energy(Vec z, EnergyParts *e) const
{
  const PetscScalar *u, *zl;
  Vec ul;
  EnergyParts loc;
  const PetscInt N = p_.N();
  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(Log().energy, 0, 0, 0, 0));
  PetscCall(GetGhostedU(z, &ul, &u));
  PetscCall(VecGetArrayRead(z, &zl));
  const PetscScalar *v = zl + xm_;
  const PetscReal *kd = kd_.data() - xs_, *kb = kb_.data() - xs_ + 1; // kd[i]: K(i, i); kb[b]: bond b
  const PetscInt lo = xs_, hi = xs_ + xm_, bhi = std::min(hi, N - 1); // bond b (b, b+1) belongs to the owner of site b
  PetscReal kin = 0, lin = 0, quart = 0;
  // The sums in vector lanes (a scalar sum is bound by the add latency; the
  // lanes reassociate it, a rounding-level change).
#pragma omp simd reduction(+ : kin, lin)
  for (PetscInt i = lo; i < hi; i++) {
    const PetscScalar ui = u[i], vi = v[i - lo];
    kin += vi * vi;
    lin += kd[i] * ui * ui;
  }
  const PetscReal *gb = gb_.data() - xs_ + 1; // gb[b]: Gamma of bond b (0 off the stiff bonds)
#pragma omp simd reduction(+ : lin, quart)
  for (PetscInt b = lo; b < bhi; b++) {
    const PetscScalar d = u[b] - u[b + 1], d2 = d * d;
    lin -= 2 * kb[b] * u[b] * u[b + 1]; // the two off-diagonal entries of bond b in u.K u
    quart += gb[b] * d2 * d2;
  }
  loc.kinetic = 0.5 * kin;
  loc.linear = 0.5 * lin;
  loc.quartic = 0.25 * quart;
  PetscCall(VecRestoreArrayRead(z, &zl));
  PetscCall(RestoreGhostedU(z, &ul, &u));
  if (size_ == 1) *e = loc;
  else {
    PetscReal in[3] = {loc.kinetic, loc.linear, loc.quartic}, out[3];
    PetscCall(MPIU_Allreduce(in, out, 3, MPIU_REAL, MPIU_SUM, comm_));
    e->kinetic = out[0];
    e->linear = out[1];
    e->quartic = out[2];
  }
  PetscCall(PetscLogEventEnd(Log().energy, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

void Lattice::TangentRow(PetscInt i, const PetscScalar *u, PetscScalar c[3]) const
{
  const PetscInt N = p_.N();
  c[0] = c[2] = 0;
  c[1] = kd_[i - xs_];
  if (i > 0) {
    c[0] = -kb_[i - 1 - xs_ + 1];
    if (u && p_.Stiff(i - 1)) {
      const PetscScalar d = u[i - 1] - u[i], s = 3 * p_.Gamma * d * d;
      c[0] -= s;
      c[1] += s;
    }
  }
  if (i < N - 1) {
    c[2] = -kb_[i - xs_ + 1];
    if (u && p_.Stiff(i)) {
      const PetscScalar d = u[i] - u[i + 1], s = 3 * p_.Gamma * d * d;
      c[2] -= s;
      c[1] += s;
    }
  }
}

PetscErrorCode Lattice::FillStiffness(const PetscScalar *u, Mat M, bool state_form, PetscReal beta) const
{
  const PetscInt N = p_.N();
  PetscFunctionBeginUser;
  PetscCall(MatZeroEntries(M));
  for (PetscInt i = xs_; i < xs_ + xm_; i++) {
    PetscScalar c[3], ku[3];
    PetscInt cols[4], nc = 0;
    TangentRow(i, u, c);
    for (PetscInt o = -1; o <= 1; o++) {
      const PetscInt j = i + o;
      if (j < 0 || j >= N) continue;
      cols[nc] = state_form ? StateIndexU(j) : j;
      ku[nc++] = c[o + 1];
    }
    if (!state_form) {
      PetscCall(MatSetValues(M, 1, &i, nc, cols, ku, INSERT_VALUES));
      continue;
    }
    // Rows of (I + beta [[0, -I], [I, 0]]) [[0, I], [-K_T, 0]] over the columns
    // (u_{i-1}, u_i, u_{i+1}, v_i); all four are always stored (zeros when
    // beta = 0) so the pattern never changes:
    //   u row: [ beta K_T | 1 ],   v row: [ -K_T | beta ].
    const PetscInt ru = StateIndexU(i), rv = StateIndexV(i);
    PetscScalar urow[4], vrow[4];
    for (PetscInt k = 0; k < nc; k++) {
      urow[k] = beta * ku[k];
      vrow[k] = -ku[k];
    }
    cols[nc] = rv;
    urow[nc] = 1.0;
    vrow[nc] = beta;
    PetscCall(MatSetValues(M, 1, &ru, nc + 1, cols, urow, INSERT_VALUES));
    PetscCall(MatSetValues(M, 1, &rv, nc + 1, cols, vrow, INSERT_VALUES));
  }
  PetscCall(MatAssemblyBegin(M, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(M, MAT_FINAL_ASSEMBLY));
  PetscFunctionReturn(0);
}

PetscErrorCode Lattice::AssembleTangentStiffness(Vec u, Mat KT) const
{
  PetscFunctionBeginUser;
  if (!u || !HasCubic()) {
    PetscCall(FillStiffness(NULL, KT, false, 0));
    PetscFunctionReturn(0);
  }
  const PetscScalar *a;
  Vec ul;
  PetscCall(GetGhostedU(u, &ul, &a));
  PetscCall(FillStiffness(a, KT, false, 0));
  PetscCall(RestoreGhostedU(u, &ul, &a));
  PetscFunctionReturn(0);
}

PetscErrorCode Lattice::AssembleStateJacobian(Vec z, Mat A, PetscReal beta) const
{
  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(Log().jacobian, 0, 0, 0, 0));
  if (!z || !HasCubic()) {
    PetscCall(FillStiffness(NULL, A, true, beta));
  } else {
    const PetscScalar *a;
    Vec ul;
    PetscCall(GetGhostedU(z, &ul, &a));
    PetscCall(FillStiffness(a, A, true, beta));
    PetscCall(RestoreGhostedU(z, &ul, &a));
  }
  PetscCall(PetscLogEventEnd(Log().jacobian, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

} // namespace nltopo
