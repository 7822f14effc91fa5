#pragma once
// The linear topological transition (paper Fig. 2a, -linear_gamma_list): over a
// grid of the dimerisation gamma, the finite lattice's whole spectrum and the
// Zak phases of the infinite lattice's two bands for the left and right unit
// cells. Only gamma changes along the grid: k, gamma0, the layout, Nc and any
// -lattice_perturbation realisation stay those of the study. Since
// k1 + k2 = 2k, k_hat = 2k + gamma0 is the same at every gamma.
#include "bands/bloch.hpp"
#include <vector>

namespace nltopo {

// n >= 2 values over [lo, hi], ends included, as (lo (n-1-i) + hi i) / (n-1):
// a grid symmetric about 0 then holds 0 and every pair +-gamma exactly
// (-1:1:201 has gamma[100] = 0, where the gap closes).
std::vector<PetscReal> GammaGrid(PetscReal lo, PetscReal hi, PetscInt n);

// All N eigenfrequencies of the lattice's K, ascending: the springs of
// LatticeSprings (the K that Lattice assembles, perturbations included) by
// LAPACK's symmetric tridiagonal QR, eigenvalues only (O(N^2)). omega =
// sqrt(max(lambda, 0)), as LinearModes writes /linear/omega; lambda_min
// (optional) is the smallest eigenvalue: negative where K is not positive
// definite (e.g. gamma -> 1 with a small gamma0: the interface site's grounding
// gamma0 + k2 - k1 is negative from gamma = gamma0 / 2k on, and K's smallest
// eigenvalue at gamma = 1 is k_hat - 2 sqrt(2) k). Serial: every rank that calls
// it computes the same numbers.
PetscErrorCode FiniteSpectrum(const LatticeParams &p, std::vector<PetscReal> *omega, PetscReal *lambda_min = nullptr);

// Whether the gap of a cell with these bonds is closed (k_intra = k_inter to
// rounding: at q = pi the Bloch Hamiltonian vanishes, its eigenvectors and the
// Zak phase are undefined; on the grid above that is gamma = 0 exactly).
bool GapClosed(PetscReal k_intra, PetscReal k_inter);

// ZakPhase (bloch.hpp, Wilson loop over 2 nq points), NaN where GapClosed.
// Elsewhere it is exactly quantised, 0 or pi up to rounding, however small the
// gap: the loop contains q = pi, the point of the circle h(q) nearest the origin.
PetscReal ZakPhaseOrNaN(PetscReal k_intra, PetscReal k_inter, int band, PetscInt nq);

struct TransitionResult {
  PetscInt N = 0;                    // sites
  std::vector<PetscReal> gamma;      // ng
  std::vector<PetscReal> omega;      // ng x N, row-major, each row ascending
  std::vector<PetscReal> zak_left;   // ng x 2 (acoustic, optical); left cell: intra k2, inter k1
  std::vector<PetscReal> zak_right;  // ng x 2; right cell: intra k1, inter k2
  std::vector<PetscReal> bands_inf;  // ng x 4: infinite-lattice acoustic bottom, top, optical bottom, top
  std::vector<PetscReal> lambda_min; // ng: smallest eigenvalue of K (< 0: not positive definite, omega clamped to 0)
};

// The transition of the study's lattice base over the values gamma; nq as -linear_nq.
PetscErrorCode ComputeTransition(const LatticeParams &base, const std::vector<PetscReal> &gamma, PetscInt nq, TransitionResult *r);

} // namespace nltopo
