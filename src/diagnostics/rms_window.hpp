#pragma once
// The averaging window of a forced run (README.md "MCR"): from the cut-off
// (or the documented fallback) to the end, the time integrals of u_i^2 (the
// RMS displacement per site, hence the MCR) and of the quartic and linear
// potential energies (the nonlinear/linear ratio). It receives the state at
// every step end, like the sample sinks receive samples: by the trapezoid
// over the steps, or, with a positions interpolant (rkn's long steps), by
// 3-point Gauss-Legendre on each step (exact for degree 5).
#include "effects/effect.hpp"
#include <petscts.h>
#include <vector>

namespace nltopo {

class RmsWindow {
public:
  explicit RmsWindow(const EffectList &fx) : fx_(fx) {}
  // The step interpolant of an rkn TS (TSRknInterpolatePositions).
  void SetInterpolant(TS ts) { interp_ = ts; }
  // The window (re)starts at the next state received (the cut-off).
  void Restart() { open_ = false; }
  // The state z with energy parts e at the end of a step at time t; states
  // before start are ignored until the window opens (*start is set to the
  // time it opened).
  PetscErrorCode Step(PetscReal t, Vec z, const EnergyParts &e, PetscReal *start);
  // RMS per site into rms (SiteDM vector) and the nonlinear/linear ratio, over
  // [start, last state]; a window of zero length gives the last state's values.
  PetscErrorCode Finish(PetscReal start, Vec rms, PetscReal *nl_ratio) const;

private:
  PetscErrorCode GaussStep(PetscReal t, bool *done);
  const EffectList &fx_;
  TS interp_ = nullptr;
  OwnedVec zs_;
  bool open_ = false;
  PetscReal t_prev_ = 0, nl_prev_ = 0, lin_prev_ = 0, acc_nl_ = 0, acc_lin_ = 0;
  std::vector<PetscReal> u2_prev_, acc_u2_;
};

} // namespace nltopo
