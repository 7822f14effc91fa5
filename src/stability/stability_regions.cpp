#include "stability/stability_regions.hpp"
#include <algorithm>
#include <cmath>

namespace nltopo {

namespace {

// Components of the curve's direction of travel at row r in (p, ln E): central where it can be.
void Tangent(const RegionCurve &c, PetscInt r, PetscReal *tp, PetscReal *te)
{
  const PetscInt n = (PetscInt)c.p.size();
  const PetscInt a = std::max<PetscInt>(r - 1, 0), b = std::min<PetscInt>(r + 1, n - 1);
  *tp = c.p[b] - c.p[a];
  *te = std::log(c.energy[b]) - std::log(c.energy[a]);
}

// The label of one column's point at E from its sorted crossings: per class the
// number of instabilities open below E (each crossing opens or closes one).
PetscInt Label(const std::vector<Crossing> &xs, PetscReal energy, bool *negative)
{
  PetscInt open[4] = {0, 0, 0, 0};
  for (const Crossing &x : xs) {
    if (x.energy >= energy) break;
    if (x.cls < 1 || x.cls > 3) continue;
    open[x.cls] += x.unstable_above ? 1 : -1;
    if (open[x.cls] < 0) *negative = true, open[x.cls] = 0;
  }
  return open[3] > 0 ? 3 : open[2] > 0 ? 2 : open[1] > 0 ? 1 : 0;
}

std::vector<Crossing> AllCrossings(const std::vector<RegionCurve> &curves, PetscReal pc)
{
  std::vector<Crossing> xs;
  for (const RegionCurve &c : curves) {
    if (c.side == 0) continue; // (a side unknown: the curve is drawn, it labels nothing)
    const std::vector<Crossing> x = ColumnCrossings(c, pc);
    xs.insert(xs.end(), x.begin(), x.end());
  }
  std::sort(xs.begin(), xs.end(), [](const Crossing &a, const Crossing &b) { return a.energy < b.energy; });
  return xs;
}

} // namespace

PetscInt UnstableSide(const RegionCurve &c, PetscInt event_row, PetscInt direction)
{
  if (c.p.size() < 2 || direction == 0 || event_row < 0 || event_row >= (PetscInt)c.p.size()) return 0;
  PetscReal tp, te;
  Tangent(c, event_row, &tp, &te);
  // the left normal (-te, tp) has E-component tp: unstable above iff side * tp > 0
  if (tp == 0) return 0;
  return direction * (tp > 0 ? 1 : -1);
}

std::vector<Crossing> ColumnCrossings(const RegionCurve &c, PetscReal pc)
{
  std::vector<Crossing> xs;
  for (size_t k = 0; k + 1 < c.p.size(); k++) {
    const PetscReal p0 = c.p[k], p1 = c.p[k + 1];
    // half-open in p, so that a column through a point counts one of its two segments
    const bool in = (p0 <= pc && pc < p1) || (p1 <= pc && pc < p0);
    if (!in) continue;
    const PetscReal t = (pc - p0) / (p1 - p0);
    Crossing x;
    x.energy = std::exp((1 - t) * std::log(c.energy[k]) + t * std::log(c.energy[k + 1]));
    x.unstable_above = c.side * (p1 - p0) > 0;
    x.cls = c.cls;
    xs.push_back(x);
  }
  return xs;
}

std::vector<PetscInt> LabelRegions(const std::vector<RegionCurve> &curves, const std::vector<PetscReal> &p, const std::vector<PetscReal> &energy,
                                   PetscInt *inconsistent)
{
  std::vector<PetscInt> label(p.size() * energy.size(), 0);
  *inconsistent = 0;
  for (size_t i = 0; i < p.size(); i++) {
    const std::vector<Crossing> xs = AllCrossings(curves, p[i]);
    bool negative = false;
    for (size_t j = 0; j < energy.size(); j++) label[i * energy.size() + j] = Label(xs, energy[j], &negative);
    if (negative) (*inconsistent)++;
  }
  return label;
}

PetscInt LabelAt(const std::vector<RegionCurve> &curves, PetscReal p, PetscReal energy)
{
  bool negative = false;
  return Label(AllCrossings(curves, p), energy, &negative);
}

} // namespace nltopo
