#pragma once
// Leading Floquet multipliers for long lattices (-floquet_mf): from the dense
// monodromy where 2N <= -floquet_mf_dense_max (FloquetLeadingDense, the only
// route that can call an orbit stable), matrix-free beyond.
//
// Matrix-free Floquet multipliers: SLEPc Krylov-Schur on a
// MATSHELL whose MatMult is the monodromy action M x = dz(T)/dz0 x, one
// tangent-linear integration of the orbit per product (PeriodicFlow::
// IntegrateWithTangent); the 2N x 2N monodromy is never formed. Options:
// -floquet_mf_nev (multiplier pairs wanted, one distinct b each on the critical
// route), -floquet_mf_which, -floquet_mf_deflate, -floquet_mf_eps_*.
//
// -floquet_mf_which largest: the multipliers of largest modulus (Krylov-Schur
// on M). Right for unstable orbits; on a stable orbit every multiplier has
// modulus 1 (and 1 is a Jordan block), so "largest" does not separate them.
// -floquet_mf_which critical (default): Krylov-Schur on B = (M + M^{-1}) / 2,
// whose eigenvalue b = (mu + 1/mu) / 2 maps the unit circle onto [-1, 1] with
// the critical points mu = +-1 at its ends, real unstable pairs outside it and
// Krein-collision quartets off the real axis: the largest |b| are the
// multipliers nearest +-1 and the real unstable pairs (saddle-node and
// period-doubling instabilities), the Jordan block at 1 becomes semisimple,
// and mu = b + sqrt(b^2 - 1). NOT found: an oscillatory (Krein-collision)
// instability away from +-1, whose b is complex with |b| < 1 (measured at
// N = 102, E = 0.94: |mu| = 1.0042 at b = -0.591 -+ 0.0034 i is missed); the dense route
// (-floquet_mf 0) finds it. M^{-1} costs one more tangent
// integration by reversibility: with R(u, v) = (u, -v) the flow satisfies
// R phi_t(R z) = phi_{-t}(z), so M(z0)^{-1} = R M(R z0) R on a periodic orbit.
//
// Deflation (-floquet_mf_deflate, default on when the family tangent is given):
// every NNM has the trivial pair mu = 1 with the exactly known invariant
// subspace span{f(z0), dz0}: M f = f (time shift) and M dz0 = dz0 - dT f
// (dz0, dT: the family tangent). In B it is the double eigenvalue 1 which,
// because the discrete M^{-1} is reversible only to the integration error, is
// nearly defective and converges slowly; it also takes two of the nev places
// from the multipliers that decide stability. SLEPc's deflation space removes
// it (the eigensolve runs on the orthogonal complement), so the nev returned
// multipliers are nontrivial ones.
#include "orbits/flow.hpp"
#include "stability/floquet.hpp"
#include "stability/floquet_localized_options.hpp"
#include <complex>
#include <vector>

