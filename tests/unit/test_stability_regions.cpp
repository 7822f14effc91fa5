// The stability map's regions from its boundary curves (stability/
// stability_regions.hpp) on constructed curves whose regions are known: a
// closed bubble (an ellipse in (p, ln E), travelled either way), an E-E
// boundary above it that stays open to the top (a branch point's), a bubble
// cut by a curve that ends inside the map (counted as inconsistent), and the
// side taken from an event's direction.
#include "stability/stability_regions.hpp"
#include <catch2/catch.hpp>
#include <cmath>

using namespace nltopo;

namespace {

// An ellipse centred at (p0, E0) with semi-axes a in p and b in ln E, n points from angle t0, counter-clockwise (dir +1) or clockwise (-1).
RegionCurve Ellipse(PetscReal p0, PetscReal E0, PetscReal a, PetscReal b, PetscInt n, PetscInt dir, PetscReal t0, PetscInt cls)
{
  RegionCurve c;
  for (PetscInt k = 0; k <= n; k++) {
    const PetscReal t = t0 + dir * 2 * M_PI * k / n;
    c.p.push_back(p0 + a * std::cos(t)), c.energy.push_back(E0 * std::exp(b * std::sin(t)));
  }
  c.cls = cls;
  return c;
}

bool InsideEllipse(PetscReal p, PetscReal E, PetscReal p0, PetscReal E0, PetscReal a, PetscReal b)
{
  const PetscReal x = (p - p0) / a, y = std::log(E / E0) / b;
  return x * x + y * y < 1;
}

std::vector<PetscReal> Grid(PetscReal lo, PetscReal hi, PetscInt n, bool log)
{
  std::vector<PetscReal> g;
  for (PetscInt i = 0; i < n; i++) {
    const PetscReal s = (PetscReal)i / (n - 1);
    g.push_back(log ? std::exp(std::log(lo) + s * (std::log(hi) - std::log(lo))) : lo + s * (hi - lo));
  }
  return g;
}

} // namespace

TEST_CASE("stability regions: a closed B-E bubble is unstable inside and stable outside, travelled either way", "[regions][serial]")
{
  const std::vector<PetscReal> p = Grid(0.1, 0.8, 71, false), E = Grid(0.1, 100, 61, true);
  for (PetscInt dir : {1, -1}) {
    RegionCurve c = Ellipse(0.45, 3, 0.2, 1.0, 400, dir, 0.3, 2);
    // the event at the row where the curve crosses p0 on its lower arc: there the instability begins as E grows
    PetscInt row = -1;
    for (size_t k = 0; k + 1 < c.p.size(); k++)
      if (c.energy[k] < 3 && (c.p[k] - 0.45) * (c.p[k + 1] - 0.45) <= 0) row = (PetscInt)k;
    REQUIRE(row >= 0);
    c.side = UnstableSide(c, row, +1);
    INFO("direction of travel " << dir << ", side " << c.side);
    REQUIRE(c.side == dir); // inside an ellipse travelled counter-clockwise is on its left
    PetscInt bad = -1, wrong = 0, near = 0;
    const std::vector<PetscInt> lab = LabelRegions({c}, p, E, &bad);
    REQUIRE(bad == 0);
    for (size_t i = 0; i < p.size(); i++)
      for (size_t j = 0; j < E.size(); j++) {
        const bool in = InsideEllipse(p[i], E[j], 0.45, 3, 0.2, 1.0);
        // within the polygon's distance of the ellipse either label is right
        const PetscReal x = (p[i] - 0.45) / 0.2, y = std::log(E[j] / 3), r = std::hypot(x, y);
        if (std::abs(r - 1) < 1e-3) {
          near++;
          continue;
        }
        wrong += lab[i * E.size() + j] != (in ? 2 : 0);
        REQUIRE(LabelAt({c}, p[i], E[j]) == lab[i * E.size() + j]);
      }
    REQUIRE(wrong == 0);
  }
}

