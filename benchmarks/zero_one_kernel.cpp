// The 0-1 test's kernel (issue 36 item 5): the sweep point's K, the largest
// over its sites, by Score per site (each site gathered with stride N) against
// ScoreSites (the sites in blocks, as ScoreMax; benchmarks/README.md "Issue 36
// item 5: the 0-1 test kernel"), on a synthetic record of the sweep's shape: n
// samples of N sites, row-major, each site a mix of a few lattice-like tones,
// a slow drift and, on every third site, a logistic-map component (chaotic K).
// The same 32 frequencies and 20 lags as the sweep's defaults (-kcorr_nc,
// -kcorr_lags). -bench_wide 0: blocks of two sites even where the CPU has AVX.
// Each repeat times both; the medians over -bench_repeats are printed with
// max_s |K_blocks(s) - K_Score(s)|.
//
//   ./build/benchmarks/zero_one_kernel -bench_n 1654 -bench_sites 102 -bench_repeats 21 [-bench_wide 0]
#include "bench_clock.hpp"
#include "diagnostics/zero_one.hpp"
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

using namespace nltopo;

namespace {

std::vector<PetscReal> Record(PetscInt n, PetscInt N)
{
  std::vector<PetscReal> x(n * N);
  PetscReal l = 0.3141592;
  for (PetscInt j = 0; j < n; j++) {
    l = 4 * l * (1 - l);
    for (PetscInt s = 0; s < N; s++) {
      const PetscReal a = 1 + 0.5 * std::sin(0.3 * s);
      x[j * N + s] = a * std::cos(1.1 * j + 0.2 * s) + 0.3 * std::sin(1.7 * j * (1 + 0.01 * s)) + 1e-4 * j + (s % 3 == 0 ? 0.2 * l : 0.0);
    }
  }
  return x;
}

} // namespace

int main(int argc, char **argv)
{
  PetscFunctionBeginUser;
  PetscCall(PetscInitialize(&argc, &argv, NULL, "zero_one_kernel: the 0-1 test of a sweep point, per site against batched\n"));
  {
    PetscInt n = 1654, N = 102, repeats = 7, nc = 32, lags = 20;
    PetscBool wide = PETSC_TRUE; // -bench_wide 0: two lanes even where the CPU has AVX
    PetscCall(PetscOptionsGetInt(NULL, NULL, "-bench_n", &n, NULL));
    PetscCall(PetscOptionsGetInt(NULL, NULL, "-bench_sites", &N, NULL));
    PetscCall(PetscOptionsGetInt(NULL, NULL, "-bench_repeats", &repeats, NULL));
    PetscCall(PetscOptionsGetInt(NULL, NULL, "-bench_nc", &nc, NULL));
    PetscCall(PetscOptionsGetInt(NULL, NULL, "-bench_lags", &lags, NULL));
    PetscCall(PetscOptionsGetBool(NULL, NULL, "-bench_wide", &wide, NULL));
    PetscCheck(n >= 100 && N >= 1 && repeats >= 1, PETSC_COMM_SELF, PETSC_ERR_USER,
               "-bench_n >= 100, -bench_sites >= 1, -bench_repeats >= 1 wanted, got %d, %d, %d", (int)n, (int)N, (int)repeats);
    const ZeroOneTest test(nc, 1, lags);
    const std::vector<PetscReal> x = Record(n, N);
    std::vector<PetscInt> sites(N);
    for (PetscInt s = 0; s < N; s++) sites[s] = s;
    std::vector<double> t_old, t_new;
    std::vector<PetscReal> k_old(N), k_new;
    PetscReal kmax_old = -1, kmax_new = -1;
    for (PetscInt r = 0; r < repeats; r++) {
      double t0 = Now();
      kmax_old = -1;
      for (PetscInt s = 0; s < N; s++) kmax_old = std::max(kmax_old, k_old[s] = test.Score(x.data() + s, n, N));
      double t1 = Now();
      test.ScoreSites(x.data(), n, N, sites, k_new, wide);
      kmax_new = *std::max_element(k_new.begin(), k_new.end());
      double t2 = Now();
      t_old.push_back(t1 - t0), t_new.push_back(t2 - t1);
    }
    PetscReal dk = 0;
    for (PetscInt s = 0; s < N; s++) dk = std::max(dk, std::abs(k_new[s] - k_old[s]));
    PetscCall(
        PetscPrintf(PETSC_COMM_SELF, "n %d, sites %d, nc %d, lags %d, repeats %d, wide %d\n", (int)n, (int)N, (int)nc, (int)lags, (int)repeats, (int)wide));
    PetscCall(PetscPrintf(PETSC_COMM_SELF, "Score per site: %.3f ms (max K %.6f); ScoreSites: %.3f ms (max K %.6f); ratio %.2f; max |dK| %.3e\n",
                          1e3 * Median(t_old), (double)kmax_old, 1e3 * Median(t_new), (double)kmax_new, Median(t_old) / Median(t_new), (double)dk));
  }
  PetscCall(PetscFinalize());
  return 0;
}
