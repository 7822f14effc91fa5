#pragma once
// The 0-1 test for chaos, correlation method (Gottwald & Melbourne, "On the
// implementation of the 0-1 test for chaos", SIAM J. Appl. Dyn. Syst. 2009;
// model.md "Diagnostics"). For a series phi_1..phi_n and a frequency c:
//   p(j) = sum_{k<=j} phi_k cos(k c),  q(j) = sum_{k<=j} phi_k sin(k c),
//   M(m) = mean_j [(p(j+m) - p(j))^2 + (q(j+m) - q(j))^2],   m = 1..n/10,
//   D(m) = M(m) - mean(phi)^2 (1 - cos(m c)) / (1 - cos c)   (the oscillatory term),
//   K_c  = corr(m, D(m));   K = median of K_c over c drawn uniformly in (pi/5, 4 pi/5).
// K ~ 0 for regular (periodic, quasi-periodic) series, K ~ 1 for chaotic ones.
// Continuous-time data must not be oversampled: the caller samples the
// signal at about a quarter of its dominant period (docs/model.md "The 0-1 test for chaos"), so
// that its spectrum sits inside the c range rather than near c = 0.
#include <petscsys.h>
#include <vector>

namespace nltopo {

class ZeroOneTest {
public:
  // nc frequencies c, drawn once from a seeded generator: the same c for every
  // series, so a score does not depend on which rank computes it.
  // lags > 0: D(m) at that many lags evenly spread over 1..n/10 instead of
  // all of them (the correlation with m is the same statistic on a sub-grid).
  ZeroOneTest(PetscInt nc, unsigned long seed, PetscInt lags = 0);
  // K of phi[0], phi[stride], ..., phi[(n-1) stride]. n must be >= 20.
  PetscReal Score(const PetscReal *phi, PetscInt n, PetscInt stride = 1) const;
  // K of each of the given sites of a record of n samples of N sites, row-major
  // (samples[j * N + s], the sweep's AfterCutoffSamples): K[i] equals
  // Score(samples + sites[i], n, N), the same sums in the same order. The sites
  // are scored in blocks, the inner loops running across a block's sites, and
  // what does not depend on the site (the cos(d c) tables, the oscillatory
  // term) is computed once per call. n must be >= 20.
  // wide: blocks of four sites where the CPU has AVX, else (and with false) of two.
  void ScoreSites(const PetscReal *samples, PetscInt n, PetscInt N, const std::vector<PetscInt> &sites, std::vector<PetscReal> &K, bool wide = true) const;
  // The largest K over the sites (ScoreSites); -1, the lowest K, if sites is empty.
  PetscReal ScoreMax(const PetscReal *samples, PetscInt n, PetscInt N, const std::vector<PetscInt> &sites) const;
  const std::vector<PetscReal> &Frequencies() const { return c_; }

private:
  // The lags m at which D(m) is evaluated for a series of n samples (ascending).
  std::vector<PetscInt> Lags(PetscInt n) const;

  std::vector<PetscReal> c_;
  PetscInt lags_;
};

} // namespace nltopo
