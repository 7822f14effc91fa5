#include "core/progress.hpp"
#include <cmath>

namespace nltopo {

void ProgressMeter::Start(MPI_Comm comm, PetscReal every)
{
  comm_ = comm;
  every_ = every;
  PetscTime(&start_);
  last_ = start_;
}

PetscErrorCode ProgressMeter::Report(const char *label, const std::string &what, double fraction, bool force)
{
  PetscLogDouble now;
  PetscFunctionBeginUser;
  if (every_ <= 0 || comm_ == MPI_COMM_NULL) PetscFunctionReturn(0);
  PetscCall(PetscTime(&now));
  if (!force && now - last_ < every_) PetscFunctionReturn(0);
  last_ = now;
  const double elapsed = now - start_;
  char eta[64] = "no estimate yet";
  if (std::isfinite(fraction) && fraction > 1e-3 && fraction <= 1)
    PetscCall(PetscSNPrintf(eta, sizeof eta, "about %.3g s to go", elapsed * (1 - fraction) / fraction));
  PetscCall(PetscPrintf(comm_, "  [%s] %s, %.3g s so far, %s\n", label, what.c_str(), elapsed, eta));
  PetscFunctionReturn(0);
}

} // namespace nltopo
