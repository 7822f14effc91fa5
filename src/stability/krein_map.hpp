#pragma once
// The Krein resonance map (issue 35, item 4): where along a branch of periodic
// orbits opposite-signature Floquet collisions can occur, from the linear
// dispersion alone, before any eigensolver runs.
//
// Far from the orbit the tangent flow is the linear lattice's: a mode of
// frequency w_q has the multiplier pair exp(+-i w_q T), the + member of
// positive Krein signature. Two pairs of opposite signature meet on the unit
// circle where exp(i w_q T) = exp(-i w_q' T), i.e.
//
//     w_q + w_q' = k Omega,   Omega = 2 pi / T,  k = 1, 2, ...
//
// (q = q' included: the parametric resonance 2 w_q = k Omega). Same-signature
// meetings (w_q - w_q' = k Omega) pass without harm (MacKay & Saffman, Proc. R.
// Soc. A 406 (1986) 115; Marin, Aubry & Floria, Physica D 113 (1998) 283). The
// lattice's linear frequencies: the acoustic band A and the optical band O of
// the infinite lattice (bands/bloch.hpp) and the finite lattice's localised
// modes E, the eigenvalues of K outside both bands (edge and interface modes,
// found by Sturm bisection on the tridiagonal K: O(N) once per run). For each
// orbit and k the map records which of the pair classes AA, AO, OO, EA, EO, EE
// can resonate: a band class when k Omega lies in its interval of sums (e.g.
// AO: [a_bottom + o_bottom, a_top + o_top]); the point class EE when
// e + e' = k Omega was crossed between the previous orbit and this one. The
// branch's own linear mode is not an E mode of its tangent flow (its pair is
// the trivial one at 1): one localised frequency equal to the branch's linear
// frequency (to 1e-6 relative) is left out.
//
// Near the interface the orbit stiffens the bonds, so the interface modes'
// frequencies move with the amplitude: the E entries are those of the linear
// lattice, a guide, not a verdict (docs/long-lattices.md "Where to expect
// trouble: the Krein resonance map").
//
// The energy criterion (Kevrekidis, Cuevas-Maraver & Pelinovsky, PRL 117,
// 094101 (2016), arXiv:1604.06956): along a family of breathers a real pair of
// multipliers passes through +1 where dE/dOmega = 0. The map flags the orbits
// where dE/dOmega changes sign: at an extremum of E (through 0, the criterion)
// or of Omega (through infinity).
#include "bands/bloch.hpp"
#include "lattice/lattice.hpp"
#include <string>
#include <vector>

namespace nltopo {

// The bits of a resonance mask (schema codes::kKreinPairs).
enum KreinPairBit : PetscInt { kPairAA = 1, kPairAO = 2, kPairOO = 4, kPairEA = 8, kPairEO = 16, kPairEE = 32 };
constexpr int kKreinPairClasses = 6;
extern const char *const kKreinPairNames[kKreinPairClasses]; // "AA", "AO", ... in bit order

// The linear frequencies the map uses.
struct KreinSpectrum {
  BandEdges bands;                  // the infinite lattice's (rad/time)
  std::vector<PetscReal> localized; // the finite lattice's frequencies outside both bands, ascending
};
// bands from lat's parameters, localized by Sturm bisection on K (collective: K is gathered on every rank).
PetscErrorCode KreinSpectrumSetup(const Lattice &lat, KreinSpectrum *s);
// The number of eigenvalues of the symmetric tridiagonal (d, e) below x (Sturm count; e[i] couples i and i + 1).
PetscInt SturmCount(const std::vector<PetscReal> &d, const std::vector<PetscReal> &e, PetscReal x);
// The eigenvalues of (d, e) in the open interval (lo, hi), ascending, to ~1e-15 relative.
std::vector<PetscReal> TridiagonalEigenvaluesIn(const std::vector<PetscReal> &d, const std::vector<PetscReal> &e, PetscReal lo, PetscReal hi);

// The E modes of a branch's tangent flow: s.localized without one copy of its
// own linear frequency omega_lin (within 1e-6 relative; none removed if none is).
std::vector<PetscReal> BranchEdgeModes(const KreinSpectrum &s, PetscReal omega_lin);

// The resonance mask at the sum k Omega = sum for the band classes; EE is set
// when some e + e' lies in [min(sum, sum_prev), max(sum, sum_prev)] (sum_prev
// = sum: equal to rounding).
PetscInt OpenResonances(const BandEdges &b, const std::vector<PetscReal> &edges, PetscReal sum, PetscReal sum_prev);
// The largest possible sum w_q + w_q' (twice the highest frequency).
PetscReal LargestSum(const BandEdges &b, const std::vector<PetscReal> &edges);

// The energy criterion's flag per point of a branch (E, Omega in branch
// order): bit 1 where E has a strict extremum there (dE/dOmega through 0),
// bit 2 where Omega has one (through infinity); 0 at the ends.
std::vector<PetscInt> EnergyCriterionFlags(const std::vector<PetscReal> &E, const std::vector<PetscReal> &Omega);
// dE/dOmega per point by the (non-uniform) central difference along the branch, one-sided at the ends; NaN with one point.
std::vector<PetscReal> EnergySlope(const std::vector<PetscReal> &E, const std::vector<PetscReal> &Omega);

// A branch's map: open[i * kmax + (k - 1)] is the mask of orbit i at k.
struct KreinMap {
  PetscInt kmax = 0;
  std::vector<PetscReal> edges; // the E frequencies used
  std::vector<PetscInt> open, criterion;
  std::vector<PetscReal> slope;
};
// E and period per orbit of a branch, omega_lin its linear frequency.
KreinMap ComputeKreinMap(const KreinSpectrum &s, PetscReal omega_lin, const std::vector<PetscReal> &E, const std::vector<PetscReal> &period);
// One line: where along the branch each class opens (Omega intervals) and where dE/dOmega changes sign.
std::string KreinMapSummary(const KreinMap &m, const BandEdges &b, const std::vector<PetscReal> &E, const std::vector<PetscReal> &period);

} // namespace nltopo
