#pragma once
// The periodic-orbit flow and its tangent map under a symplectic splitting
// (-nnm_ts_type symsplit, timeint/ts_symsplit.hpp), with a monodromy that is
// exactly symplectic: M^T Omega M = Omega and det M = 1 to rounding.
//
// The discrete map of the shooting is
//   z(T) = B_beta(S_h^n(z0)),   h = T / n,
//   B_beta(z) = z + beta T grad E(z),   grad E = [K u + f_NL(u), v] = [-a(u), v],
// where S_h is one step of the symmetric splitting of the free lattice
// (Hamiltonian, so S_h^n is symplectic) and B_beta is the unfolding of
// Munoz-Almaraz et al. (Physica D 181, 2003) applied once at the end: it raises
// E by beta T |grad E|^2 + O(beta^2), so a periodic orbit needs beta = 0, and at
// beta = 0 the map is S_h^n alone (Floquet multipliers are taken there).
//
// Tangent map. A kick-drift step of u'' = a(u) is differentiated exactly by
// the same kick-drift step of the augmented second-order system
//   q = (u, W_u),  p = (v, P),  q'' = (a(u), -K_T(u) W_u + 2 s a(u)),
// with P = W_v + s v and s = s_T / T: a drift W_u += c h P is the derivative
// of u += c h v along (dz, dT = s_T) (h = T / n depends on T), and a kick
// P += b h (-K_T W_u + 2 s a) that of v += b h a(u) plus s times the kick of v
// itself. So one TS of type symsplit on [q | p] integrates the orbit and every
// column of the derivative of S_h^n, the T column included; B_beta's derivative
// is applied at the end.
//
// Layout: each rank owns [q_local | p_local], q per owned site (u_i, W_u,i(0..ncol-1))
// contiguous (the tridiagonal K_T then reads the neighbours' rows of W_u: one
// ghost exchange of two site blocks per acceleration).
#include "effects/effect.hpp"
#include <vector>

namespace nltopo {

class SymplecticVariationalFlow {
public:
  // ncol columns: the dense monodromy (ncol = 2N, identity start) or one
  // tangent column (ncol = 1). steps = n fixed steps per period.
  // fx: the (conservative) effects whose flow this is; kept by reference.
  PetscErrorCode Setup(const EffectList &fx, PetscInt ncol, PetscInt steps);
  void SetSteps(PetscInt steps) { steps_ = steps; } // fixed steps per period from the next Integrate on
  // Dense (dz NULL): zT = z(T) and S = [dz(T)/dz0 | dz(T)/dbeta] (2N x (2N+1),
  // dense, state-row layout). Tangent (dz given, ncol = 1): w = dz(T)/dz0 dz +
  // dz(T)/dbeta s_beta + dz(T)/dT s_T, the exact derivative of the discrete map.
  PetscErrorCode Integrate(Vec z0, PetscReal T, PetscReal beta, Vec dz, PetscReal s_beta, PetscReal s_T, Vec zT, Mat S, Vec w);
  // q'' of the augmented system for the owned q (the TS acceleration).
  PetscErrorCode Acceleration(Vec Y, PetscScalar *A);
  // Block tangent (set up with ncol = s = dz.size()): w[j] = dz(T)/dz0 dz[j]
  // for the s start vectors at once, B_beta's derivative I + beta T Hess E
  // applied at the end; no beta or T source (the columns of a monodromy
  // product; at beta = 0 the products of M). One pass over the orbit: the
  // orbit state, its acceleration and K_T(u) are computed once per stage for
  // all s columns (site-major blocks (u_i, W_u,i(0..s-1))).
  PetscErrorCode IntegrateBlock(Vec z0, PetscReal T, PetscReal beta, const std::vector<Vec> &dz, Vec zT, const std::vector<Vec> &w);

private:
  const EffectList *fx_ = nullptr;
  const Lattice *lat_ = nullptr;
  PetscInt ncol_ = 0, bs_ = 0, steps_ = 0; // bs_ = 1 + ncol: one site's q block
  PetscReal s_ = 0;                        // s_T / T: the T source
  OwnedTS ts_;
  OwnedVec Y_, ghost_; // ghost_: the q blocks of sites xs-1 and xs+xm (parallel only)
  OwnedVecScatter to_ghost_;
  std::vector<PetscScalar> u_, a_, kd_, kb_; // displacement (ghosted), acceleration and K_T by global site; kb_[b + 1]: bond b
  std::vector<PetscScalar> A_;               // the acceleration at the end (B_beta's derivative)
};

} // namespace nltopo
