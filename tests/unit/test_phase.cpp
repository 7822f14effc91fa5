// Fourier phase at omega_ext and the dimer-phase wrap of model.md, against
// synthetic sinusoids of known phase.
#include "diagnostics/phase.hpp"
#include "helpers.hpp"
#include <cmath>
#include <vector>

using namespace nltopo;

TEST_CASE("Fourier phase of two sinusoids recovers their offset; the wrap keeps 0 and pi inside", "[diagnostics][serial]")
{
  const PetscReal w = 1.9513, T = 2 * PETSC_PI / w, dt = T / 16, t0 = 437.25;
  const PetscInt n = 16 * 23; // 23 whole periods
  for (PetscReal offset : {0.0, 0.4, PETSC_PI, -2.5, 3.0}) {
    std::vector<PetscReal> x(2 * n); // two sites interleaved (stride 2), with a harmonic and a mean
    for (PetscInt k = 0; k < n; k++) {
      const PetscReal t = t0 + k * dt;
      x[2 * k] = 0.7 * std::cos(w * t + 0.3) + 0.2 * std::cos(3 * w * t) + 0.05;
      x[2 * k + 1] = 1.3 * std::cos(w * t + 0.3 + offset) - 0.1 * std::sin(2 * w * t);
    }
    const PetscReal p0 = FourierPhase(x.data(), n, 2, t0, dt, w), p1 = FourierPhase(x.data() + 1, n, 2, t0, dt, w);
    REQUIRE(std::abs(p0 - 0.3) < 1e-8);
    const PetscReal d = WrapDimerPhase(p1 - p0), want = WrapDimerPhase(offset);
    INFO("offset " << offset << ": recovered " << d);
    REQUIRE(std::abs(d - want) < 1e-8);
    REQUIRE((d >= -PETSC_PI / 2 && d < 1.5 * PETSC_PI));
  }
  REQUIRE(std::abs(WrapDimerPhase(-0.01) + 0.01) < 1e-15);                         // near 0 stays near 0
  REQUIRE(std::abs(WrapDimerPhase(-PETSC_PI + 0.01) - (PETSC_PI + 0.01)) < 1e-14); // near -pi becomes near pi
  REQUIRE(std::abs(WrapDimerPhase(2 * PETSC_PI - 0.01) + 0.01) < 1e-14);
}
