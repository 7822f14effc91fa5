#pragma once
// Floquet multipliers of a periodic orbit: the eigenvalues of the monodromy
// M = dz(T)/dz0 (SLEPc EPS, non-Hermitian, options -floquet_eps_*), their
// Krein signatures K = sign(-i v^H J v), J = [[0, I], [-I, 0]] (model.md), and
// the kind of instability (docs/model.md, docs/continuation.md "Floquet multipliers and Krein signatures").
#include "lattice/lattice.hpp"
#include <cmath>
#include <complex>
#include <vector>

namespace nltopo {

struct FloquetOptions {
  PetscReal tol = 1e-6;         // |mu| > 1 + tol is unstable
  PetscReal krein_tol = 1e-6;   // |-i v^H J v| / |v|^2 below this: signature 0 (real or on a collision)
  PetscReal edge_weight = 0.75; // an eigenvector with more of its displacement norm than this
                                // within +-edge_sites of the interface counts as an edge (localised) mode
  PetscInt edge_sites = 10;
  PetscInt confirm_periods = 20; // an unstable verdict is confirmed by integrating its eigenvector this many periods
  PetscReal confirm_rtol = 0.1;  // ... and its growth rate per period must match ln|mu| to this relative tolerance
};
PetscErrorCode FloquetOptionsFromOptions(MPI_Comm comm, FloquetOptions *o);

struct FloquetResult {
  std::vector<PetscReal> re, im; // 2N multipliers, sorted by angle then modulus
  std::vector<PetscInt> krein;   // -1, 0, 1
  std::vector<PetscReal> edge;   // share of each eigenvector's displacement norm in the edge region
  std::vector<PetscReal> kappa;  // the Krein value -i v^H J v / |v|^2 itself (krein is its sign above krein_tol)
  PetscReal max_modulus = 0;
  PetscReal worst_re = 1, worst_im = 0; // the multiplier of largest modulus (upper half plane member)
  bool stable = true;
  PetscInt instability = 0; // 0 none, 1 bulk-bulk, 2 bulk-edge, 3 edge-edge
  PetscInt trivial = 0;     // multipliers within 1e-4 of 1 (2 for an isolated NNM)
  PetscReal det_error = 0;  // |det M - 1| with det M from an LU factorisation in extended
                            // precision (the product of the computed multipliers carries
                            // their rounding, ~2N eps): Liouville's theorem says det M = 1
  // Only when asked for (FloquetAnalysis circle_vectors): the eigenvectors of
  // the multipliers on the unit circle (||mu| - 1| <= tol) in the open upper
  // half plane with an edge share of at least circle_vectors, natural order
  // [u_1..u_N, v_1..v_N], unit norm, on every rank; empty for the others. They
  // tell the members of two orbits' spectra apart (Krein collisions that pass).
  std::vector<std::vector<std::complex<PetscReal>>> vectors;
  // The leading nontrivial eigenvector (LeadingIndex below): its participation
  // ratio over sites (DisplacementParticipation) and its edge share.
  PetscReal leading_participation = NAN, leading_edge = NAN;
};

// M: the 2N x 2N monodromy in the state layout (columns 0..2N-1 of the
// sensitivity matrix S, whose last column is ignored). With vec, also the
// eigenvector of the multiplier nearest target (re, im): natural order
// [u_1..u_N, v_1..v_N] on every rank, unit norm, its phase turned so that its
// real part (written) is largest, the largest entry positive.
// circle_vectors >= 0: also r->vectors (above), for edge shares >= it.
// worst_re, worst_im (optional, state layout like z0): the eigenvector of the
// multiplier of largest modulus, when the orbit is unstable (for ConfirmGrowth).
PetscErrorCode FloquetAnalysis(const Lattice &lat, Mat S, const FloquetOptions &o, FloquetResult *r, const PetscReal *target = nullptr,
                               std::vector<PetscReal> *vec = nullptr, PetscReal circle_vectors = -1, Vec worst_re = nullptr, Vec worst_im = nullptr);

// The Krein value -i v^H J v / |v|^2 and the edge share of the displacement
// norm (within e sites of the interface cell) of v = xr + i xi, state layout. Collective.
PetscErrorCode EigenvectorShares(const Lattice &lat, Vec xr, Vec xi, PetscInt e, PetscReal *kappa, PetscReal *edge);

// The Krein signature of a Krein value kappa = -i v^H J v / |v|^2: 0 below
// -floquet_krein_tol (real multipliers, off the circle, or on a collision).
inline PetscInt KreinSign(const FloquetOptions &o, PetscReal kappa) { return std::abs(kappa) < o.krein_tol ? 0 : (kappa > 0 ? 1 : -1); }
// The class of an eigenvector with edge share w (of its displacement norm):
// 3 E-E above -floquet_edge_weight, 1 B-B below 1 minus it, 2 B-E between.
inline PetscInt Localisation(const FloquetOptions &o, PetscReal w) { return w > o.edge_weight ? 3 : (w < 1 - o.edge_weight ? 1 : 2); }
// Whether site i lies in the edge region of the interface cell (sites iface, iface + 1) with e sites each side.
inline bool InEdgeRegion(PetscInt i, PetscInt iface, PetscInt e) { return i >= iface - e && i <= iface + 1 + e; }

// The participation ratio of an eigenvector over the sites, from its
// displacement part: with d_i = |x_{u_i}|^2, PR = (sum_i d_i)^2 / sum_i d_i^2,
// in units of sites (1: one site; N: spread evenly over all N). disp = sum d_i,
// disp2 = sum d_i^2 (summed over ranks first); 0 for a vector without displacement.
inline PetscReal DisplacementParticipation(PetscReal disp, PetscReal disp2) { return disp2 > 0 ? disp * disp / disp2 : 0; }

// The leading nontrivial multiplier of a whole spectrum mu, as the dense
// -floquet_mf route picks it (floquet_mf.hpp FloquetLeadingDense): the two
// multipliers nearest 1 (the trivial pair) left out; beyond 1 + tol the largest
// |mu|; otherwise, on the circle, the upper-half-plane one nearest +-1 (largest
// |Re mu|). Its index, -1 if there is none.
PetscInt LeadingIndex(const std::vector<std::complex<PetscReal>> &mu, PetscReal tol);

// The first n columns of the dense sensitivity matrix S (the monodromy) on
// rank 0, column-major in PETSc's state order on rows and columns alike (a
// similarity of M); other ranks get an empty vector. Collective.
PetscErrorCode GatherMonodromy(Mat S, PetscInt n, std::vector<PetscReal> *a);

// H = Q^T M Q of a (n x n, column-major; a keeps the reflectors below the
// subdiagonal, tau their factors), H into h and its eigenvalues wr + i wi
// (QR on a copy). work: LAPACK's workspace, kept for the later calls. Not collective.
PetscErrorCode HessenbergEigenvalues(int n, PetscReal *a, std::vector<PetscReal> &tau, std::vector<PetscReal> &h, std::vector<PetscReal> &wr,
                                     std::vector<PetscReal> &wi, std::vector<PetscReal> &work);

// The multipliers (eigenvalues only) of the first n columns of S on every
// rank: the monodromy gathered on rank 0, Hessenberg QR there, broadcast.
// The test functions of the codim-2 curves need no eigenvectors, Krein
// signatures or classes (FloquetAnalysis). Collective.
PetscErrorCode MonodromyMultipliers(Mat S, PetscInt n, std::vector<std::complex<PetscReal>> *mu);

// The real vector e^{i phi} v with the largest real part, unit norm, its
// largest entry positive (an eigenvector's shape, whatever its phase).
std::vector<PetscReal> RealPhase(const std::vector<std::complex<PetscReal>> &v);

// The Krein value -i v^H J v / |v|^2 of v = xr + i xi for J = [[0, I], [-I, 0]],
// summed over n (u, v) pairs laid out as [u_1..u_n, v_1..v_n] (the owned part of
// a state vector, or a whole small canonical state): returns the local sums
// {2 (xr_u . xi_v - xr_v . xi_u), |v|^2}, to be reduced over ranks.
void KreinSums(const PetscScalar *xr, const PetscScalar *xi, PetscInt n, PetscReal sums[2]);

} // namespace nltopo
