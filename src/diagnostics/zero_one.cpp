#include "diagnostics/zero_one.hpp"
#include <algorithm>
#include <cmath>
#include <cstdint>
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

// w[d] = 2 cos(d c), d < mmax, by a rotation recurrence re-anchored every 64 terms against drift.
void TwiceCos(PetscReal c, PetscInt mmax, PetscReal *w)
{
  PetscReal cr = 1, si = 0;
  const PetscReal cc = std::cos(c), sc = std::sin(c);
  for (PetscInt d = 0; d < mmax; d++) {
    if (d % 64 == 0) {
      cr = std::cos(d * c);
      si = std::sin(d * c);
    }
    w[d] = 2 * cr;
    const PetscReal t = cr * cc - si * sc;
    si = si * cc + cr * sc;
    cr = t;
  }
}

// The batched kernel (ScoreSites) scores Lanes<V>() sites at once: a V holds
// one value of each lane (GCC/Clang vector extension), and every loop below
// does LagCorrelations' and Score's arithmetic lane by lane and in their order,
// so that its K are Score's bit for bit; what it changes is which sums run side
// by side (lanes, lags, frequencies). Two lane widths: two (SSE2 on x86-64,
// any target), four under target("avx") where the CPU has it (AVX has no
// fused multiply-add: the same roundings).
typedef PetscReal V2 __attribute__((vector_size(16)));
#if defined(__x86_64__) && defined(__GNUC__)
#define NLTOPO_ZERO_ONE_AVX 1
typedef PetscReal V4 __attribute__((vector_size(32)));
#endif
template <class V> constexpr PetscInt Lanes() { return sizeof(V) / sizeof(PetscReal); }
constexpr PetscInt kLagBlock = 3, kFreqBlock = 4;
#define NLTOPO_INLINE inline __attribute__((always_inline)) // into the wrappers of each lane width

// LagCorrelations' partial sums beyond the head: for d < mmax, the lagged
// products y_k = x_k x_{k+d} from k = a = mmax - d + 1 on go to four sums t_i
// (k = a + 4q + i, q < Q = (len - a + 1) / 4), the left-over k <= len to t0, and
// T[d] = (t0 + t1) + (t2 + t3). Indexed by u = k + d, the term goes to
// t_{(u - mmax - 1) mod 4} whatever d: kLagBlock lags share one pass over u.
template <class V> NLTOPO_INLINE void BlockPartialSums(const V *x, PetscInt len, PetscInt mmax, V *T)
{
  const PetscInt u0 = mmax + 1;
  for (PetscInt d0 = 0; d0 < mmax; d0 += kLagBlock) {
    const PetscInt nd = std::min(kLagBlock, mmax - d0), qmin = (len - mmax + d0) / 4; // Q grows with d
    V t[kLagBlock][4] = {};
    if (nd == kLagBlock) {
      for (PetscInt q = 0; q < qmin; q++) {
        const V *xu = x + u0 + 4 * q, *xk = xu - d0; // x_{k+d} and x_k at d = d0
        for (PetscInt i = 0; i < 4; i++)
          for (PetscInt j = 0; j < kLagBlock; j++) t[j][i] += xk[i - j] * xu[i];
      }
    } else {
      for (PetscInt q = 0; q < qmin; q++)
        for (PetscInt i = 0; i < 4; i++)
          for (PetscInt j = 0; j < nd; j++) t[j][i] += x[u0 + 4 * q + i - d0 - j] * x[u0 + 4 * q + i];
    }
    for (PetscInt j = 0; j < nd; j++) {
      const PetscInt d = d0 + j, Q = (len - mmax + d) / 4;
      for (PetscInt q = qmin; q < Q; q++)
        for (PetscInt i = 0; i < 4; i++) t[j][i] += x[u0 + 4 * q + i - d] * x[u0 + 4 * q + i];
      for (PetscInt u = u0 + 4 * Q; u <= len + d; u++) t[j][0] += x[u - d] * x[u];
      T[d] = (t[j][0] + t[j][1]) + (t[j][2] + t[j][3]);
    }
  }
}

