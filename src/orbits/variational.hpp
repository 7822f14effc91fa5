#pragma once
// The flow and its variational equations integrated together with PETSc TS
// (prefix -nnm_ts_, fixed steps T/n): Y = [z; W] with
//   z' = f_beta(z),   W' = A_beta(z) W (+ s_beta grad E(z) + (s_T / T) f_beta(z)
//   in the last column), A_beta = (I + beta [[0,-I],[I,0]]) [[0, I], [-K_T(u), 0]].
// The sources make the last column the derivative of the *discrete* map
// z0 -> z_n (n fixed steps of T/n) along beta and T: in the time s = t/T the
// flow is z' = T f, its T-derivative w' = f + T A w, and the RK stages of w
// are exactly the derivatives of those of z. (f_beta(z(T)) is the T-derivative
// of the exact flow only, off by the discretization error.)
// Per site the augmented DMDA holds [u, v, Wu(0..ncol), Wv(0..ncol)], so the
// tridiagonal K_T acts on contiguous rows of W with one ghost exchange: the
// structured product costs O(N ncol), against a general sparse-times-dense
// product and ~30 dense AXPYs per step in PETSc 3.18's TSForward for RK
// (docs/continuation.md, "The monodromy").
#include "effects/effect.hpp"
#include <vector>

namespace nltopo {

class VariationalFlow {
public:
  // ncol columns of W; the last one carries the beta and T sources.
  // fx: the (conservative) effects whose flow this is; kept by reference.
  PetscErrorCode Setup(const EffectList &fx, PetscInt ncol, PetscInt steps);
  void SetSteps(PetscInt steps) { steps_ = steps; } // fixed steps per period from the next Integrate on
  // W0 columns: identity on the state columns (dense monodromy, ncol = 2N + 1,
  // last column the beta column: s_beta = 1, s_T = 0) when dz is NULL, else
  // the one column (ncol = 1) starts at dz and returns in w the derivative of
  // the discrete z(T) along (dz, s_beta, s_T). Returns zT and S (2N x ncol,
  // dense, state-row layout) or w.
  PetscErrorCode Integrate(Vec z0, PetscReal T, PetscReal beta, Vec dz, PetscReal s_beta, PetscReal s_T, Vec zT, Mat S, Vec w);
  PetscErrorCode Rhs(PetscReal t, Vec Y, Vec F);
  PetscReal beta_ = 0, src_beta_ = 1, src_f_ = 0; // src_f_ = s_T / T

private:
  const EffectList *fx_ = nullptr;
  const Lattice *lat_ = nullptr;
  PetscInt ncol_ = 0, dof_ = 0, steps_ = 0;
  OwnedDM da_;
  OwnedTS ts_;
  OwnedVec Y_;
  std::vector<PetscScalar> u_, a_, kd_, kb_; // ghosted displacement, acceleration and K_T by global site; kb_[b + 1]: bond b
};

} // namespace nltopo