TEST_CASE("stability regions: E-E wins over B-E, an open E-E boundary labels everything above it, a curve ended inside the map is counted", "[regions][serial]")
{
  const std::vector<PetscReal> p = Grid(0.1, 0.8, 36, false), E = Grid(0.1, 100, 41, true);
  RegionCurve bubble = Ellipse(0.45, 3, 0.2, 1.0, 400, 1, 0.3, 2);
  bubble.side = 1;
  // E-E from E = 2 (1 + p) up: the curve travels in +p, the unstable side (above) on its left
  RegionCurve ee;
  for (PetscReal q : Grid(0.05, 0.85, 50, false)) ee.p.push_back(q), ee.energy.push_back(2 * (1 + q));
  ee.cls = 3;
  ee.side = UnstableSide(ee, 10, +1);
  REQUIRE(ee.side == 1);
  PetscInt bad = -1;
  const std::vector<PetscInt> lab = LabelRegions({bubble, ee}, p, E, &bad);
  REQUIRE(bad == 0);
  for (size_t i = 0; i < p.size(); i++)
    for (size_t j = 0; j < E.size(); j++) {
      const PetscReal edge = 2 * (1 + p[i]);
      if (std::abs(E[j] / edge - 1) < 1e-9) continue;
      const PetscInt want = E[j] > edge ? 3 : InsideEllipse(p[i], E[j], 0.45, 3, 0.2, 1.0) ? 2 : 0;
      const PetscReal r = std::hypot((p[i] - 0.45) / 0.2, std::log(E[j] / 3));
      if (std::abs(r - 1) < 1e-3) continue;
      INFO("p " << p[i] << " E " << E[j]);
      REQUIRE(lab[i * E.size() + j] == want);
    }
  // the upper arc of the bubble alone (its lower arc missing): where it crosses, it closes an instability no crossing opened
  RegionCurve upper; // counter-clockwise from angle 0.01 to pi - 0.01: the inside (below it) on its left
  for (PetscInt k = 0; k <= 200; k++) {
    const PetscReal t = 0.01 + (M_PI - 0.02) * k / 200;
    upper.p.push_back(0.45 + 0.2 * std::cos(t)), upper.energy.push_back(3 * std::exp(std::sin(t)));
  }
  upper.cls = 2, upper.side = 1;
  const std::vector<PetscInt> lab2 = LabelRegions({upper}, p, E, &bad);
  PetscInt crossed = 0;
  for (PetscReal q : p) crossed += !ColumnCrossings(upper, q).empty();
  REQUIRE(crossed > 0);
  REQUIRE(bad == crossed);
  for (PetscInt l : lab2) REQUIRE(l == 0);
}

TEST_CASE("stability regions: a column's crossing of a curve is third order in the points' spacing (the curve, not its chords)", "[regions][serial]")
{
  // an arc of the ellipse (half of it, the upper side: one crossing per column), n and 2n points; the crossing's
  // ln E against the ellipse's own, over the columns away from the arc's vertical ends
  auto worst = [](PetscInt n) {
    const PetscReal p0 = 0.45, E0 = 3, a = 0.3, b = 1.2;
    RegionCurve c = Ellipse(p0, E0, a, b, 2 * n, 1, 0, 2);
    c.p.resize(n + 1), c.energy.resize(n + 1); // t in [0, pi]
    c.side = 1;
    PetscReal w = 0;
    for (PetscReal x = -0.8; x <= 0.8; x += 0.01) {
      const std::vector<Crossing> xs = ColumnCrossings(c, p0 + a * x);
      REQUIRE(xs.size() == 1);
      w = std::max(w, std::abs(std::log(xs[0].energy / E0) - b * std::sqrt(1 - x * x)));
    }
    return w;
  };
  const PetscReal e16 = worst(16), e32 = worst(32);
  INFO("largest |ln E - ln E(curve)|: " << e16 << " (16 points), " << e32 << " (32 points)");
  REQUIRE(e16 / e32 >= 6); // the chords': 4
  REQUIRE(e32 <= 1e-4);
}
