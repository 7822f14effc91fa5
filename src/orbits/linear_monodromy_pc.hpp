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
// with the shifted tridiagonal solves for n <= n_max (n_max >= 4 and
// w_nmax^2 >= 64 lambda, lambda the Gershgorin bound of K's spectrum) and the
// tail sum_{n>n_max} (K - w_n^2)^{-1} = -sum_k K^k s_{k+1},
// s_j = sum_{n>n_max} w_n^{-2j}, to k = 3. The lattice is a chain, so K is
// tridiagonal and every solve is O(N) (LU with partial pivoting: the shifts lie
// inside K's spectrum). Each rank solves the whole chain redundantly on the
// gathered right-hand side: O(N) memory and work per rank, no dense matrix.
//
// Why it bounds the Krylov iterations: away from the localized nonlinear core
// the orbit is small and M - I equals M_lin - I, so the preconditioned operator
// is the identity plus a perturbation whose rank is set by the core, not by N.
//
// -nnm_mf_pc parametric adds the orbit's 2 w parametric term (w = 2 pi / T) where
// it matters: on the band modes of frequency near w, which the averaged
// stiffness leaves near-singular once the orbit is inside a band. With
// K_T(t) ~ K0 + Kc cos 2wt + Ks sin 2wt and u = a cos wt + b sin wt, averaging
// over the fast phase (rotating-wave approximation) gives the slow system
//   [a; b]' = B [a; b],  B = 1/(2w) [[Ks/2, D - Kc/2], [-(D + Kc/2), -Ks/2]],
//   D = K0 - w^2,  and (u, v) = (a, w b) at t = 0 and T,
// so near the 1:1 resonance M - I ~ S^-1 (B T) S with S = diag(I, I/w). Its
// inverse is the exact averaged one's n = 1 partial fraction when Kc = Ks = 0;
// the preconditioner adds the difference S^-1 [(B T)^-1 - (B0 T)^-1] S, which
// vanishes away from the resonance. B T is a 2N x 2N band matrix in the order
// (a_0, b_0, a_1, ...) with 3 sub- and superdiagonals: LAPACK's banded LU, O(N).
// Along the orbit's own mode the block is exactly singular (D = |Kc + i Ks|/2:
// the orbit's phase shift, which the shooting system fixes by its phase row,
// not by the state rows this preconditioner acts on), and GMRES breaks down on
// it once Newton has converged. Kc and Ks are therefore scaled by a weight < 1
// (-nnm_mf_pc_parametric_weight, default 0.95): det = (1 - weight^2) D^2 there,
// and the band modes keep 95 % of their parametric coupling.
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
  // The orbit's 2 w harmonics Kc, Ks of K_T (-nnm_mf_pc parametric), owned rows
  // as in SetStiffness, scaled by weight in (0, 1]; empty vectors remove the
  // term. Collective.
  PetscErrorCode SetParametricTerm(const std::vector<PetscReal> &cdiag, const std::vector<PetscReal> &coff, const std::vector<PetscReal> &sdiag,
                                   const std::vector<PetscReal> &soff, PetscReal weight);
  // Factor the shifted chains (and the rotating-wave block) for the period T;
  // nothing to do when neither T nor the stiffness changed since the last
  // factorisation. The matrix-free shooting calls it at every Jacobian evaluation.
  PetscErrorCode SetPeriod(PetscReal T);
  // x = (M_lin - I)^{-1} r on state vectors (x may not alias r).
  PetscErrorCode Apply(Vec r, Vec x);

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
  PetscErrorCode GatherChain(const std::vector<PetscReal> &diag, const std::vector<PetscReal> &off, std::vector<PetscReal> *d, std::vector<PetscReal> *e);
  PetscErrorCode FactorRotatingWave();                              // B T of the header, banded LU
  void ApplyRotatingWave(const PetscReal *ru, const PetscReal *rv); // cu_, cv_ = the parametric correction

  const Lattice *lat_ = nullptr;
  PetscInt N_ = 0;
  std::vector<PetscReal> diag_, off_; // K(i,i) and K(i,i+1) of the whole chain
  std::vector<PetscMPIInt> counts_, displs_;
  PetscReal lambda_max_ = 0, T_ = 0;
  std::vector<TridiagonalLU> lu_;    // shift 0, then w_1^2 .. w_nmax^2
  PetscReal tail_[4] = {0, 0, 0, 0}; // s_1 .. s_4
  std::vector<PetscReal> ru_, rv_, gu_, gv_, t1_, t2_;
  // -nnm_mf_pc parametric
  bool parametric_ = false;
  std::vector<PetscReal> kcd_, kco_, ksd_, kso_; // Kc, Ks of the whole chain
  PetscReal pw_ = 1;                             // scale of Kc, Ks
  PetscReal shift1_ = 0;                         // the shift of lu_[1]: w^2, nudged off K's spectrum
  std::vector<PetscReal> band_, rhs2_;           // LAPACK band storage of B T (ldab 10), interleaved right-hand side
  std::vector<int> ipiv_;
  std::vector<PetscReal> cu_, cv_;
};

} // namespace nltopo
