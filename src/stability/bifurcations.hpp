#pragma once
// Bifurcations along a family of periodic orbits of a Hamiltonian system
// (README.md "Bifurcations"): the events -cont_bifurcations reports, the
// multiplier bookkeeping they rest on, and the search that locates them.
//
// The multipliers of a Hamiltonian orbit come as mu, 1/mu, conj(mu),
// 1/conj(mu); two of them sit at +1 (the trivial pair: the flow direction and
// the family tangent). Along a one-parameter family a pair can leave the unit
// circle only
//   through +1: a branch point (a real pair > 1 appears; at an energy fold
//               the trivial block at +1 grows instead),
//   through -1: a period doubling (a real pair < -1),
//   or where two pairs on the circle collide: by the Krein rule, pairs of
//   opposite signature may leave it as a complex quadruplet
//   (Hamiltonian-Hopf), pairs of equal signature cannot and pass (Krein 1950;
//   MacKay, in "Hamiltonian dynamical systems", 1987).
// So the set of nontrivial multipliers outside the circle changes at these
// events (and where two unstable ones meet off the circle, e.g. two real
// pairs turning into a quadruplet: reported as one ending and one beginning). Each orbit's set (one representative per pair or quadruplet,
// by kind and angle) is compared between orbits; where it changes, the event
// is located on a test function that is smooth through it: near a
// collision at e^{i theta*} the two colliding multipliers are
// e^{i theta* +- sqrt(c (s* - s))}, so G = (theta_1 - theta_2)^2 on the circle
// side and G = -(2 ln |mu|)^2 off it are one linear function of s. Energy
// folds are located on dE/ds.
#include "stability/floquet.hpp"
#include <petscsys.h>
#include <functional>
#include <vector>

