#pragma once
// Scaling of Floquet instabilities with the lattice size N (issue 35, "Scaling
// with N"; docs/long-lattices.md "Does the instability persist? Scaling with
// N"). Instability bubbles open and close along a branch as band modes move
// through the edge modes' multipliers, so a single orbit's |mu| - 1 is not
// comparable between lattices: the envelope is. Per energy window, the
// envelope at each N is the largest |mu| - 1 over the window's orbits, and
// it is fitted as C N^-p by least squares in log-log. The literature's two
// kinds (Marin, Aubry & Floria, Physica D 113 (1998) 283): an instability
// whose eigenvector keeps weight at the interface (a localised mode meeting
// the band) persists as N grows (p ~ 0); one from the collision of two
// extended band pairs weakens as the band modes' amplitude at the orbit does
// (p ~ 1).
#include <petscsys.h>
#include <vector>

namespace nltopo {

// The verdict of one window (the integer `verdict` of /floquet_scaling/windows).
enum ScalingVerdict : PetscInt {
  kScalingStable = 0,        // no orbit of the window beyond 1 + tol at any N
  kScalingPersists = 1,      // p < p_persist: the envelope does not fall like a finite-size effect
  kScalingFiniteSize = 2,    // p >= p_persist
  kScalingUndetermined = 3,  // fewer than two N with an unstable orbit, or p_persist within one standard error of p
};
const char *ScalingVerdictName(PetscInt v);
// "0 stable; 1 persists; ..." for the schema's codes.
extern const char *const kScalingVerdictCodes;

struct EnvelopeFit {
  PetscReal p = NAN, C = NAN;  // envelope ~ C N^-p
  PetscReal r2 = NAN;          // coefficient of determination of the log-log fit (1 with two points; NaN with fewer)
  PetscReal residual = NAN;    // root mean square of the log residuals, ln(envelope / (C N^-p))
  PetscReal p_stderr = NAN;    // standard error of p (NaN with two points or fewer)
  PetscInt npoints = 0;        // N with an unstable orbit in the window (envelope > tol): the points fitted
  PetscInt verdict = kScalingUndetermined;
};

// envelope[k]: the window's largest |mu| - 1 at size N[k] (NaN: no orbit of
// the branch in the window at that N). Points with envelope <= tol (stable
// there) are left out of the fit.
EnvelopeFit FitEnvelope(const std::vector<PetscReal> &N, const std::vector<PetscReal> &envelope, PetscReal tol, PetscReal p_persist);

// The window's envelope of one branch: the largest max_modulus - 1 over the
// orbits with lo <= energy < hi, its index (-1: no orbit there; NaN-modulus
// orbits are skipped).
PetscInt WindowMaximum(const std::vector<PetscReal> &energy, const std::vector<PetscReal> &max_modulus, PetscReal lo, PetscReal hi, PetscReal *envelope);

} // namespace nltopo
