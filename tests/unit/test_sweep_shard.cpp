// The sweep's shards (studies/sweep_shard.hpp): every grid point in exactly
// one shard, the shards' modelled costs within one point's cost of each other,
// the same split on every call, and -sweep_shard's text checked in one line.
#include "core/errors.hpp"
#include "helpers.hpp"
#include "studies/sweep_shard.hpp"
#include <algorithm>
#include <cmath>

using namespace nltopo;

TEST_CASE("sweep shards: every point once, balanced by the cost model, the same split every time", "[sweep][serial]")
{
  const size_t no = 7;
  std::vector<PetscReal> energy;
  for (int e = 0; e < 11; e++) energy.push_back(std::pow(10.0, -3 + 0.6 * e)); // 1e-3 .. 1e3, log
  const PetscReal e_q = 100;
  CHECK(SweepPointCost(1, e_q) == 1000);
  CHECK(SweepPointCost(1e4, e_q) == std::lround(1000 * std::sqrt(10.0))); // (1e4 / 100)^(1/4)
  for (PetscInt n : {1, 2, 3, 8, 77}) {
    INFO(n << " shards");
    std::vector<int> seen(energy.size() * no, 0);
    long lo = -1, hi = 0, biggest = SweepPointCost(energy.back(), e_q);
    double shares = 0;
    for (PetscInt i = 0; i < n; i++) {
      double share;
      const std::vector<size_t> p = SweepShardPoints(energy, no, e_q, {i, n}, &share);
      CHECK(p == SweepShardPoints(energy, no, e_q, {i, n})); // deterministic
      CHECK(std::is_sorted(p.begin(), p.end()));
      long cost = 0;
      for (size_t k : p) seen.at(k)++, cost += SweepPointCost(energy[k / no], e_q);
      lo = lo < 0 ? cost : std::min(lo, cost), hi = std::max(hi, cost);
      shares += share;
    }
    CHECK(std::all_of(seen.begin(), seen.end(), [](int c) { return c == 1; }));
    CHECK(hi - lo <= biggest); // the longest-processing-time rule's bound
    CHECK(shares == Approx(1));
  }
  // no -sweep_shard: the whole grid
  CHECK(SweepShardPoints(energy, no, e_q, SweepShard()).size() == energy.size() * no);
}

TEST_CASE("-sweep_shard i/n: 0 <= i < n <= points, else one line naming it", "[sweep][serial]")
{
  SweepShard s;
  PCHK(ParseSweepShard(PETSC_COMM_SELF, "2/3", 48, &s));
  CHECK((s.On() && s.index == 2 && s.count == 3));
  PCHK(ParseSweepShard(PETSC_COMM_SELF, "", 48, &s));
  CHECK(!s.On());
  for (const char *bad : {"3/3", "1/0", "-1/3", "1/-3", "a/b", "1/3x", " 1/3", "13", "1/3/4", "5/60", "49/49", "0/1e3", "1.5/3"}) {
    INFO(bad);
    PetscErrorCode ierr;
    char msg[512];
    PCHK(CaptureError([&]() { return ParseSweepShard(PETSC_COMM_SELF, bad, 48, &s); }, &ierr, msg, sizeof msg));
    CHECK(ierr != 0);
    CHECK(std::string(msg).rfind(std::string("-sweep_shard ") + bad + ":", 0) == 0);
  }
}
