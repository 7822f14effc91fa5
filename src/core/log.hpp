#pragma once
// Log stages and events, registered once, so that -log_view shows where the
// time goes (one event per kernel, one stage per study phase).
#include <petscsys.h>

namespace nltopo {

struct LogEvents {
  PetscClassId classid; // the effects register their own events (RhsLinear, RhsCubic, ...) with it
  PetscLogEvent energy, jacobian, eigen, bloch, output, diagnostics, variational, floquet, floquet_eigenvalues, mf_pc;
  PetscLogEvent bifurcations; // -cont_bifurcations: locating the events of a branch
  PetscLogEvent transition;   // -linear_gamma_list: spectra and Zak phases over gamma
  PetscLogStage setup, solve, write;
};

// Registers on first call; later calls return the same ids.
const LogEvents &Log();
PetscErrorCode LogRegister();
// The event of a kernel outside LogEvents (a Floquet route, the Lyapunov
// exponent, ...), registered under name on its first use: one id per name.
PetscErrorCode NamedLogEvent(const char *name, PetscLogEvent *ev);

} // namespace nltopo
