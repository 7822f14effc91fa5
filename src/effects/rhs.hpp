#pragma once
// The right-hand side z' = f(t, z) = [v, a(t, u, v)] of one run: the sum of
// the scene's effects (effects/effect.hpp), with the forcing switched off for
// good at the cut-off. Each effect has its own log event and call counter, so
// tests and -log_view can see that an effect the scene did not enable is
// never computed.
#include "effects/effect.hpp"

namespace nltopo {

// Calls per effect of one run; rhs counts the evaluations of f (or of a).
struct EffectCounters {
  PetscInt rhs = 0, linear = 0, cubic = 0, forcing = 0, damping = 0;
};

class Rhs {
public:
  explicit Rhs(const EffectList &fx);

  // State form: f = [v, a(t, u, v)].
  PetscErrorCode Evaluate(PetscReal t, Vec z, Vec f);
  // Split (symplectic) form, momentum part: pdot = a(t, q) (q, pdot: SiteDM
  // layout; velocity-independent effects only).
  PetscErrorCode Momentum(PetscReal t, Vec q, Vec pdot);
  // The same on raw arrays (the symsplit and rkn TS types): a[i] = acceleration
  // of owned site i (local index) for the state (or SiteDM vector) x.
  PetscErrorCode Acceleration(PetscReal t, Vec x, PetscScalar *a);

  bool Forcing() const { return forcing_ >= 0 && calls_.on[forcing_]; }
  void DropForcing()
  {
    if (forcing_ >= 0) calls_.on[forcing_] = 0;
  }
  EffectCounters Counters() const;

private:
  // a[i] for owned sites i (a indexed by global site), x a state or SiteDM vector.
  PetscErrorCode Accelerate(PetscReal t, Vec x, PetscScalar *a);

  const EffectList &fx_;
  EffectCalls calls_;
  PetscInt forcing_ = -1; // index of the forcing effect
  PetscInt rhs_ = 0;
  bool needs_v_;
};

} // namespace nltopo
