#pragma once
// Writes the cost card (/cost attributes) of the ledger in core/cost.hpp.
#include <petscviewer.h>

namespace nltopo {

// Writes /cost (attributes) on the viewer; sums over its communicator first
// unless CostReduceWorld has done it (collective on the viewer's communicator).
PetscErrorCode WriteCostCard(PetscViewer v, PetscReal wall_seconds);

} // namespace nltopo
