#pragma once
// -cont_bifurcations: the events along a continued branch (stability/
// bifurcations.hpp), located between its points. Between two points X_i and
// X_{i+1} = (z0, T, beta) an orbit is found at any fraction sigma of the chord
// by the shooting Newton with the pseudo-arclength constraint
// d . (X - X_i - sigma (X_{i+1} - X_i)) = 0, d the unit chord, and the phase
// condition through z0_i; its Floquet multipliers (dense route) or dE/ds
// (from the family tangent there) are the test functions of the bisection.
#include "orbits/continuation.hpp"
#include "stability/bifurcations.hpp"
#include "stability/floquet.hpp"
#include <map>

namespace nltopo {

class BifurcationLocator {
public:
  PetscErrorCode Setup(Shooting &shoot, const FloquetOptions &fo, const BifurcationOptions &bo);
  // The events of branch b, given the dense Floquet multipliers of its points
  // (re, im: 2N per point, on every rank), in the order of the branch.
  // Prints one line per event (name: the branch label).
  // edge: each eigenvector's edge share, krein: each multiplier's Krein
  // signature (2N per point; empty: unknown). Segments before first_segment
  // are not searched (a switched family's first one starts at the singular
  // orbit of its parent's event, whose own change of stability it holds).
  PetscErrorCode Locate(const Branch &b, const std::vector<PetscReal> &re, const std::vector<PetscReal> &im, const std::vector<PetscReal> &edge,
                        const char *name, std::vector<BifurcationEvent> *events, const std::vector<PetscInt> &krein = {}, PetscInt first_segment = 0);
  PetscInt Probes() const { return probes_; }                    // orbits solved so far
  void SetProgress(PetscReal every) { progress_every_ = every; } // seconds between progress lines of Locate (-cont_progress)
  // The orbit X = (z0, T, beta) at sigma of a segment of the branch last
  // given to Locate (e.g. an event's point and sigma).
  PetscErrorCode OrbitAt(PetscInt segment, PetscReal sigma, Vec X, bool *converged);

private:
  PetscReal progress_every_ = 0;
  PetscErrorCode SetSegment(PetscInt i);
  // The orbit at sigma of the current segment; with floquet its multipliers
  // (and, given vec, the eigenvector nearest target), with tangent dE/ds and
  // (given tz) the state part of the family tangent in natural order.
  PetscErrorCode Probe(PetscReal sigma, bool floquet, bool tangent, BifurcationSample *s, const PetscReal *target = nullptr,
                       std::vector<PetscReal> *vec = nullptr, std::vector<PetscReal> *tz = nullptr);
  PetscErrorCode Predict(PetscReal sigma, Vec X);
  PetscErrorCode Remember(PetscReal sigma, Vec X);
  void Place(PetscInt seg, const BifurcationSample &a, const BifurcationSample &c, BifurcationEvent *e) const;
  PetscErrorCode Folds(const Branch &b, PetscInt first_segment, std::vector<BifurcationEvent> *ev);
  PetscErrorCode StabilityChanges(PetscInt i, std::vector<BifurcationEvent> *ev);
  // Krein collisions of equal signature (kind 4) and internal resonances
  // (kind 6) in segment i, whose ends have multipliers fi and fj.
  PetscErrorCode Passes(PetscInt i, const FloquetResult &fi, const FloquetResult &fj, std::vector<BifurcationEvent> *ev);
  PetscErrorCode Resonances(PetscInt i, const FloquetResult &fi, const FloquetResult &fj, std::vector<BifurcationEvent> *ev);
  // The orbit last probed over half its period: whether z(T/2) = -z(0)
  // (to 1e-6 relative), and the multipliers of the half-period monodromy.
  PetscErrorCode HalfPeriod(bool *symmetric, FloquetResult *half);
  PetscErrorCode Report(const char *name, PetscInt k, const BifurcationEvent &e);

  Shooting *shoot_ = nullptr;
  FloquetOptions fo_;
  BifurcationOptions bo_;
  PetscInt N_ = 0, seg_ = -1, probes_ = 0;
  std::vector<PetscReal> rows_, period_, beta_, s_; // z0 rows of every point (every rank), arclength at each point
  OwnedVec Xa_, Xb_, d_, X_, Xpred_, t_, z_, za_, zT_, tz_, g_;
  OwnedMat S_;
  bool seed_ = false; // S_ holds the last probe's monodromy: the next probe's chord Jacobian (ShootingSolver::SeedJacobian)
  PetscReal chord_ = 0;
  PetscReal vectors_ = -1; // >= 0: probes also keep the circle eigenvectors of at least this edge share (FloquetResult::vectors)
  PetscReal last_T_ = 0, last_beta_ = 0;
  PetscInt passes_avoided_ = 0, resonances_undriven_ = 0; // candidates that proved not to be events
  PetscReal min_edge_ = 0;                                // outside multipliers with a smaller edge share are not tracked (B-B, unless -cont_bif_bulk)
  // orbits solved in each segment of the branch (sigma, local X): the predictors (kept for OrbitAt: at a
  // branch point only a start on the orbit itself keeps Newton from drifting along the near-null direction)
  std::map<PetscInt, std::vector<std::pair<PetscReal, std::vector<PetscScalar>>>> solved_;
};

} // namespace nltopo
