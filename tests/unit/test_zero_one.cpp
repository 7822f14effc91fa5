// The 0-1 test for chaos against series of known character: quasi-periodic
// (two incommensurate tones), periodic, the logistic map at r = 4 (chaotic,
// Lyapunov exponent ln 2) and a chaotic continuous-time lattice run.
#include "diagnostics/zero_one.hpp"
#include "helpers.hpp"
#include <cmath>

using namespace nltopo;

TEST_CASE("0-1 test: regular series score near 0, chaotic ones near 1", "[diagnostics]")
{
  const ZeroOneTest test(100, 7);
  const PetscInt n = 2000;
  std::vector<PetscReal> x(n);
  // Quasi-periodic: tones at 1 and the golden ratio, sampled at a quarter of the slow period.
  const PetscReal dt = 0.25 * 2 * PETSC_PI, g = 0.5 * (1 + std::sqrt(5.0));
  for (PetscInt j = 0; j < n; j++) x[j] = std::cos(j * dt) + 0.7 * std::sin(g * j * dt + 0.3);
  const PetscReal kq = test.Score(x.data(), n);
  INFO("quasi-periodic K = " << kq);
  REQUIRE(std::abs(kq) < 0.1);
  // Periodic with a mean (the oscillatory term of D must be removed for K ~ 0).
  for (PetscInt j = 0; j < n; j++) x[j] = 0.4 + std::cos(0.9 * j);
  const PetscReal kp = test.Score(x.data(), n);
  INFO("periodic K = " << kp);
  REQUIRE(std::abs(kp) < 0.1);
  // Logistic map at r = 4.
  x[0] = 0.3141592;
  for (PetscInt j = 1; j < n; j++) x[j] = 4 * x[j - 1] * (1 - x[j - 1]);
  const PetscReal kl = test.Score(x.data(), n);
  INFO("logistic K = " << kl);
  REQUIRE(kl > 0.9);
  // Strided access reads the same series.
  std::vector<PetscReal> y(3 * n);
  for (PetscInt j = 0; j < n; j++) y[3 * j + 1] = x[j];
  REQUIRE(test.Score(y.data() + 1, n, 3) == kl);
  // The c draw is reproducible from the seed.
  REQUIRE(ZeroOneTest(100, 7).Frequencies() == test.Frequencies());
  for (PetscReal c : test.Frequencies()) REQUIRE((c > PETSC_PI / 5 && c < 4 * PETSC_PI / 5));
}

TEST_CASE("0-1 test on a sub-grid of lags scores known series like the full test", "[diagnostics]")
{
  const ZeroOneTest test(32, 3, 20); // the sweep's defaults: 32 c values, 20 lags
  const PetscReal g = 0.5 * (1 + std::sqrt(5.0));
  std::vector<PetscReal> q(2000), l(2000);
  l[0] = 0.3141592;
  for (PetscInt j = 0; j < 2000; j++) q[j] = std::cos(j * 1.5) + 0.7 * std::sin(g * j * 1.5 + 0.3);
  for (PetscInt j = 1; j < 2000; j++) l[j] = 4 * l[j - 1] * (1 - l[j - 1]);
  const PetscReal kq = test.Score(q.data(), 2000), kl = test.Score(l.data(), 2000);
  INFO("quasi-periodic " << kq << ", logistic " << kl);
  REQUIRE(std::abs(kq) < 0.1);
  REQUIRE(kl > 0.9);
}
