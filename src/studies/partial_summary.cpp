#include "studies/partial_summary.hpp"
#include <algorithm>
#include <cmath>
#include <numeric>

namespace nltopo {

ThresholdScan ScanThreshold(const std::vector<PetscReal> &energy, const std::vector<ScanPoint> &state)
{
  ThresholdScan s;
  std::vector<size_t> order(energy.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) { return energy[a] < energy[b]; });
  PetscReal distinct_known = -1; // the highest Distinct energy below the first one not run
  for (size_t i : order) {
    const PetscReal e = energy[i];
    switch (state[i]) {
    case ScanPoint::NotRun:
      s.not_run++;
      if (s.first_missing < 0) s.first_missing = e;
      break;
    case ScanPoint::Distinct:
      if (s.not_distinct_above < 0 && s.first_missing < 0) distinct_known = e;
      break;
    case ScanPoint::NotDistinct:
      if (s.not_distinct_above < 0) s.not_distinct_above = e;
      break;
    case ScanPoint::NotReached: break;
    }
  }
  s.last_distinct = distinct_known;
  // Determined: no energy not run below the first NotDistinct (with none NotDistinct: no energy not run at all).
  s.determined = s.first_missing < 0 || (s.not_distinct_above >= 0 && s.not_distinct_above < s.first_missing);
  s.threshold = !s.determined ? NAN : s.not_distinct_above;
  return s;
}

} // namespace nltopo
