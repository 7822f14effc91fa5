#pragma once
// The regions of a stability map in (p, E) (issue 37, -study stabilitymap;
// docs/studies/stabilitymap.md "Regions"): the event curves of one branch
// (stability/codim2.hpp) bound where its orbits are stable, B-E or E-E
// unstable. Each curve carries the side its instability lies on: at the event
// the one-parameter branch says whether the instability begins (direction +1)
// or ends (-1) as E grows at the run's p; that side stays on the same hand of
// the curve's direction of travel along the whole curve (its test function
// keeps its sign on each side), so at any p the crossing says whether E above
// it is unstable. A column of the raster then counts, from small E up (where
// the NNM is its linear mode, stable), the instabilities of each class that
// are open: E-E where any E-E one is, else B-E, else stable.
#include <petscsys.h>
#include <vector>

namespace nltopo {

// One boundary: its points in order along the curve, the Localisation class of
// the instability it bounds (1 B-B, 2 B-E, 3 E-E) and the hand of its travel
// the unstable side lies on (+1 left in the (p, ln E) plane, -1 right, 0 unknown).
struct RegionCurve {
  std::vector<PetscReal> p, energy;
  PetscInt cls = 0;
  PetscInt side = 0;
};

// The side from the event: the curve's row at the event and the event's
// direction along the one-parameter branch (+1: unstable above it in E).
// 0 when the curve is vertical there (a turn in p at the event itself).
PetscInt UnstableSide(const RegionCurve &c, PetscInt event_row, PetscInt direction);

// Where the curve crosses the column p = pc: each crossing's E (interpolated
// linearly in ln E between the bracketing points) and whether the side above
// it is the unstable one (not known for a side-0 curve: LabelRegions leaves such curves out).
struct Crossing {
  PetscReal energy = 0;
  bool unstable_above = false;
  PetscInt cls = 0;
};
std::vector<Crossing> ColumnCrossings(const RegionCurve &c, PetscReal pc);

// The raster: label[i * ne + j] at (p[i], energy[j]), in the codes of the
// instability class (0 stable, 2 B-E, 3 E-E; a B-B curve labels 1 when no
// other is open). *inconsistent counts the columns where some class's count
// went below zero (a crossing closes an instability no crossing below had
// opened: a curve missing from the map, or one that ended inside it).
std::vector<PetscInt> LabelRegions(const std::vector<RegionCurve> &curves, const std::vector<PetscReal> &p, const std::vector<PetscReal> &energy,
                                   PetscInt *inconsistent);

// The label of one point (p, E), by the same rule.
PetscInt LabelAt(const std::vector<RegionCurve> &curves, PetscReal p, PetscReal energy);

} // namespace nltopo
