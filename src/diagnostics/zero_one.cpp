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

// The mean square displacements S_c(m) = sum_{j<len} |P(j+m) - P(j)|^2, with
// P(j) = sum_{k<=j} x_k e^{i k c}, for every c at once. The increment is a
// window sum, P(j+m) - P(j) = sum_{k=j+1}^{j+m} x_k e^{i k c}, so
//   S_c(m) = C_m(0) + 2 sum_{d=1}^{m-1} cos(d c) C_m(d),
//   C_m(d) = sum_k x_k x_{k+d} #{j < len: j < k, k + d <= j + m},
// where the count is k for k <= m - d, m - d up to k = len, and len + m - d - k
// beyond. The C_m(d) do not depend on c: they cost O(n) per d once, and each c
// then costs O(m) per lag instead of O(n) (the direct sums over j).
// C[li * mmax + d] holds C_{lag[li]}(d).
void LagCorrelations(const std::vector<PetscReal> &x, PetscInt len, const std::vector<PetscInt> &lag, PetscInt mmax, std::vector<PetscReal> &C)
{
  C.assign(lag.size() * mmax, 0.0);
  std::vector<PetscReal> head_w(mmax + 1), head(mmax + 1), tail(mmax + 1), tail_w(mmax + 1);
  for (PetscInt d = 0; d < mmax; d++) {
    const PetscReal *xd = x.data() + d;
    // head[K] = sum_{k=1}^K y_k, head_w[K] = sum_{k=1}^K k y_k (y_k = x_k x_{k+d}), K <= mmax - d
    head[0] = head_w[0] = 0;
    for (PetscInt k = 1; k <= mmax - d; k++) {
      const PetscReal y = x[k] * xd[k];
      head[k] = head[k - 1] + y;
      head_w[k] = head_w[k - 1] + k * y;
    }
    // total = sum_{k=1}^{len} y_k; four partial sums (a single one is bound by the add latency)
    PetscReal t0 = 0, t1 = 0, t2 = 0, t3 = 0;
    PetscInt k = mmax - d + 1;
    for (; k + 3 <= len; k += 4) {
      t0 += x[k] * xd[k];
      t1 += x[k + 1] * xd[k + 1];
      t2 += x[k + 2] * xd[k + 2];
      t3 += x[k + 3] * xd[k + 3];
    }
    for (; k <= len; k++) t0 += x[k] * xd[k];
    const PetscReal total = head[mmax - d] + ((t0 + t1) + (t2 + t3));
    // tail[R] = sum_{r=1}^R y_{len+r}, tail_w[R] = sum_{r=1}^R r y_{len+r}
    tail[0] = tail_w[0] = 0;
    for (PetscInt r = 1; r < mmax - d; r++) {
      const PetscReal y = x[len + r] * xd[len + r];
      tail[r] = tail[r - 1] + y;
      tail_w[r] = tail_w[r - 1] + r * y;
    }
    for (size_t li = 0; li < lag.size(); li++) {
      const PetscInt w = lag[li] - d; // m - d
      if (w <= 0) continue;
      C[li * mmax + d] = head_w[w] + w * (total - head[w]) + (w * tail[w - 1] - tail_w[w - 1]);
    }
  }
}
} // namespace

PetscReal ZeroOneTest::Score(const PetscReal *phi, PetscInt n, PetscInt stride) const
{
  const PetscInt ncut = n / 10;
  const PetscInt len = n - ncut; // the same number of increments for every m
  std::vector<PetscInt> lag;
  if (lags_ > 0 && lags_ < ncut) {
    for (PetscInt i = 0; i < lags_; i++) lag.push_back(1 + (PetscInt)std::llround((double)i * (ncut - 1) / (lags_ - 1 > 0 ? lags_ - 1 : 1)));
  } else {
    for (PetscInt m = 1; m <= ncut; m++) lag.push_back(m);
  }
  const PetscInt mmax = *std::max_element(lag.begin(), lag.end());
  std::vector<PetscReal> x(n), C, D(lag.size()), K, cosd(mmax);
  PetscReal mean = 0;
  for (PetscInt j = 0; j < n; j++) {
    x[j] = phi[j * stride];
    mean += x[j];
  }
  mean /= n;
  LagCorrelations(x, len, lag, mmax, C);
  for (PetscReal c : c_) {
    // cos(d c) by a rotation recurrence, re-anchored every 64 terms against drift
    PetscReal cr = 1, si = 0;
    const PetscReal cc = std::cos(c), sc = std::sin(c);
    for (PetscInt d = 0; d < mmax; d++) {
      if (d % 64 == 0) {
        cr = std::cos(d * c);
        si = std::sin(d * c);
      }
      cosd[d] = 2 * cr;
      const PetscReal t = cr * cc - si * sc;
      si = si * cc + cr * sc;
      cr = t;
    }
    for (size_t li = 0; li < lag.size(); li++) {
      const PetscInt m = lag[li];
      const PetscReal *Cm = C.data() + li * mmax;
      PetscReal S = Cm[0];
      for (PetscInt d = 1; d < m; d++) S += cosd[d] * Cm[d];
      D[li] = S / len - mean * mean * (1 - std::cos(m * c)) / (1 - std::cos(c));
    }
    K.push_back(Correlation(lag, D));
  }
  std::sort(K.begin(), K.end());
  const size_t h = K.size() / 2;
  return K.size() % 2 ? K[h] : 0.5 * (K[h - 1] + K[h]);
}

} // namespace nltopo
