#pragma once
// Bifurcations along a family of periodic orbits of a Hamiltonian system
// (docs/continuation.md "Bifurcations along a branch"): the events -cont_bifurcations reports, the
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
//
// Two events leave the set outside the circle as it is, and are found apart:
//   Krein collisions of equal signature (kind 4): two pairs on the circle
//     meet and pass. Sorted by angle the spectrum looks the same before and
//     after, so the members are told apart by their eigenvectors (overlap
//     with those at the segment's start); where the tracked pairs' order of
//     angle flips, the signed difference of their angles is the test function.
//     Where it only jumps (the eigenvectors swap character: an avoided
//     crossing, the generic case between pairs of one symmetry class) there
//     is no collision and nothing is reported.
//   Internal resonances (kind 6): a pair crosses e^{2 pi i p/q}, 3 <= q <=
//     -cont_bif_resonance_order (q = 1, 2 are the branch point and the period
//     doubling). An orbit with the half-period symmetry z(t + T/2) = -z(t)
//     (the families continued from linear modes of this lattice: the force
//     is odd in u; switched families may break it) has a T/2-periodic
//     tangent, so its monodromy is the square of the half-period one, whose
//     multiplier nu on the same eigenvector fixes the perturbation's frequency
//     omega_j modulo 2 omega (nu = e^{i pi omega_j/omega}). A resonance
//     q omega_j = n omega is driven by a term of the expansion in the
//     perturbation of degree q - 1 times a harmonic n of the orbit; the force
//     is odd, so that term has an odd total degree and n = q mod 2. For a
//     root of order exactly q (n prime to q) this leaves odd q only, with
//     nu^q = (-1)^q: the half-period map's multiplier rho = -nu is itself a
//     q-th root of unity. The other crossings are resonances no harmonic of
//     the orbit drives, and are not reported.
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
  PetscInt index; // in the FloquetResult
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

// The nontrivial multipliers on the circle (||mu| - 1| <= tol) in the open
// upper half plane with an edge share of at least min_edge (all when r has
// none): (index, angle), by angle.
std::vector<std::pair<PetscInt, PetscReal>> UpperCircle(const FloquetResult &r, PetscReal tol, PetscReal min_edge = 0);

// Pairs of circle multipliers that may pass each other between orbits a and
// c (kind 4): neighbours in angle at both, of equal nonzero signature at a
// (when a has krein), closer at both than twice the largest move of a
// member from a to c. Their angles at a, lower first.
std::vector<std::pair<PetscReal, PetscReal>> PassCandidates(const FloquetResult &a, const FloquetResult &c, PetscReal tol, PetscReal min_edge = 0);
// The members of x that continue members ia and ib of ref (both with
// r.vectors): the largest |overlap| of their eigenvectors, ja != jb. Returns
// the smaller of the two overlaps (0: x has no vectors to compare).
PetscReal TrackPair(const FloquetResult &ref, PetscInt ia, PetscInt ib, const FloquetResult &x, PetscInt *ja, PetscInt *jb);
// The member j of x that continues member i of ref, by the same overlap;
// returns that overlap (0: none to compare).
PetscReal TrackMember(const FloquetResult &ref, PetscInt i, const FloquetResult &x, PetscInt *j);

// The roots of unity e^{2 pi i p/q} in the open upper half plane of order q,
// 3 <= q <= max_order: (p, q) by angle.
std::vector<std::pair<PetscInt, PetscInt>> ResonanceRoots(PetscInt max_order);
// How many members of UpperCircle(r, tol, min_edge) lie below angle.
PetscInt CountBelow(const FloquetResult &r, PetscReal angle, PetscReal tol, PetscReal min_edge = 0);
// Whether the orbit's harmonics drive the crossing of mu = e^{2 pi i p/q} by
// a pair whose half-period multiplier nu (nu^2 = mu) is given (see above):
// q odd and nu^q nearer (-1)^q than -(-1)^q.
bool ResonanceDriven(PetscInt q, PetscReal nu_re, PetscReal nu_im);
// The multiplier nu of the half-period monodromy (half, with its circle
// vectors) on eigenvector v of the monodromy: the member whose eigenvector
// (or its conjugate, for nu in the lower half plane) overlaps v most. Returns
// that overlap.
PetscReal HalfPeriodMultiplier(const FloquetResult &half, const std::vector<std::complex<PetscReal>> &v, PetscReal *nu_re, PetscReal *nu_im);