namespace nltopo {

// outputs.md /continuation/<branch>/bifurcations "kind".
enum class EventKind : PetscInt { Fold = 1, BranchPoint = 2, PeriodDoubling = 3, KreinCollision = 4, HamiltonianHopf = 5, Resonance = 6 };
const char *EventKindName(EventKind k);

// The indices of all but the trivial pair: the two multipliers with the
// smallest |(mu + 1/mu)/2 - 1|, a quantity in which the rounding split of the
// Jordan block at +1 enters squared.
std::vector<PetscInt> NontrivialIndices(const PetscReal *re, const PetscReal *im, PetscInt n);

// A nontrivial multiplier outside the circle (|mu| > 1 + tol), one per real
// pair (the one > 1 in modulus) or quadruplet (the one in the upper half plane).
struct Outside {
  EventKind kind;  // BranchPoint (real > 1), PeriodDoubling (real < -1), HamiltonianHopf (complex)
  PetscReal angle; // arg mu in [0, pi]
  PetscReal modulus;
  PetscInt index;  // in the FloquetResult
};
// min_edge > 0: only those whose eigenvector has at least this share of its
// displacement norm in the edge region (r.edge; all when r has none).
std::vector<Outside> OutsideMultipliers(const FloquetResult &r, PetscReal tol, PetscReal min_edge = 0);
// Whether two sets hold the same multipliers: as many of each kind, each
// within angle_tol of its partner.
bool SameOutside(const std::vector<Outside> &a, const std::vector<Outside> &b, PetscReal angle_tol);
// The members of b without a partner in a (born from a to b) and of a without
// one in b (died), as (member, +1 born / -1 died).
std::vector<std::pair<Outside, PetscInt>> OutsideChanges(const std::vector<Outside> &a, const std::vector<Outside> &b, PetscReal angle_tol);

// The test function of a collision of the given kind at e^{i angle} on the
// multipliers r (see above); NaN if r has no pair to measure it on.
PetscReal CollisionFunction(const FloquetResult &r, EventKind kind, PetscReal angle, PetscReal tol, PetscReal angle_tol, PetscReal min_edge = 0);
// The signatures of the two colliding pairs' members on the circle side r
// (upper half plane first; at +-1 the pair's two members), by the sign of
// their Krein values.
void CollidingSignatures(const FloquetResult &r, EventKind kind, PetscReal angle, PetscReal tol, PetscInt krein[2], PetscReal min_edge = 0);

// The Krein rule for two pairs that meet on the unit circle, given the
// signatures of their members in the upper half plane: opposite signatures
// give a Hamiltonian-Hopf collision (the pairs leave the circle), equal ones
// a Krein collision the pairs pass through.
EventKind KreinCollisionOutcome(PetscInt k1, PetscInt k2);

struct BifurcationOptions {
  PetscBool enabled = PETSC_FALSE; // -cont_bifurcations (on with the dense -floquet unless set)
  PetscReal tol = 1e-7;            // bracket of a located event: omega within tol, E within tol E
  PetscInt max_probes = 60;        // orbits solved at most to locate one event
  PetscReal angle_tol = 0.15;      // multipliers of two orbits closer in angle than this are the same
  PetscBool bulk = PETSC_FALSE;    // also events of bulk (B-B) eigenvectors
};
// dense_floquet: whether every orbit gets all its multipliers (-floquet
// without -floquet_mf), which the events are read from; the default.
PetscErrorCode BifurcationOptionsFromOptions(MPI_Comm comm, PetscBool dense_floquet, BifurcationOptions *o);

// One located event (outputs.md /continuation/<branch>/bifurcations).
struct BifurcationEvent {
  EventKind kind = EventKind::Fold;
  PetscInt direction = 0;   // +1: a pair leaves the circle (fold: E has a maximum) along the branch; -1: returns (minimum)
  PetscInt point = 0;       // the continuation point the event follows
  PetscReal energy = 0, omega = 0, s = 0; // at the located point; s: arclength from the first point
  PetscReal omega_bracket = 0;            // width in omega of the final bracket
  PetscReal mu_re = 1, mu_im = 0;         // the critical multiplier (just off the circle)
  PetscInt krein[2] = {0, 0};             // signatures of the colliding pairs (upper-half-plane members), on the circle side
  PetscInt instability = 0;               // localisation of the critical eigenvector: 1 B-B, 2 B-E, 3 E-E (0 fold)
  std::vector<PetscReal> vector;          // the critical eigenvector (2N, natural order; fold: the family tangent)
  PetscReal sigma = 0;                    // the located point in its segment (BifurcationLocator::OrbitAt)
};

// One probed orbit of a segment between two continuation points.
struct BifurcationSample {
  PetscReal sigma = 0; // position in the segment, 0 .. 1
  PetscReal omega = 0, energy = 0;
  PetscReal dEds = 0;  // fold test function
  FloquetResult fr;    // the multipliers there (when probed with them)
  std::vector<Outside> out;
  bool ok = true;      // false: the orbit was not found there (Newton failed)
};
using SampleProbe = std::function<PetscErrorCode(PetscReal sigma, BifurcationSample *)>;

// Locates where same(a, x) stops holding between a and c (a.sigma < c.sigma,
// !same(a, c)): Illinois steps on the test function G(a, c, x) (smooth
// through the change, opposite signs at a and c; NaN: not available), a
// bisection after any step that did not halve the bracket; a probe where
// Newton fails is retried a quarter bracket aside. On return same(a, c) is
// false and |omega_c - omega_a| <= tol, |E_c - E_a| <= tol |E_c| (converged),
// or max_probes were spent or a probe failed (not converged).
using SamePredicate = std::function<bool(const BifurcationSample &a, const BifurcationSample &x)>;
using TestFunction = std::function<PetscReal(const BifurcationSample &a, const BifurcationSample &c, const BifurcationSample &x)>;
PetscErrorCode LocateChange(const SampleProbe &probe, const SamePredicate &same, const TestFunction &G, PetscReal tol, PetscInt max_probes,
                            BifurcationSample *a, BifurcationSample *c, PetscInt *probes, bool *converged);

} // namespace nltopo
