#pragma once
// Progress lines for phases longer than a few seconds: at most one line per
// `every` wall seconds (0: none), saying how far the phase is, the time so
// far and an estimate of the time to go from the fraction done.
#include <petscsys.h>
#include <string>

namespace nltopo {

class ProgressMeter {
public:
  // every: seconds between lines (0: never). Starts the clock.
  void Start(MPI_Comm comm, PetscReal every);
  // When a line is due (or force): "  [label] <what>, <t> s so far, about <eta> s to go".
  // fraction: the share done, in [0, 1] (outside: no estimate).
  PetscErrorCode Report(const char *label, const std::string &what, double fraction, bool force = false);

private:
  MPI_Comm comm_ = MPI_COMM_NULL;
  PetscReal every_ = 0;
  PetscLogDouble start_ = 0, last_ = 0;
};

} // namespace nltopo
