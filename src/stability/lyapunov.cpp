#include "stability/lyapunov.hpp"
#include "core/handle.hpp"
#include "core/log.hpp"
#include "orbits/flow.hpp"

namespace nltopo {

namespace {

// A fixed start vector with weight on every site (positions and velocities),
// unit norm: the same at every point of a sweep and on any number of ranks
// (LyapunovStartValue of the natural state index).
PetscErrorCode StartVector(const Lattice &lat, Vec v)
{
  const PetscInt N = lat.N(), xs = lat.OwnedStart(), xm = lat.OwnedCount();
  PetscScalar *a;
  PetscFunctionBeginUser;
  PetscCall(VecGetArray(v, &a));
  for (PetscInt i = xs; i < xs + xm; i++) a[i - xs] = LyapunovStartValue(i), a[xm + i - xs] = LyapunovStartValue(N + i); // [u owned | v owned]
  PetscCall(VecRestoreArray(v, &a));
  PetscReal n;
  PetscCall(VecNormalize(v, &n));
  PetscFunctionReturn(0);
}

} // namespace

PetscErrorCode FiniteTimeLyapunov(const EffectList &fx, Vec z0, PetscReal window, PetscReal renorm, PetscReal dt, LyapunovResult *r)
{
  PetscLogEvent ev;
  PetscFunctionBeginUser;
  *r = LyapunovResult();
  r->window = window;
  if (!(window > 0)) PetscFunctionReturn(0);
  PetscCall(NamedLogEvent("Lyapunov", &ev));
  PetscCall(PetscLogEventBegin(ev, 0, 0, 0, 0));
  const PetscInt n = std::max<PetscInt>(1, (PetscInt)std::ceil(window / renorm - 1e-9));
  const PetscReal tau = window / n;
  FlowOptions fo;
  fo.steps = std::max<PetscInt>(1, (PetscInt)std::ceil(tau / dt - 1e-9));
  PeriodicFlow flow;
  PetscCall(flow.Setup(fx, fo));
  OwnedVec z, zT, v, w;
  PetscCall(VecDuplicate(z0, z.out()));
  PetscCall(VecDuplicate(z0, zT.out()));
  PetscCall(VecDuplicate(z0, v.out()));
  PetscCall(VecDuplicate(z0, w.out()));
  PetscCall(VecCopy(z0, z));
  PetscCall(StartVector(fx.Lat(), v));
  PetscReal sum = 0;
  for (PetscInt k = 0; k < n; k++) {
    PetscReal g;
    PetscCall(flow.IntegrateWithTangent(z, tau, 0.0, v, 0, 0, zT, w));
    PetscCall(VecNorm(w, NORM_2, &g));
    sum += std::log(g);
    PetscCall(VecAXPBY(v, 1 / g, 0.0, w)); // renormalised
    PetscCall(VecCopy(zT, z));
    if (k + 1 == (n + 1) / 2) r->half = sum / (tau * (k + 1));
  }
  r->exponent = sum / window;
  r->intervals = n;
  PetscCall(PetscLogEventEnd(ev, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

} // namespace nltopo