namespace nltopo {

// A shell for M at the orbit (z0, T, beta). The flow, z0 and the shell must
// outlive its use; products() counts the integrations.
class MonodromyShell {
public:
  // symmetrized: the product is B x = (M x + R M(R z0) R x) / 2 (two integrations)
  PetscErrorCode Create(PeriodicFlow &flow, Vec z0, PetscReal T, PetscReal beta, bool symmetrized = false);
  Mat Get() const { return M_; }
  PetscInt Products() const { return products_; }
  PetscErrorCode Mult(Vec x, Vec y);

private:
  PeriodicFlow *flow_ = nullptr;
  Vec z0_ = nullptr;
  PetscReal T_ = 0, beta_ = 0;
  PetscInt products_ = 0;
  bool symmetrized_ = false;
  OwnedMat M_;
  OwnedVec zT_, zr_, xr_, yr_;
};

enum class FloquetMfWhich { Largest = 0, Critical = 1, Localized = 2 }; // Localized: stability/floquet_localized.hpp
struct FloquetMfOptions {
  PetscInt nev = 4;
  FloquetMfWhich which = FloquetMfWhich::Critical;
  // b within circle_tol of [-1, 1] counts as on the unit circle. Near b = +-1
  // the map b -> mu is a square root (|mu| - 1 ~ sqrt(2 (|b| - 1))), so an
  // eigenvalue error of 1e-10 would read as |mu| = 1 + 1.4e-5: the critical
  // route resolves instabilities down to sqrt(2 circle_tol) ~ 4.5e-5, the
  // dense route (all 2N multipliers) down to -floquet_tol.
  PetscReal circle_tol = 1e-9;
  PetscBool deflate = PETSC_TRUE; // deflate the trivial pair when the family tangent is known
  // Orbits with 2N <= dense_max take the dense route (FloquetLeadingDense):
  // where the 2N x 2N monodromy is affordable it is the only route whose
  // "stable" is a verdict (below), and at N = 102 it is also the cheaper one.
  PetscInt dense_max = 2048;
  LocalizedOptions loc; // -floquet_loc_* (which = localized)
};
PetscErrorCode FloquetMfOptionsFromOptions(MPI_Comm comm, FloquetMfOptions *o);

// The stability verdict a route can give (the `stable` column of floquet_mf).
// A Krylov method on M or B can prove an orbit unstable (a converged
// multiplier off the circle) but never stable: a complex quadruplet from a
// Krein collision inside the spectrum has b = (mu + 1/mu)/2 inside [-1, 1],
// where the critical route does not look, and "largest" on M does not separate
// |mu| = 1 + 1e-3 from the circle within an affordable Krylov space
// (benchmarks/README.md "Matrix-free Floquet inside the band"). Only the dense
// route, which has all 2N multipliers, says "stable".
enum FloquetVerdict : PetscInt { kUndecided = -1, kUnstable = 0, kStable = 1 };

struct LeadingMultipliers {
  std::vector<PetscReal> re, im;     // the multipliers (|mu| >= 1 member of each pair)
  PetscReal max_modulus = 0;         // NaN unless all nev converged
  PetscInt converged = 0;            // < nev: the rest are NaN (-floquet_mf_eps_max_it reached, or rejected)
  PetscInt spurious = 0;             // Ritz values Krylov-Schur called converged whose true residual rejected them
  std::vector<PetscReal> resolution; // matrix-free: how far |mu| - 1 of each is resolved (from its true residual)
  PetscInt products = 0;             // monodromy actions used (two per product of B)
  PetscInt verdict = kUndecided;
  std::vector<PetscInt> krein; // per multiplier: sign(-i v^H J v) as in FloquetResult; 0 when not computed (matrix-free)
  PetscInt instability = -1;   // the leading unstable eigenvector's class as in FloquetResult (0 stable); -1 not computed
  // dense route: the leading pair's eigenvector (the first of re, im): its participation ratio over
  // sites (floquet.hpp DisplacementParticipation) and edge share; NaN matrix-free (not computed)
  PetscReal leading_participation = NAN, leading_edge = NAN;
};

// warm (optional, in/out): eigenvectors of the previous orbit of a branch as
// the initial Krylov space; replaced by this orbit's. dz0 (optional): the
// state part of the family tangent at this orbit; with -floquet_mf_deflate the
// trivial pair is deflated and the nev multipliers returned are nontrivial.
// lead_re, lead_im (optional, state layout): the eigenvector of M for the
// accepted multiplier of largest modulus (on the critical route the eigenvector
// of B projected onto it: v = M x - x / mu); zero when none was accepted.
PetscErrorCode FloquetLeading(PeriodicFlow &flow, Vec z0, PetscReal T, PetscReal beta, const FloquetMfOptions &o, LeadingMultipliers *r,
                              std::vector<OwnedVec> *warm = nullptr, Vec dz0 = nullptr, Vec lead_re = nullptr, Vec lead_im = nullptr);

// The verdict of a matrix-free result at -floquet_tol tol: unstable when a
// converged multiplier lies beyond 1 + max(tol, its resolution), otherwise
// undecided.
PetscInt MatrixFreeVerdict(const LeadingMultipliers &r, PetscReal tol);

// The dense route's answer in the same form: all 2N multipliers of the
// monodromy (the first 2N columns of the sensitivity matrix S) on rank 0 by
// LAPACK (Hessenberg reduction and QR, eigenvalues only), the trivial pair
// (the two nearest 1) left out; the nev leading pairs, |mu| >= 1 member of
// each (upper half plane on the circle): the multipliers beyond 1 + tol by
// modulus, then those on the circle nearest +-1 (largest |Re mu|), as the
// critical route orders them. Only their eigenvectors are computed (inverse
// iteration on the Hessenberg form), for the Krein signatures and the kind.
// max_modulus: the largest nontrivial |mu|; verdict stable or unstable.
// lead_re, lead_im (optional, state layout): the leading multiplier's
// eigenvector when the orbit is unstable (for ConfirmGrowth); zero otherwise.
PetscErrorCode FloquetLeadingDense(const Lattice &lat, Mat S, PetscInt nev, const FloquetOptions &o, LeadingMultipliers *r, Vec lead_re = nullptr,
                                   Vec lead_im = nullptr);
// Refuses the dense route's monodromy (2N <= o.dense_max: 2N x 2N on rank 0)
// where it would not fit in memory; FloquetLeadingDense checks it, a study before any set-up.
PetscErrorCode CheckDenseMonodromyMemory(MPI_Comm comm, PetscInt N, const FloquetMfOptions &o);

// Its serial kernel: a (n x n, column-major, overwritten) on one process; uidx,
// vidx: the row of u_s and v_s for each site s (natural order); iface: the
// interface site (-1: no edge region). The leading pairs, their Krein
// signatures and edge shares, the largest nontrivial |mu| and the class.
struct LeadingPairs {
  std::vector<std::complex<PetscReal>> mu;
  std::vector<PetscInt> krein;
  std::vector<PetscReal> edge;
  PetscReal max_modulus = 0;
  PetscInt instability = 0;
  std::vector<PetscReal> lead_re, lead_im; // unstable: the leading pair's eigenvector in PETSc state order (else empty)
  PetscReal leading_participation = NAN, leading_edge = NAN; // of the first pair's eigenvector (NaN: none)
};
PetscErrorCode DenseLeadingPairs(PetscInt n, PetscReal *a, PetscInt nev, const FloquetOptions &o, const std::vector<PetscInt> &uidx,
                                 const std::vector<PetscInt> &vidx, PetscInt iface, LeadingPairs *out);

} // namespace nltopo