struct BifurcationOptions {
  PetscBool enabled = PETSC_FALSE; // -cont_bifurcations (on with the dense -floquet unless set)
  PetscReal tol = 1e-7;            // bracket of a located event: omega within tol, E within tol E
  PetscInt max_probes = 60;        // orbits solved at most to locate one event
  PetscReal angle_tol = 0.15;      // multipliers of two orbits closer in angle than this are the same
  PetscBool bulk = PETSC_FALSE;    // also events of bulk (B-B) eigenvectors
  PetscBool passes = PETSC_TRUE;   // Krein collisions of equal signature (kind 4)
  PetscInt resonance_order = 4;    // internal resonances up to this order q (kind 6); < 3: none
};
// dense_floquet: whether every orbit gets all its multipliers (-floquet
// without -floquet_mf), which the events are read from; the default.
PetscErrorCode BifurcationOptionsFromOptions(MPI_Comm comm, PetscBool dense_floquet, BifurcationOptions *o);

// One located event (outputs.md /continuation/<branch>/bifurcations).
struct BifurcationEvent {
  EventKind kind = EventKind::Fold;
  PetscInt direction = 0;                 // +1: a pair leaves the circle (fold: E has a maximum) along the branch; -1: returns (minimum)
  PetscInt point = 0;                     // the continuation point the event follows
  PetscReal energy = 0, omega = 0, s = 0; // at the located point; s: arclength from the first point
  PetscReal omega_bracket = 0;            // width in omega of the final bracket
  PetscReal mu_re = 1, mu_im = 0;         // the critical multiplier (just off the circle)
  PetscInt krein[2] = {0, 0};             // signatures of the colliding pairs (upper-half-plane members), on the circle side
  PetscInt instability = 0;               // localisation of the critical eigenvector: 1 B-B, 2 B-E, 3 E-E (0 fold)
  std::vector<PetscReal> vector;          // the critical eigenvector (2N, natural order; fold: the family tangent)
  PetscReal sigma = 0;                    // the located point in its segment (BifurcationLocator::OrbitAt)
  PetscInt resonance[2] = {0, 0};         // kind 6: p, q of the root e^{2 pi i p/q} crossed
};

// One probed orbit of a segment between two continuation points.
struct BifurcationSample {
  PetscReal sigma = 0; // position in the segment, 0 .. 1
  PetscReal omega = 0, energy = 0;
  PetscReal dEds = 0; // fold test function
  FloquetResult fr;   // the multipliers there (when probed with them)
  std::vector<Outside> out;
  bool ok = true;          // false: the orbit was not found there (Newton failed)
  PetscReal aux = NAN;     // the test function of a search that is not about fr's outside set (kinds 4, 6)
  PetscInt aux_index = -1; // and the member of fr it was measured on
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

// A search on members followed by their eigenvectors from a0 (kinds 4, 6;
// a0 and c0's fr carry vectors, and so must every probe's).
enum class TrackedOutcome {
  Untracked,  // a member was not found again at c0 (overlap < 1/2)
  NoCrossing, // the test function has one sign at a0 and c0
  NotLocated, // a probe failed or max_probes were spent
  Avoided,    // it jumps through its change of sign (the eigenvectors swapped character)
  Crossed     // it goes through zero: located in [a, c]
};
// Kind 4: members ia and ib of a0.fr pass each other (test function: the
// angle of ia's continuation minus ib's).
PetscErrorCode LocatePass(const SampleProbe &probe, const BifurcationSample &a0, const BifurcationSample &c0, PetscInt ia, PetscInt ib, PetscReal tol,
                          PetscInt max_probes, BifurcationSample *a, BifurcationSample *c, PetscInt *probes, TrackedOutcome *out);
// Kind 6: member ia of a0.fr crosses e^{i angle} (its angle minus angle).
PetscErrorCode LocateRootCrossing(const SampleProbe &probe, const BifurcationSample &a0, const BifurcationSample &c0, PetscInt ia, PetscReal angle,
                                  PetscReal tol, PetscInt max_probes, BifurcationSample *a, BifurcationSample *c, PetscInt *probes, TrackedOutcome *out);

} // namespace nltopo