// LagCorrelations for the lanes of x, given BlockPartialSums' T: C[li * mmax + d] = C_{lag[li]}(d)
// (work: 4 (mmax + 1)). The head and tail chains of one d run side by side.
template <class V> NLTOPO_INLINE void BlockLagCorrelations(const V *x, PetscInt len, const PetscInt *lag, PetscInt nl, PetscInt mmax, const V *T, V *C, V *work)
{
  for (PetscInt i = 0; i < nl * mmax; i++) C[i] = V{};
  V *head = work, *head_w = head + mmax + 1, *tail = head_w + mmax + 1, *tail_w = tail + mmax + 1;
  for (PetscInt d = 0; d < mmax; d++) {
    V h = {}, hw = {}, t = {}, tw = {};
    head[0] = head_w[0] = tail[0] = tail_w[0] = h;
    for (PetscInt k = 1; k <= mmax - d; k++) {
      const V y = x[k] * x[k + d];
      head[k] = h = h + y;
      head_w[k] = hw = hw + (PetscReal)k * y;
      if (k < mmax - d) {
        const V z = x[len + k] * x[len + k + d];
        tail[k] = t = t + z;
        tail_w[k] = tw = tw + (PetscReal)k * z;
      }
    }
    const V total = head[mmax - d] + T[d];
    for (PetscInt li = 0; li < nl; li++) {
      const PetscInt w = lag[li] - d; // m - d
      if (w <= 0) continue;
      C[li * mmax + d] = head_w[w] + (PetscReal)w * (total - head[w]) + ((PetscReal)w * tail[w - 1] - tail_w[w - 1]);
    }
  }
}

PetscReal Median(std::vector<PetscReal> &K)
{
  std::sort(K.begin(), K.end());
  const size_t h = K.size() / 2;
  return K.size() % 2 ? K[h] : 0.5 * (K[h - 1] + K[h]);
}
} // namespace

std::vector<PetscInt> ZeroOneTest::Lags(PetscInt n) const
{
  const PetscInt ncut = n / 10;
  std::vector<PetscInt> lag;
  if (lags_ > 0 && lags_ < ncut) {
    for (PetscInt i = 0; i < lags_; i++) lag.push_back(1 + (PetscInt)std::llround((double)i * (ncut - 1) / (lags_ - 1 > 0 ? lags_ - 1 : 1)));
  } else {
    for (PetscInt m = 1; m <= ncut; m++) lag.push_back(m);
  }
  return lag;
}

PetscReal ZeroOneTest::Score(const PetscReal *phi, PetscInt n, PetscInt stride) const
{
  const PetscInt ncut = n / 10;
  const PetscInt len = n - ncut; // the same number of increments for every m
  const std::vector<PetscInt> lag = Lags(n);
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
    TwiceCos(c, mmax, cosd.data());
    for (size_t li = 0; li < lag.size(); li++) {
      const PetscInt m = lag[li];
      const PetscReal *Cm = C.data() + li * mmax;
      PetscReal S = Cm[0];
      for (PetscInt d = 1; d < m; d++) S += cosd[d] * Cm[d];
      D[li] = S / len - mean * mean * (1 - std::cos(m * c)) / (1 - std::cos(c));
    }
    K.push_back(Correlation(lag, D));
  }
  return Median(K);
}

