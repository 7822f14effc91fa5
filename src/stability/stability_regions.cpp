#include "stability/stability_regions.hpp"
#include <algorithm>
#include <array>
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

// The curve's point k in the plane (p, ln E); beyond the ends, the end's reflection through its neighbour.
std::array<PetscReal, 2> PlanePoint(const RegionCurve &c, PetscInt k)
{
  const PetscInt n = (PetscInt)c.p.size();
  auto at = [&](PetscInt i) { return std::array<PetscReal, 2>{c.p[i], std::log(c.energy[i])}; };
  if (k < 0) return {2 * at(0)[0] - at(1)[0], 2 * at(0)[1] - at(1)[1]};
  if (k >= n) return {2 * at(n - 1)[0] - at(n - 2)[0], 2 * at(n - 1)[1] - at(n - 2)[1]};
  return at(k);
}

// ln E where segment k (points k, k + 1, whose p bracket pc) crosses the
// column pc, on the centripetal Catmull-Rom spline through points k - 1 ..
// k + 2 (Barry-Goldman's recursion): third order in the spacing, where a chord
// is second order (the follower's steps grow to where the chord's sagitta
// exceeds the map's -smap_same_curve_rtol), and without the loops a uniform
// spline makes where points bunch (a step collapse). The root in the segment's
// parameter by bisection.
PetscReal CrossingLogEnergy(const RegionCurve &c, size_t k, PetscReal pc)
{
  using P = std::array<PetscReal, 2>;
  const P q[4] = {PlanePoint(c, (PetscInt)k - 1), PlanePoint(c, (PetscInt)k), PlanePoint(c, (PetscInt)k + 1), PlanePoint(c, (PetscInt)k + 2)};
  PetscReal t[4] = {0, 0, 0, 0};
  for (int i = 1; i < 4; i++) t[i] = t[i - 1] + std::max(std::sqrt(std::hypot(q[i][0] - q[i - 1][0], q[i][1] - q[i - 1][1])), (PetscReal)1e-12);
  auto lerp = [](const P &a, const P &b, PetscReal ta, PetscReal tb, PetscReal u) {
    const PetscReal w = (u - ta) / (tb - ta);
    return P{(1 - w) * a[0] + w * b[0], (1 - w) * a[1] + w * b[1]};
  };
  auto at = [&](PetscReal u) {
    const P a1 = lerp(q[0], q[1], t[0], t[1], u), a2 = lerp(q[1], q[2], t[1], t[2], u), a3 = lerp(q[2], q[3], t[2], t[3], u);
    return lerp(lerp(a1, a2, t[0], t[2], u), lerp(a2, a3, t[1], t[3], u), t[1], t[2], u);
  };
  PetscReal lo = t[1], hi = t[2];
  const bool rising = q[2][0] > q[1][0];
  for (int it = 0; it < 60; it++) {
    const PetscReal mid = 0.5 * (lo + hi);
    if ((at(mid)[0] < pc) == rising) lo = mid;
    else hi = mid;
  }
  return at(0.5 * (lo + hi))[1];
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
    Crossing x;
    x.energy = std::exp(CrossingLogEnergy(c, k, pc));
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
