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
// plane y = (q / q0, p / p0) follows it: tangent orthogonal to grad g (finite
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
  PetscReal step = 0.02;             // first step, in the scaled plane (q / q0, p / p0)
  PetscReal step_min = 1e-6, step_max = 0.1;
  PetscInt max_points = 60;  // per direction from the event
  PetscReal tol = 1e-10;     // corrector: the last Newton step in the scaled plane
  PetscReal test_tol = 1e-7; // and |g| / |grad g| at the converged point (the distance to the curve, scaled plane)
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

// One curve: /continuation/<branch>/codim2/<name> of outputs.md.
struct Codim2Curve {
  std::string name; // <tag><event>, e.g. fold3
  EventKind kind = EventKind::Fold;
  PetscInt event = 0;
  Codim2Parameter parameter = Codim2Parameter::Gamma;
  static constexpr PetscInt kMultipliers = 4;                                       // written per point: the multipliers nearest the kind's critical point
  std::vector<PetscReal> p, energy, omega, period, test, max_modulus, mu_re, mu_im; // mu: npts x kMultipliers
  PetscInt event_point = 0;                                                         // the row of the event itself
  std::string stop_reason;
  PetscInt solves = 0; // orbits solved
  PetscReal seconds = 0;
};

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

} // namespace nltopo