namespace {
// One ScoreSites call: the record, the lags, what depends on c alone, and
// scratch for ScoreBlocks at the widest lanes (aligned to 64 bytes).
struct BlockProblem {
  const PetscReal *samples;
  PetscInt n, N, len, mmax, nl, nc, ncpad;
  const PetscInt *sites, *lag;
  size_t nsites;
  const PetscReal *cosd, *osc, *osc1; // 2 cos(d c) [ci * mmax + d] (zero rows pad nc to ncpad), 1 - cos(m c), 1 - cos(c)
  PetscReal *scratch;
  PetscReal *K;
};

// ScoreBlocks' scratch, in units of V (whatever its lanes).
size_t ScratchSize(const BlockProblem &p) { return (size_t)p.n + p.mmax + p.nl * p.mmax + 4 * (p.mmax + 1) + p.ncpad * p.nl + p.ncpad * p.mmax; }

template <class V> NLTOPO_INLINE void ScoreBlocks(const BlockProblem &p)
{
  constexpr PetscInt L = Lanes<V>();
  const PetscInt n = p.n, N = p.N, len = p.len, mmax = p.mmax, nl = p.nl, nc = p.nc, ncpad = p.ncpad;
  V *x = reinterpret_cast<V *>(p.scratch), *T = x + n, *C = T + mmax, *work = C + nl * mmax, *S = work + 4 * (mmax + 1), *cosv = S + ncpad * nl;
  for (PetscInt i = 0; i < ncpad * mmax; i++) cosv[i] = V{} + p.cosd[i]; // in every lane
  std::vector<PetscReal> D(nl), Kc(nc);
  const std::vector<PetscInt> lag(p.lag, p.lag + nl);
  for (size_t b = 0; b < p.nsites; b += L) {
    const PetscInt nb = std::min((PetscInt)(p.nsites - b), L);
    V mean = {};
    for (PetscInt j = 0; j < n; j++) {
      for (PetscInt s = 0; s < L; s++) x[j][s] = s < nb ? p.samples[(size_t)j * N + p.sites[b + s]] : 0;
      mean += x[j];
    }
    mean /= (PetscReal)n;
    BlockPartialSums(x, len, mmax, T);
    BlockLagCorrelations(x, len, p.lag, nl, mmax, T, C, work);
    // S_c(m) = C_m(0) + sum_{d=1}^{m-1} 2 cos(d c) C_m(d), kFreqBlock c side by side.
    for (PetscInt li = 0; li < nl; li++) {
      const V *Cm = C + li * mmax;
      for (PetscInt c0 = 0; c0 < ncpad; c0 += kFreqBlock) {
        V acc[kFreqBlock];
        for (PetscInt j = 0; j < kFreqBlock; j++) acc[j] = Cm[0];
        for (PetscInt dd = 1; dd < p.lag[li]; dd++)
          for (PetscInt j = 0; j < kFreqBlock; j++) acc[j] += cosv[(c0 + j) * mmax + dd] * Cm[dd];
        for (PetscInt j = 0; j < kFreqBlock; j++) S[(c0 + j) * nl + li] = acc[j];
      }
    }
    for (PetscInt s = 0; s < nb; s++) {
      for (PetscInt ci = 0; ci < nc; ci++) {
        for (PetscInt li = 0; li < nl; li++) D[li] = S[ci * nl + li][s] / len - mean[s] * mean[s] * p.osc[ci * nl + li] / p.osc1[ci];
        Kc[ci] = Correlation(lag, D);
      }
      p.K[b + s] = Median(Kc);
    }
  }
}

void ScoreBlocks2(const BlockProblem &p) { ScoreBlocks<V2>(p); }
#if defined(NLTOPO_ZERO_ONE_AVX)
__attribute__((target("avx"))) void ScoreBlocks4(const BlockProblem &p) { ScoreBlocks<V4>(p); }
#endif
} // namespace

// Score for blocks of sites (the last block zero padded).
void ZeroOneTest::ScoreSites(const PetscReal *samples, PetscInt n, PetscInt N, const std::vector<PetscInt> &sites, std::vector<PetscReal> &K, bool wide) const
{
  const std::vector<PetscInt> lag = Lags(n);
  BlockProblem p;
  p.samples = samples, p.n = n, p.N = N, p.len = n - n / 10, p.sites = sites.data(), p.nsites = sites.size(), p.lag = lag.data();
  p.mmax = *std::max_element(lag.begin(), lag.end()), p.nl = (PetscInt)lag.size(), p.nc = (PetscInt)c_.size();
  p.ncpad = (p.nc + kFreqBlock - 1) / kFreqBlock * kFreqBlock;
  std::vector<PetscReal> cosd(p.ncpad * p.mmax, 0.0), osc(p.nc * p.nl), osc1(p.nc);
  for (PetscInt ci = 0; ci < p.nc; ci++) {
    TwiceCos(c_[ci], p.mmax, cosd.data() + ci * p.mmax);
    for (PetscInt li = 0; li < p.nl; li++) osc[ci * p.nl + li] = 1 - std::cos(lag[li] * c_[ci]);
    osc1[ci] = 1 - std::cos(c_[ci]);
  }
  p.cosd = cosd.data(), p.osc = osc.data(), p.osc1 = osc1.data();
  std::vector<PetscReal> scratch(4 * ScratchSize(p) + 8);
  p.scratch = reinterpret_cast<PetscReal *>((reinterpret_cast<uintptr_t>(scratch.data()) + 63) & ~(uintptr_t)63);
  K.assign(sites.size(), 0.0);
  p.K = K.data();
#if defined(NLTOPO_ZERO_ONE_AVX)
  static const bool avx = __builtin_cpu_supports("avx");
  if (wide && avx) return ScoreBlocks4(p);
#endif
  (void)wide;
  ScoreBlocks2(p);
}

PetscReal ZeroOneTest::ScoreMax(const PetscReal *samples, PetscInt n, PetscInt N, const std::vector<PetscInt> &sites) const
{
  std::vector<PetscReal> K;
  ScoreSites(samples, n, N, sites, K);
  PetscReal kmax = -1;
  for (PetscReal k : K) kmax = std::max(kmax, k);
  return kmax;
}

} // namespace nltopo
