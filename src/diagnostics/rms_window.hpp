#pragma once
// The averaging window of a forced run (docs/model.md "RMS window, MCR and nl_ratio"): from the cut-off
// (or the documented fallback) to the end, the time integrals of u_i^2 (the
// RMS displacement per site, hence the MCR) and of the quartic and linear
// potential energies (the nonlinear/linear ratio).
//
// Two ways in. The integrator carries the integrals as quadrature states
// (Integrals(), whose rate is Integrand()): then they are integrated by the
// scheme's own weights at its stages, to the accuracy of the run. Otherwise
// (an integrator that does not carry them) over the step ends passed to
// Step(): u_i^2 by the two-point Hermite rule (fourth order in the step), the
// energies by the trapezoid. Finish() uses the quadrature states when the integrator
// evaluated the integrand inside the window, the trapezoid otherwise.
#include "effects/effect.hpp"
#include <vector>

namespace nltopo {

class RmsWindow {
public:
  explicit RmsWindow(const EffectList &fx) : fx_(fx) {}
  // The window (re)starts at the next state received (the cut-off).
  void Restart() { open_ = false; }
  // The state z with energy parts e at the end of a step at time t; states
  // before start are ignored until the window opens (*start is set to the
  // time it opened, and the quadrature states are zeroed then).
  PetscErrorCode Step(PetscReal t, Vec z, const EnergyParts &e, PetscReal *start);
  // The quadrature states (created on the first call): per rank, the owned
  // sites' integrals of u_i^2, then this rank's share of the integrals of the
  // quartic and of the linear potential energy.
  PetscErrorCode Integrals(Vec *q);
  // Their rate at the state z (positions read only): zero while the window is
  // closed (collective on the lattice when it has more than one rank).
  PetscErrorCode Integrand(Vec z, Vec rate);
  // Adds a step of length h with stage states y[i] and weights b[i] to the
  // quadrature states, when the window is open (an explicit Runge-Kutta step).
  PetscErrorCode AddStages(PetscReal h, PetscInt s, const PetscReal *b, const Vec *y);
  // RMS per site into rms (SiteDM vector) and the nonlinear/linear ratio, over
  // [start, last state]; a window of zero length gives the last state's values.
  PetscErrorCode Finish(PetscReal start, Vec rms, PetscReal *nl_ratio) const;

private:
  const EffectList &fx_;
  OwnedVec q_, rate_;    // the quadrature states; a rate (AddStages)
  bool carried_ = false; // the integrator evaluated the integrand inside the window
  bool open_ = false;
  PetscReal t_prev_ = 0, nl_prev_ = 0, lin_prev_ = 0, acc_nl_ = 0, acc_lin_ = 0;
  std::vector<PetscReal> u2_prev_, du2_prev_, acc_u2_; // u_i^2 and its derivative at the last state
};

} // namespace nltopo
