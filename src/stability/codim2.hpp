#pragma once
// -cont_codim2: two-parameter continuation of a located event (issue 37;
// docs/continuation.md "Two-parameter continuation"). An event of a branch
// (stability/bifurcations.hpp kinds) is followed as a curve in (E, p), p one
// of the lattice's options (-lattice_gamma, -lattice_k, -lattice_cubic).
//
// The curve is the zero set of the kind's scalar test function g(q, p) in the
// plane of the orbit's coordinate q and p: at given (q, p) the orbit is found
// by the shooting Newton (q fixed by its constraint) on the lattice rebuilt at
// p, and g is evaluated there (block elimination of the minimally augmented
// system [orbit rows; g; arclength] in (X, p)). Pseudo-arclength in the scaled
// plane y = (ln(q / q0), p / p0) follows it: tangent orthogonal to grad g (finite
// differences), predictor, Newton corrector on [g; tau . (y - y_pred)].
//
// Implemented: kind 1, the energy fold, g = d ln E / d ln omega along the
// family at fixed p, q = omega (at a fold E does not fix the orbit, omega does);
// kind 2, the branch point, g = b - 1 of the nontrivial pair nearest +1, q = E;
// kind 3, the period doubling, g = b + 1, b = (mu + 1/mu)/2 of the pair
// nearest -1, q = E; kind 5, the Hamiltonian-Hopf onset, g = the discriminant
// (b1 - b2)^2 of the two colliding pairs' b, q = E.
#include "orbits/shooting.hpp"
#include "stability/bifurcations.hpp"
#include "stability/floquet.hpp"
#include <complex>
#include <string>
#include <vector>

