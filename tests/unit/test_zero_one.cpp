// The 0-1 test for chaos against series of known character: quasi-periodic
// (two incommensurate tones), periodic, the logistic map at r = 4 (chaotic,
// Lyapunov exponent ln 2) and a chaotic continuous-time lattice run.
#include "diagnostics/zero_one.hpp"
#include "helpers.hpp"
#include <algorithm>
#include <cmath>

using namespace nltopo;

TEST_CASE("0-1 test: regular series score near 0, chaotic ones near 1", "[diagnostics][serial]")
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

TEST_CASE("0-1 test on a sub-grid of lags scores known series like the full test", "[diagnostics][serial]")
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

namespace {
// The test's definition, summed directly (O(n) per lag and c): K of x for the
// frequencies c and the lags of the class under test.
PetscReal DirectScore(const std::vector<PetscReal> &x, const std::vector<PetscReal> &cs, PetscInt lags)
{
  const PetscInt n = (PetscInt)x.size(), ncut = n / 10, len = n - ncut;
  std::vector<PetscInt> lag;
  if (lags > 0 && lags < ncut)
    for (PetscInt i = 0; i < lags; i++) lag.push_back(1 + (PetscInt)std::llround((double)i * (ncut - 1) / (lags - 1)));
  else
    for (PetscInt m = 1; m <= ncut; m++) lag.push_back(m);
  PetscReal mean = 0;
  for (PetscReal v : x) mean += v / n;
  std::vector<PetscReal> K;
  for (PetscReal c : cs) {
    std::vector<PetscReal> p(n), q(n), D;
    PetscReal sp = 0, sq = 0;
    for (PetscInt j = 0; j < n; j++) {
      sp += x[j] * std::cos((j + 1) * c);
      sq += x[j] * std::sin((j + 1) * c);
      p[j] = sp, q[j] = sq;
    }
    for (PetscInt m : lag) {
      PetscReal M = 0;
      for (PetscInt j = 0; j < len; j++) M += (p[j + m] - p[j]) * (p[j + m] - p[j]) + (q[j + m] - q[j]) * (q[j + m] - q[j]);
      D.push_back(M / len - mean * mean * (1 - std::cos(m * c)) / (1 - std::cos(c)));
    }
    PetscReal xm = 0, ym = 0, sxy = 0, sxx = 0, syy = 0;
    for (size_t i = 0; i < D.size(); i++) xm += (PetscReal)lag[i] / D.size(), ym += D[i] / D.size();
    for (size_t i = 0; i < D.size(); i++) sxy += (lag[i] - xm) * (D[i] - ym), sxx += (lag[i] - xm) * (lag[i] - xm), syy += (D[i] - ym) * (D[i] - ym);
    K.push_back(sxy / std::sqrt(sxx * syy));
  }
  std::sort(K.begin(), K.end());
  const size_t h = K.size() / 2;
  return K.size() % 2 ? K[h] : 0.5 * (K[h - 1] + K[h]);
}
} // namespace

TEST_CASE("0-1 test: the lag-correlation sums equal the direct definition", "[diagnostics][serial]")
{
  // Series of every character the sweep meets: periodic with a mean,
  // quasi-periodic, a resonant tone (c range contains its frequency: P grows
  // linearly), chaotic (logistic) and a slow drift plus noise.
  const PetscInt n = 1654; // the sweep's record: 1500 s at a quarter insulated period
  std::vector<std::vector<PetscReal>> series(5, std::vector<PetscReal>(n));
  const PetscReal g = 0.5 * (1 + std::sqrt(5.0));
  series[3][0] = 0.3141592;
  unsigned long s = 12345;
  for (PetscInt j = 0; j < n; j++) {
    series[0][j] = 0.4 + std::cos(0.9 * j);
    series[1][j] = std::cos(j * 1.5) + 0.7 * std::sin(g * j * 1.5 + 0.3);
    series[2][j] = 1e-3 * std::cos(1.2 * j + 0.1);
    if (j) series[3][j] = 4 * series[3][j - 1] * (1 - series[3][j - 1]);
    s = s * 6364136223846793005UL + 1442695040888963407UL;
    series[4][j] = 5 + 1e-3 * j + (double)(s >> 11) / 9007199254740992.0;
  }
  for (PetscInt lags : {20, 0}) {
    const ZeroOneTest test(32, 3, lags);
    for (size_t i = 0; i < series.size(); i++) {
      const PetscReal fast = test.Score(series[i].data(), n), direct = DirectScore(series[i], test.Frequencies(), lags);
      INFO("series " << i << ", lags " << lags << ": K = " << fast << ", direct " << direct);
      REQUIRE(std::abs(fast - direct) <= 1e-9);
    }
  }
}

