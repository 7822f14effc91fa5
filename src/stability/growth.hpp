#pragma once
// The growth of a perturbation along an unstable Floquet eigenvector, by
// direct (nonlinear) simulation: the orbit z and z + eps |z| v / |v| are
// integrated side by side with a simulation's integrator (-sim_ts_*) for a
// number of periods, and ln of their distance at each period end is fitted by
// least squares over the periods before it reaches 1e-3 |z| (the linear
// regime). A right Floquet verdict gives the slope ln|mu| per period
// (docs/studies/stability.md, docs/long-lattices.md "Verdicts").
#include "effects/effect.hpp"
#include "timeint/simulation.hpp"
#include <vector>

namespace nltopo {

struct GrowthMeasurement {
  PetscReal rate = 0;  // fitted ln(distance) per period (NaN: fewer than 3 periods in the linear regime)
  PetscInt fitted = 0; // periods the fit used
};

// window (optional): natural site indices lo..hi whose (u, v) entries alone
// make the distance (a localized mode that radiates into the band: its
// window holds the mode, the rest the outgoing wave). Collective.
PetscErrorCode MeasureGrowth(const EffectList &fx, const SimulationOptions &sim, Vec z, PetscReal T, Vec v, PetscInt periods, PetscReal eps,
                             GrowthMeasurement *out, const PetscInt *window = nullptr);

} // namespace nltopo
