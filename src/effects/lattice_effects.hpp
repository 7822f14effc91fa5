#pragma once
// The lattice's own effects (model.md "Equations of motion"): the linear
// coupling -K u (always) and the cubic bonds -f_NL(u) (when Gamma != 0).
#include "effects/effect.hpp"

namespace nltopo {

std::unique_ptr<Effect> CreateLinearCoupling(const Lattice &lat);
// -lattice_cubic into p->Gamma, validated.
PetscErrorCode CubicBondsOptionsFromOptions(MPI_Comm comm, LatticeParams *p);
// NULL when the lattice has no cubic coefficient (-lattice_cubic 0).
std::unique_ptr<Effect> CreateCubicBonds(const Lattice &lat);

} // namespace nltopo
