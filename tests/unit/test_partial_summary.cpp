// What an interrupted study may conclude (issue 34, class 9): the zak
// threshold from an energy scan with runs not done (studies/partial_summary.hpp),
// and the work-precision recommendation with configurations without an error.
#include "helpers.hpp"
#include "studies/partial_summary.hpp"
#include "studies/workprecision.hpp"
#include <cmath>

using namespace nltopo;

namespace {
using P = ScanPoint;
const P D = P::Distinct, X = P::NotDistinct, U = P::NotReached, R = P::NotRun;
} // namespace

TEST_CASE("a threshold scan concludes nothing from energies not run", "[serial]")
{
  const std::vector<PetscReal> e = {1, 2, 3, 4, 5};
  // every run done: the old rule (lowest not distinct, highest distinct below it)
  ThresholdScan s = ScanThreshold(e, {D, D, X, D, X});
  REQUIRE((s.determined && s.threshold == 3 && s.last_distinct == 2));
  s = ScanThreshold(e, {D, U, D, D, D}); // E* not reached decides nothing, but is no run missing
  REQUIRE((s.determined && s.threshold == -1 && s.last_distinct == 5));
  // the example: the rest not run is neither "not reached" nor "distinct over the whole range"
  s = ScanThreshold(e, {D, D, R, R, R});
  REQUIRE(!s.determined);
  REQUIRE(std::isnan(s.threshold));
  REQUIRE((s.last_distinct == 2 && s.first_missing == 3 && s.not_run == 3 && s.not_distinct_above == -1));
  // not distinct above a gap: the threshold lies at or below 4, not at 4
  s = ScanThreshold(e, {D, R, D, X, R});
  REQUIRE((!s.determined && s.last_distinct == 1 && s.not_distinct_above == 4 && s.first_missing == 2));
  // a gap above the threshold does not matter
  s = ScanThreshold(e, {D, X, R, R, R});
  REQUIRE((s.determined && s.threshold == 2 && s.last_distinct == 1));
  // energies in any order (an -zak_energy_list as given): the lowest, not the first listed
  s = ScanThreshold({5, 1, 3, 2}, {X, D, X, D});
  REQUIRE((s.determined && s.threshold == 3 && s.last_distinct == 2));
}

TEST_CASE("a work-precision recommendation counts the configurations it could not compare", "[serial]")
{
  WorkPrecisionResult res;
  res.observables = {"mcr"};
  WorkPrecisionRow a, b;
  a.config = "a", a.error = {1e-3}, a.wall = 2;
  b.config = "b", b.error = {NAN}, b.wall = 1;
  res.rows = {a, b};
  std::vector<WpRecommendation> r = CheapestMeeting(res, 1e-2);
  REQUIRE((r[0].config == "a" && r[0].unscored == 1));
  r = CheapestMeeting(res, 1e-4);
  REQUIRE((r[0].config.empty() && r[0].unscored == 1 && r[0].error == 1e-3));
}