namespace nltopo {

// The second parameter: a lattice option (its name without the dash: lattice_gamma, ...).
enum class Codim2Parameter { Gamma = 0, K = 1, Cubic = 2 };
const char *Codim2ParameterOption(Codim2Parameter p); // "-lattice_gamma", "-lattice_k", "-lattice_cubic"
PetscReal Codim2ParameterValue(const LatticeParams &lp, Codim2Parameter p);
void SetCodim2Parameter(LatticeParams *lp, Codim2Parameter p, PetscReal value);

struct Codim2Options {
  std::string spec; // -cont_codim2 <branch>:<kind>@<omega> ("" none)
  Codim2Parameter parameter = Codim2Parameter::Gamma;
  PetscReal pmin = -1e6, pmax = 1e6; // bounds of p (the parameter's own range applies too)
  PetscReal step = 0.02;             // first step, in the scaled plane (ln(q / q0), p / p0)
  PetscReal step_min = 1e-4, step_max = 0.1;
  PetscInt max_points = 60;  // per direction from the event
  PetscReal tol = 1e-10;     // corrector: the last Newton step in the scaled plane
  PetscReal test_tol = 1e-7; // and |g| / |grad g| at the converged point (the distance to the curve, scaled plane)
  PetscReal emin = 0, emax = 1e12; // the curve stops once E leaves [emin, emax] (that point kept)
  PetscBool verbose = PETSC_TRUE;
};

// -cont_codim2, parsed: the branch and the kind and nearest omega of its event.
struct Codim2Spec {
  std::string text, branch; // the item as given; a -cont_branch entry
  EventKind kind = EventKind::Fold;
  PetscReal omega = 0;
  bool Given() const { return !text.empty(); }
};
// Reads the -cont_codim2_* options; a malformed -cont_codim2, or kind 4 or 6
// (no boundaries of stability), is refused with one line naming the option and the value.
PetscErrorCode Codim2OptionsFromOptions(MPI_Comm comm, Codim2Options *o, Codim2Spec *s);
PetscErrorCode ParseCodim2Spec(MPI_Comm comm, const std::string &text, Codim2Spec *s);

// The codim-2 points of a curve (point_kind of /continuation/<branch>/codim2/<curve>; the codes of io/schema.hpp codes::kCodim2Point).
enum class Codim2PointKind : PetscInt {
  End = 0,            // an end of the curve not classified below (a bound, -cont_codim2_max_points, step collapse: stop_reason)
  Turn = 1,           // a turn in p: dp/ds = 0, the curve goes on through it
  CollisionPlus = 2,  // a Hamiltonian-Hopf curve ends where the colliding pairs' b reaches +1 (1:1 resonance)
  CollisionMinus = 3, // ... reaches -1 (1:2 resonance)
  LinearLimit = 4     // the curve ends as E -> 0 (the linear limit)
};

// One curve: /continuation/<branch>/codim2/<name> of outputs.md.
struct Codim2Curve {
  std::string name; // <tag><event>, e.g. fold3
  EventKind kind = EventKind::Fold;
  PetscInt event = 0;
  Codim2Parameter parameter = Codim2Parameter::Gamma;
  static constexpr PetscInt kMultipliers = 4;                                       // written per point: the multipliers nearest the kind's critical point
  std::vector<PetscReal> p, energy, omega, period, test, max_modulus, mu_re, mu_im; // mu: npts x kMultipliers
  PetscInt event_point = 0;                                                         // the row of the event itself
  std::vector<PetscInt> point_kind;                                                 // its codim-2 points (Codim2PointKind), in order of point_arc
  std::vector<PetscReal> point_p, point_energy, point_omega, point_arc;             // point_arc: the fractional row along the curve
  std::string stop_reason;
  PetscInt solves = 0; // orbits solved
  PetscReal seconds = 0;
};

// A curve's fields to bytes (put) or from them, in one order (a curve
// followed by one group of ranks, sent to the others).
class Bytes;
void Codim2CurveFields(Codim2Curve &c, Bytes &w, bool put);

// The orbit of an event: z0 in natural order [u, v] (every rank), T, beta.
struct Codim2Start {
  std::vector<PetscReal> z0;
  PetscReal period = 0, beta = 0, omega = 0, energy = 0;
};

// Follows the curve of event e (index event of its branch, orbit start, on
// the lattice base at its own value of o.parameter) in both directions of p.
// fo, so: the orbit solver's options (the dense Jacobian); flo: Floquet's;
// period_multiple: the flow's period multiple on the branch; name: the
// branch label (messages). A stop signal returns PETSC_ERR_SIG.
PetscErrorCode ContinueCodim2(MPI_Comm comm, const LatticeParams &base, const FlowOptions &fo, const ShootingOptions &so, const FloquetOptions &flo,
                              PetscInt period_multiple, const Codim2Options &o, const BifurcationEvent &e, PetscInt event, const Codim2Start &start,
                              const char *name, Codim2Curve *curve);

// ---- The curve follower, on any scalar test function of the scaled plane ----
// The orbit-based test functions (codim2.cpp) are one implementation; a closed
// form is another (tests/unit/test_codim2.cpp).

// One sample of the test function g at the point (a, b) of the scaled plane.
struct Codim2Sample {
  bool ok = false;        // g was evaluated (a finite number)
  PetscReal a = 0, b = 0; // the point: (ln(q / q0), p / p0) for an orbit
  PetscReal omega = 0, p = 0, energy = 0, period = 0, beta = 0, g = NAN;
  PetscReal bmid = 0;        // kind 5: the middle of the two colliding pairs' b (kind 3: -1, kind 1: +1)
  std::vector<PetscReal> z0; // the orbit (natural order, every rank); empty for a closed form
  std::vector<std::complex<PetscReal>> mu; // the orbit's multipliers (all 2N, as the test function computed them); empty for a closed form
  std::vector<PetscReal> basis;            // kind 5: the colliding pairs' invariant subspace (2N x 4, rank 0; stability/collision_subspace.hpp)
};

class Codim2Function {
public:
  virtual ~Codim2Function() = default;
  // g at (a, b) into *x (x->a, x->b: the point actually reached); from: a nearby sample (the Newton guess of an orbit)
  virtual PetscErrorCode Sample(PetscReal a, PetscReal b, const Codim2Sample &from, Codim2Sample *x) = 0;
  // x is a new point of the curve (kind 5: the collision's b moves along it)
  virtual void Accept(const Codim2Sample &x) { (void)x; }
  // whether bmid is the collision of two pairs (kind 5): a curve that ends with |bmid| near 1 ends at +-1
  virtual bool Collision() const { return false; }
};

// A curve followed from a start point in both directions of p.
struct Codim2Trace {
  std::vector<Codim2Sample> pts; // in order along the curve: the side where p first decreases (reversed), the start, the other side
  PetscInt start = 0;            // the row of the start point
  struct Point {
    Codim2PointKind kind;
    Codim2Sample x; // the curve there
    PetscReal arc;  // fractional row of pts
  };
  std::vector<Point> points;    // sorted by arc
  std::string why_down, why_up; // why each side ended
  PetscInt its = 0;             // corrector iterations at the start point
  bool started = false;         // the start point was corrected onto the curve (at its b)
};

// Corrects guess onto g = 0 at its b (p fixed), then walks both ways by
// pseudo-arclength (-cont_codim2_* of o: steps, tolerances, p bounds on the
// samples' p, max points), detecting and locating the turns in p and
// classifying both ends. label: the messages' prefix.
PetscErrorCode FollowCodim2(MPI_Comm comm, Codim2Function &f, const Codim2Options &o, const Codim2Sample &guess, const char *label, Codim2Trace *t);

// Where two curves' polylines (p, E) cross, by linear interpolation within the
// segments: p, E there and the fractional rows arc1, arc2 of either curve.
struct Codim2Crossing {
  PetscReal p, energy, arc1, arc2;
};
std::vector<Codim2Crossing> Codim2Intersections(const std::vector<PetscReal> &p1, const std::vector<PetscReal> &e1, const std::vector<PetscReal> &p2,
                                                const std::vector<PetscReal> &e2);

} // namespace nltopo
