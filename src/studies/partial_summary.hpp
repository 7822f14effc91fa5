#pragma once
// What a study's summary may conclude from the runs it did (issue 34, class
// 9): an interrupted study writes its partial output (complete = 0) and says
// so on stdout; a run not done decides nothing, so a conclusion that needs it
// is "not determined", never read as if the run had happened.
#include <petscsys.h>
#include <vector>

namespace nltopo {

// One energy of an energy scan (zak: both band-edge runs).
enum class ScanPoint { Distinct, NotDistinct, NotReached, NotRun };

// The threshold of a scan: the lowest energy that is NotDistinct, with the
// highest Distinct one below it (energies in any order; NotReached decides
// nothing and is passed over). determined is false when an energy not run
// lies below that threshold (or, with none NotDistinct, anywhere): then
// threshold is NaN, first_missing the lowest energy not run, and
// last_distinct the highest Distinct energy below it; not_distinct_above the
// lowest NotDistinct energy (-1: none), an upper bound of the threshold.
struct ThresholdScan {
  bool determined = true;
  PetscReal threshold = -1, last_distinct = -1; // -1: none in range
  PetscReal first_missing = -1, not_distinct_above = -1;
  PetscInt not_run = 0; // energies not run
};
ThresholdScan ScanThreshold(const std::vector<PetscReal> &energy, const std::vector<ScanPoint> &state);

} // namespace nltopo
