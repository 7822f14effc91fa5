#pragma once
// The right-hand side z' = f(t, z) as the sum of the effects the scene enabled
// (model.md, Equations of motion):
//   linear coupling  f = [v, -K u]           (always: the lattice itself; a stencil
//                                            over the bond rule that assembles K and L)
//   cubic bonds      f_v += -f_NL(u)         (only when Gamma != 0)
//   forcing          f_v += eta S g(t)       (only when configured; dropped for good at cut-off)
// Each effect has its own log event and call counter, so tests and -log_view
// can see that an effect the scene did not enable is never computed.
#include "effects/forcing.hpp"
#include "lattice/lattice.hpp"

namespace nltopo {

struct EffectCounters {
  PetscInt rhs = 0, linear = 0, cubic = 0, forcing = 0;
};

class Rhs {
public:
  Rhs(const Lattice &lat, const ToneBurst *forcing);

  // State form: f = [v, -K u - f_NL(u) + F(t)].
  PetscErrorCode Evaluate(PetscReal t, Vec z, Vec f);
  // Split (symplectic) form, momentum part: pdot = -K q - f_NL(q) + F(t) (q, pdot: SiteDM layout).
  PetscErrorCode Momentum(PetscReal t, Vec q, Vec pdot);
  // The same on raw arrays (the symsplit TS type): a[i] = acceleration of owned
  // site i (local index) for the u part of x (a state or SiteDM vector).
  PetscErrorCode Acceleration(PetscReal t, Vec x, PetscScalar *a);

  bool Forcing() const { return forcing_ != nullptr; }
  void DropForcing() { forcing_ = nullptr; }
  const EffectCounters &Counters() const { return count_; }

private:
  // a[i] = -(K u)_i + the local effects, for u the u part of x (state or SiteDM vector).
  PetscErrorCode Accelerate(PetscReal t, Vec x, PetscScalar *a);
  // Cubic bonds and forcing: u ghosted, a[i] the acceleration of site i (both by global site).
  PetscErrorCode AddLocalEffects(PetscReal t, const PetscScalar *u, PetscScalar *a);

  const Lattice &lat_;
  const ToneBurst *forcing_;
  bool cubic_;
  EffectCounters count_;
};

} // namespace nltopo
