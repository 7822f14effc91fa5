#pragma once
// The orbit of a located event as the start of its two-parameter curve
// (stability/codim2.hpp): found again by the locator, which still holds the
// branch the event was located on.
#include "stability/bifurcation_locator.hpp"
#include "stability/codim2.hpp"
#include "studies/nnm_setup.hpp"

namespace nltopo {

// st: the event's orbit (z0 on every rank, T, beta, omega, E); found is false
// when the locator's Newton does not converge there again. Collective.
PetscErrorCode EventOrbit(MPI_Comm comm, BifurcationLocator &loc, NnmSetup &nnm, const BifurcationEvent &e, Codim2Start *st, bool *found);

} // namespace nltopo
