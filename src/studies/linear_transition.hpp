#pragma once
// -linear_gamma_list of the linear study (docs/studies/linear.md
// "The transition over gamma"): the option's value and the run's summary on stdout. The
// computation itself is bands/transition.hpp.
#include "bands/transition.hpp"
#include <string>

namespace nltopo {

// -linear_gamma_list min:max:n; off when not given (n = 0).
struct GammaList {
  PetscReal lo = 0, hi = 0;
  PetscInt n = 0;
  std::string text; // as given, without surrounding blanks
};

// Parses and checks "min:max:n": -1 <= min < max <= 1 (k1 = k(1+gamma) and
// k2 = k(1-gamma) are not negative; at +-1 one bond is cut), 2 <= n <= 1e5.
// Errors name the option and the value.
PetscErrorCode ParseGammaList(MPI_Comm comm, const std::string &given, GammaList *g);

// The summary: time, where each Zak phase jumps or is NaN, the spectrum next to
// sqrt(k_hat) nearest gamma = 0, the localised modes nearest lp.gamma, and a
// warning where K is not positive definite.
PetscErrorCode PrintTransitionSummary(MPI_Comm comm, const LatticeParams &lp, const TransitionResult &t, PetscLogDouble seconds);

} // namespace nltopo
