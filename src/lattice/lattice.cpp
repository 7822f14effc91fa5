#include "lattice/lattice.hpp"
#include "core/memory_guard.hpp"
#include "core/log.hpp"
#include <algorithm>
#include <petscdmda.h>

namespace nltopo {

PetscErrorCode CheckLatticeMemory(MPI_Comm comm, PetscInt N)
{
  PetscMPIInt size;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_size(comm, &size));
  // K, L, the state and work vectors: a few hundred bytes per site (N = 10^6: ~0.3 GB).
  PetscCall(CheckMemory(comm, 300.0 * (double)N / size, "the lattice (-lattice_cells)"));
  PetscFunctionReturn(0);
}

PetscErrorCode Lattice::Setup(MPI_Comm comm, const LatticeParams &p)
{
  const PetscInt *lx;
  PetscFunctionBeginUser;
  PetscCall(LogRegister());
  comm_ = comm;
  p_ = p;
  const PetscInt N = p.N();
  PetscCallMPI(MPI_Comm_size(comm, &size_));
  PetscCheck(N >= size_, comm, PETSC_ERR_USER, "-lattice_cells %" PetscInt_FMT " gives N = %" PetscInt_FMT " sites, fewer than the %d MPI ranks", p.cells, N,
             (int)size_);
  PetscCall(CheckLatticeMemory(comm, N));
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
  PetscCall(ISCreateStride(comm, xm_, 2 * xs_, 1, is_u_.out()));
  PetscCall(ISCreateStride(comm, xm_, 2 * xs_ + xm_, 1, is_v_.out()));
  // the u part of a state vector as a site vector, by its array (GetGhostedU)
  if (size_ > 1) PetscCall(VecCreateMPIWithArray(comm, 1, xm_, N, NULL, u_view_.out()));

  PetscCall(DMCreateMatrix(da_, K_.out()));
  PetscCall(PetscObjectSetName((PetscObject)K_.get(), "K"));
  {
    std::vector<PetscScalar> kb(kb_.size());
    for (size_t b = 0; b < kb_.size(); b++) kb[b] = -kb_[b]; // K(b, b+1) = -k_b
    PetscCall(AssembleNearestNeighbour(kd_.data() - xs_, kb.data() - xs_ + 1, NULL, K_, true, 0));
  }
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
  PetscCall(DMGetLocalVector(da_, ul));
  if (n == 2 * xm_) {
    // a state vector: its owned u values lead its local array, and u_view_ wraps
    // them for the ghost exchange. (VecGetSubVector would do the same, with an
    // MPI_Allreduce on every call: a global synchronisation per force evaluation.)
    const PetscScalar *xa;
    PetscCall(VecGetArrayRead(x, &xa));
    PetscCall(VecPlaceArray(u_view_, const_cast<PetscScalar *>(xa))); // (read only: the source of the scatter)
    PetscCall(DMGlobalToLocalBegin(da_, u_view_, INSERT_VALUES, *ul));
    PetscCall(DMGlobalToLocalEnd(da_, u_view_, INSERT_VALUES, *ul));
    PetscCall(VecResetArray(u_view_));
    PetscCall(VecRestoreArrayRead(x, &xa));
  } else {
    PetscCall(DMGlobalToLocalBegin(da_, x, INSERT_VALUES, *ul));
    PetscCall(DMGlobalToLocalEnd(da_, x, INSERT_VALUES, *ul));
  }
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

void Lattice::KRow(PetscInt i, PetscScalar c[3]) const
{
  const PetscReal *kb = BondSprings(); // 0 outside the chain
  c[0] = -kb[i - 1];
  c[1] = kd_[i - xs_];
  c[2] = -kb[i];
}

PetscErrorCode Lattice::AssembleNearestNeighbour(const PetscScalar *kd, const PetscScalar *kb, const PetscScalar *c, Mat M, bool site_form,
                                                 PetscReal beta) const
{
  const PetscInt N = p_.N();
  PetscFunctionBeginUser;
  PetscCall(MatZeroEntries(M));
  for (PetscInt i = xs_; i < xs_ + xm_; i++) {
    const PetscScalar row[3] = {kb[i - 1], kd[i], kb[i]};
    PetscScalar ku[3];
    PetscInt cols[4], nc = 0;
    for (PetscInt o = -1; o <= 1; o++) {
      const PetscInt j = i + o;
      if (j < 0 || j >= N) continue;
      cols[nc] = site_form ? j : StateIndexU(j);
      ku[nc++] = row[o + 1];
    }
    if (site_form) {
      PetscCall(MatSetValues(M, 1, &i, nc, cols, ku, INSERT_VALUES));
      continue;
    }
    // Rows of (I + beta J) [[0, I], [-K_T, -C]], J = [[0, -I], [I, 0]], over
    // the columns (u_{i-1}, u_i, u_{i+1}, v_i); all four are always stored
    // (zeros when beta = 0) so the pattern never changes:
    //   u row: [ beta K_T | 1 + beta C ],   v row: [ -K_T | beta - C ].
    const PetscInt ru = StateIndexU(i), rv = StateIndexV(i);
    const PetscScalar ci = c ? c[i] : 0.0;
    PetscScalar urow[4], vrow[4];
    for (PetscInt k = 0; k < nc; k++) {
      urow[k] = beta * ku[k];
      vrow[k] = -ku[k];
    }
    cols[nc] = rv;
    urow[nc] = 1.0 + beta * ci;
    vrow[nc] = beta - ci;
    PetscCall(MatSetValues(M, 1, &ru, nc + 1, cols, urow, INSERT_VALUES));
    PetscCall(MatSetValues(M, 1, &rv, nc + 1, cols, vrow, INSERT_VALUES));
  }
  PetscCall(MatAssemblyBegin(M, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(M, MAT_FINAL_ASSEMBLY));
  PetscFunctionReturn(0);
}

PetscErrorCode SumDisplacements(const Lattice &lat, Vec a, Vec b, DisplacementSums *s)
{
  const PetscScalar *x, *y;
  const PetscInt m = lat.OwnedCount(); // the owned u entries lead each rank's part of the state
  PetscReal loc[4] = {0, 0, 0, 0}, g[4];
  PetscFunctionBeginUser;
  PetscCall(VecGetArrayRead(a, &x));
  PetscCall(VecGetArrayRead(b, &y));
  for (PetscInt k = 0; k < m; k++) {
    loc[0] += x[k] * y[k];
    loc[1] += x[k] * x[k];
    loc[2] += y[k] * y[k];
    loc[3] += x[k] * x[k] * x[k] * x[k];
  }
  PetscCall(VecRestoreArrayRead(b, &y));
  PetscCall(VecRestoreArrayRead(a, &x));
  PetscCall(MPIU_Allreduce(loc, g, 4, MPIU_REAL, MPIU_SUM, lat.Comm()));
  *s = {g[0], g[1], g[2], g[3]};
  PetscFunctionReturn(0);
}

} // namespace nltopo