TEST_CASE("0-1 test: sites scored in blocks equal Score per site", "[diagnostics][serial]")
{
  // A samples-by-sites record (row-major, as the sweep's sink holds it): random
  // sites, a periodic one with a mean, a logistic-map one (chaotic) and a
  // quiet drift; an odd number of sites so that the last block is padded.
  const PetscInt N = 9;
  unsigned long r = 987654321;
  auto uniform = [&r]() {
    r = r * 6364136223846793005UL + 1442695040888963407UL;
    return (double)(r >> 11) / 9007199254740992.0;
  };
  for (PetscInt n : {20, 37, 1654}) { // the shortest record, a few lags only, the sweep's record
    std::vector<PetscReal> x(n * N);
    PetscReal l = 0.3141592;
    for (PetscInt j = 0; j < n; j++) {
      for (PetscInt s = 0; s < N; s++) x[j * N + s] = uniform() - 0.5;
      x[j * N + 2] = 0.4 + std::cos(0.9 * j);
      x[j * N + 5] = l, l = 4 * l * (1 - l);
      x[j * N + 7] = 1e-6 * (1 + 1e-3 * j) + 1e-9 * std::sin(2.1 * j);
    }
    for (PetscInt lags : {20, 0}) {
      const ZeroOneTest test(13, 5, lags); // 13 frequencies: not a multiple of the frequency block
      for (const std::vector<PetscInt> &sites : {std::vector<PetscInt>{0, 1, 2, 3, 4, 5, 6, 7, 8}, std::vector<PetscInt>{8, 2, 5}, std::vector<PetscInt>{5}}) {
        for (bool wide : {true, false}) { // four lanes (where the CPU has AVX) and two
          std::vector<PetscReal> K;
          test.ScoreSites(x.data(), n, N, sites, K, wide);
          REQUIRE(K.size() == sites.size());
          for (size_t i = 0; i < sites.size(); i++) {
            const PetscReal k = test.Score(x.data() + sites[i], n, N);
            INFO("n " << n << ", lags " << lags << ", wide " << wide << ", site " << sites[i] << ": blocked " << K[i] << ", Score " << k);
            REQUIRE(std::abs(K[i] - k) <= 1e-12);
          }
        }
        PetscReal kmax = -1;
        for (PetscInt s : sites) kmax = std::max(kmax, test.Score(x.data() + s, n, N));
        REQUIRE(std::abs(test.ScoreMax(x.data(), n, N, sites) - kmax) <= 1e-12);
      }
      REQUIRE(test.ScoreMax(x.data(), n, N, {}) == -1);
    }
  }
  // The known characters survive batching: the logistic site reads chaotic, the periodic one regular.
  const PetscInt n = 1654;
  std::vector<PetscReal> y(2 * n);
  y[1] = 0.3141592;
  for (PetscInt j = 0; j < n; j++) {
    y[2 * j] = 0.4 + std::cos(0.9 * j);
    if (j) y[2 * j + 1] = 4 * y[2 * j - 1] * (1 - y[2 * j - 1]);
  }
  std::vector<PetscReal> K;
  ZeroOneTest(32, 3, 20).ScoreSites(y.data(), n, 2, {0, 1}, K);
  INFO("periodic K = " << K[0] << ", logistic K = " << K[1]);
  REQUIRE(std::abs(K[0]) < 0.1);
  REQUIRE(K[1] > 0.9);
}
