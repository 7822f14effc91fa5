#include "studies/sweep_shard.hpp"
#include <algorithm>
#include <cctype>
#include <cmath>
#include <functional>
#include <numeric>
#include <queue>

namespace nltopo {

PetscErrorCode ParseSweepShard(MPI_Comm comm, const std::string &text, size_t points, SweepShard *shard)
{
  PetscFunctionBeginUser;
  *shard = SweepShard();
  if (text.empty()) PetscFunctionReturn(0);
  // two decimal integers around one slash, nothing else (no sign, no space)
  const size_t slash = text.find('/');
  auto digits = [](const std::string &s) {
    return !s.empty() && s.size() <= 9 && std::all_of(s.begin(), s.end(), [](char c) { return std::isdigit((unsigned char)c); });
  };
  const bool ok = slash != std::string::npos && digits(text.substr(0, slash)) && digits(text.substr(slash + 1));
  PetscCheck(ok, comm, PETSC_ERR_USER, "-sweep_shard %s: give i/n, shard i of n (0 <= i < n), e.g. 0/4", text.c_str());
  const long i = std::stol(text.substr(0, slash)), n = std::stol(text.substr(slash + 1));
  PetscCheck(n >= 1 && i < n, comm, PETSC_ERR_USER, "-sweep_shard %s: shard i of n needs 0 <= i < n, got i = %ld, n = %ld", text.c_str(), i, n);
  PetscCheck((size_t)n <= points, comm, PETSC_ERR_USER, "-sweep_shard %s: %ld shards of a grid of %zu points (at most one shard per point)", text.c_str(), n,
             points);
  shard->index = (PetscInt)i;
  shard->count = (PetscInt)n;
  PetscFunctionReturn(0);
}

PetscReal SweepCostEnergy(const LatticeParams &lp, PetscReal dt_quartic_energy)
{
  if (dt_quartic_energy > 0) return dt_quartic_energy;
  return lp.Gamma != 0 ? lp.K1() * lp.K1() / (2 * std::fabs(lp.Gamma)) : 0;
}

long SweepPointCost(PetscReal energy, PetscReal e_q)
{
  const double c = e_q > 0 && energy > e_q ? std::pow((double)(energy / e_q), 0.25) : 1.0;
  return std::lround(1000 * c);
}

std::vector<size_t> SweepShardPoints(const std::vector<PetscReal> &energy, size_t no, PetscReal e_q, const SweepShard &s, double *share)
{
  const size_t ne = energy.size(), n = s.On() ? (size_t)s.count : 1;
  std::vector<long> cost(ne);
  for (size_t e = 0; e < ne; e++) cost[e] = SweepPointCost(energy[e], e_q);
  // rows most expensive first (the later row among equals: a sweep's order), each row's columns from the last
  std::vector<size_t> rows(ne);
  std::iota(rows.begin(), rows.end(), 0);
  std::sort(rows.begin(), rows.end(), [&](size_t a, size_t b) { return cost[a] != cost[b] ? cost[a] > cost[b] : a > b; });
  using Load = std::pair<long, size_t>; // (cost so far, shard): the least first, the lower shard among equals
  std::priority_queue<Load, std::vector<Load>, std::greater<Load>> heap;
  for (size_t k = 0; k < n; k++) heap.push({0, k});
  std::vector<size_t> mine;
  long total = 0, own = 0;
  for (size_t e : rows)
    for (size_t w = no; w-- > 0;) {
      Load l = heap.top();
      heap.pop();
      if (l.second == (size_t)s.index) mine.push_back(e * no + w), own += cost[e];
      total += cost[e];
      l.first += cost[e];
      heap.push(l);
    }
  std::sort(mine.begin(), mine.end());
  if (share) *share = total ? (double)own / (double)total : 1.0;
  return mine;
}

} // namespace nltopo
