#pragma once
// The flow and its variational equations integrated together with PETSc TS
// (prefix -nnm_ts_, fixed steps T/n): Y = [z; W] with
//   z' = f_beta(z),   W' = A_beta(z) W (+ grad E(z) in the last column, the
//   beta derivative), A_beta = (I + beta [[0,-I],[I,0]]) [[0, I], [-K_T(u), 0]].
// Per site the augmented DMDA holds [u, v, Wu(0..ncol), Wv(0..ncol)], so the
// tridiagonal K_T acts on contiguous rows of W with one ghost exchange: the
// structured product costs O(N ncol), against a general sparse-times-dense
// product and ~30 dense AXPYs per step in PETSc 3.18's TSForward for RK
// (README.md, NNM performance).
#include "lattice/lattice.hpp"
#include <vector>

namespace nltopo {

class VariationalFlow {
public:
  // ncol columns of W; the last one is the beta column.
  PetscErrorCode Setup(const Lattice &lat, PetscInt ncol, PetscInt steps);
  // W0 columns: identity on the state columns (dense monodromy, ncol = 2N + 1) when dz is NULL,
  // else column 0 = dz (ncol = 2). Returns zT and S (2N x ncol, dense, state-row layout) or w.
  PetscErrorCode Integrate(Vec z0, PetscReal T, PetscReal beta, Vec dz, Vec zT, Mat S, Vec w_dir, Vec w_beta);
  PetscErrorCode Rhs(PetscReal t, Vec Y, Vec F);
  PetscReal beta_ = 0;

private:
  const Lattice *lat_ = nullptr;
  PetscInt ncol_ = 0, dof_ = 0, steps_ = 0;
  OwnedDM da_;
  OwnedTS ts_;
  OwnedVec Y_;
  std::vector<PetscScalar> u_, a_; // ghosted displacement and acceleration by global site
};

} // namespace nltopo
