#include "diagnostics/zero_one.hpp"
#include <algorithm>
#include <cmath>
#include <random>

namespace nltopo {

ZeroOneTest::ZeroOneTest(PetscInt nc, unsigned long seed, PetscInt lags) : lags_(lags)
{
  std::mt19937_64 gen(seed);
  std::uniform_real_distribution<double> dist(PETSC_PI / 5, 4 * PETSC_PI / 5);
  for (PetscInt i = 0; i < nc; i++) c_.push_back(dist(gen));
}

namespace {
// Pearson correlation of the lags x[] with d[].
PetscReal Correlation(const std::vector<PetscInt> &lag, const std::vector<PetscReal> &d)
{
  const size_t m = d.size();
  PetscReal xm = 0, ym = 0;
  for (size_t i = 0; i < m; i++) xm += lag[i], ym += d[i];
  xm /= m;
  ym /= m;
  PetscReal sxy = 0, sxx = 0, syy = 0;
  for (size_t i = 0; i < m; i++) {
    const PetscReal x = lag[i] - xm, y = d[i] - ym;
    sxy += x * y;
    sxx += x * x;
    syy += y * y;
  }
  return syy > 0 ? sxy / std::sqrt(sxx * syy) : 0;
}
} // namespace

PetscReal ZeroOneTest::Score(const PetscReal *phi, PetscInt n, PetscInt stride) const
{
  const PetscInt ncut = n / 10;
  std::vector<PetscInt> lag;
  if (lags_ > 0 && lags_ < ncut) {
    for (PetscInt i = 0; i < lags_; i++) lag.push_back(1 + (PetscInt)std::llround((double)i * (ncut - 1) / (lags_ - 1 > 0 ? lags_ - 1 : 1)));
  } else {
    for (PetscInt m = 1; m <= ncut; m++) lag.push_back(m);
  }
  std::vector<PetscReal> x(n), p(n), q(n), D(lag.size()), K;
  PetscReal mean = 0;
  for (PetscInt j = 0; j < n; j++) {
    x[j] = phi[j * stride];
    mean += x[j];
  }
  mean /= n;
  for (PetscReal c : c_) {
    // p, q by a rotation recurrence, re-anchored every 64 terms against drift
    PetscReal sp = 0, sq = 0, cr = 1, si = 0;
    const PetscReal cc = std::cos(c), sc = std::sin(c);
    for (PetscInt j = 0; j < n; j++) {
      if (j % 64 == 0) {
        cr = std::cos((j + 1) * c);
        si = std::sin((j + 1) * c);
      }
      sp += x[j] * cr;
      sq += x[j] * si;
      p[j] = sp;
      q[j] = sq;
      const PetscReal t = cr * cc - si * sc;
      si = si * cc + cr * sc;
      cr = t;
    }
    for (size_t li = 0; li < lag.size(); li++) {
      const PetscInt m = lag[li];
      const PetscInt len = n - ncut; // the same number of increments for every m
      PetscReal a0 = 0, a1 = 0, a2 = 0, a3 = 0;
      PetscInt j = 0;
      for (; j + 1 < len; j += 2) {
        const PetscReal dp0 = p[j + m] - p[j], dq0 = q[j + m] - q[j];
        const PetscReal dp1 = p[j + 1 + m] - p[j + 1], dq1 = q[j + 1 + m] - q[j + 1];
        a0 += dp0 * dp0;
        a1 += dq0 * dq0;
        a2 += dp1 * dp1;
        a3 += dq1 * dq1;
      }
      for (; j < len; j++) {
        const PetscReal dp = p[j + m] - p[j], dq = q[j + m] - q[j];
        a0 += dp * dp + dq * dq;
      }
      const PetscReal M = (a0 + a1 + a2 + a3) / len;
      D[li] = M - mean * mean * (1 - std::cos(m * c)) / (1 - std::cos(c));
    }
    K.push_back(Correlation(lag, D));
  }
  std::sort(K.begin(), K.end());
  const size_t h = K.size() / 2;
  return K.size() % 2 ? K[h] : 0.5 * (K[h - 1] + K[h]);
}

} // namespace nltopo
