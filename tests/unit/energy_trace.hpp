#pragma once
// A sample sink that keeps the sample times and the total energy.
#include "timeint/simulation.hpp"
#include <vector>

namespace nltopo::test {

class EnergyTrace : public SampleSink {
public:
  std::vector<PetscReal> t, e;
  PetscErrorCode Sample(PetscReal tt, Vec, const EnergyParts &en) override
  {
    t.push_back(tt);
    e.push_back(en.Total());
    return 0;
  }
};

} // namespace nltopo::test
