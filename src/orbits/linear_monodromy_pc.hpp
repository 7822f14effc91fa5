#pragma once
// Preconditioner of the matrix-free shooting (-nnm_mf_pc linear): the exact
// inverse of M_lin - I, the monodromy of the LINEAR lattice over the period T
// minus the identity. Per mode of K (frequency w, theta = w T) M_lin - I is
// [[cos - 1, sin / w], [-w sin, cos - 1]], whose inverse is
// [[-1/2, -cot(theta/2) / (2 w)], [w cot(theta/2) / 2, -1/2]], so for z = [u; v]
//   (M_lin - I)^{-1} [r_u; r_v] = [-r_u/2 - G r_v/2;  K G r_u/2 - r_v/2],
//   G = g(K),  g(l) = cot(sqrt(l) T/2) / sqrt(l).
// g is applied through its partial fractions (cot x = 1/x + sum_n 2x/(x^2 - n^2 pi^2)):
//   g(K) = (2/T) K^{-1} + (4/T) sum_{n>=1} (K - w_n^2 I)^{-1},   w_n = 2 pi n / T,
// with the shifted tridiagonal solves for n <= n_max (w_nmax^2 > 4 lambda_max(K))
// and the tail sum_{n>n_max} (K - w_n^2)^{-1} = -sum_k K^k s_{k+1},
// s_j = sum_{n>n_max} w_n^{-2j}, to k = 3. The lattice is a chain, so K is
// tridiagonal and every solve is O(N) (LU with partial pivoting: the shifts lie
// inside K's spectrum). Each rank solves the whole chain redundantly on the
// gathered right-hand side: O(N) memory and work per rank, no dense matrix.
//
// Why it bounds the Krylov iterations: away from the localized nonlinear core
// the orbit is small and M - I equals M_lin - I, so the preconditioned operator
// is the identity plus a perturbation whose rank is set by the core, not by N.
#include "lattice/lattice.hpp"
#include <vector>

namespace nltopo {

class LinearMonodromyPC {
public:
  PetscErrorCode Setup(const Lattice &lat); // stiffness K of the lattice
  // Replace the stiffness by another symmetric tridiagonal one, e.g. the orbit's
  // time-averaged tangent stiffness <K_T(u(t))> (-nnm_mf_pc averaged); owned rows:
  // diag[i - xs] = K(i,i), off[i - xs] = K(i,i+1). Collective.
  PetscErrorCode SetStiffness(const std::vector<PetscReal> &diag, const std::vector<PetscReal> &off);
  // Factor the shifted chains for the period T (called at every Jacobian evaluation).
  PetscErrorCode SetPeriod(PetscReal T);
  // x = (M_lin - I)^{-1} r on state vectors (x may not alias r).
  PetscErrorCode Apply(Vec r, Vec x);
  PetscInt Shifts() const { return (PetscInt)lu_.size(); }

private:
  struct TridiagonalLU { // LAPACK gttrf layout: L multipliers, U with a second superdiagonal, pivots
    std::vector<PetscReal> dl, d, du, du2;
    std::vector<char> swapped;
    void Factor(const std::vector<PetscReal> &diag, const std::vector<PetscReal> &off, PetscReal shift);
    void Solve(PetscReal *b) const;
    PetscReal PivotRatio() const;
  };
  void MultK(const PetscReal *x, PetscReal *y) const; // y = K x on the whole chain
  void ApplyG(const PetscReal *r, PetscReal *y);      // y = g(K) r on the whole chain

  const Lattice *lat_ = nullptr;
  PetscInt N_ = 0;
  std::vector<PetscReal> diag_, off_; // K(i,i) and K(i,i+1) of the whole chain
  std::vector<PetscMPIInt> counts_, displs_;
  PetscReal lambda_max_ = 0, T_ = 0;
  std::vector<TridiagonalLU> lu_; // shift 0, then w_1^2 .. w_nmax^2
  PetscReal tail_[4] = {0, 0, 0, 0}; // s_1 .. s_4
  std::vector<PetscReal> ru_, rv_, gu_, gv_, t1_, t2_;
};

} // namespace nltopo
