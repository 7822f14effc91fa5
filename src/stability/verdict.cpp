#include "stability/verdict.hpp"
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

namespace nltopo {

const char *VerdictName(Verdict v)
{
  switch (v) {
  case Verdict::Stable: return "stable";
  case Verdict::UnstableLocalized: return "unstable-localized";
  case Verdict::UnstableExtended: return "unstable-extended";
  case Verdict::StableTo: return "stable-to";
  case Verdict::Unresolved: return "unresolved";
  }
  return "unresolved";
}

static OrbitVerdict Make(Verdict code, PetscReal bound, const std::string &reason)
{
  OrbitVerdict v;
  v.code = code, v.bound = bound, v.reason = reason;
  return v;
}
OrbitVerdict StableVerdict(PetscReal tol, const std::string &reason) { return Make(Verdict::Stable, tol, reason); }
OrbitVerdict StableToVerdict(PetscReal delta, const std::string &reason) { return Make(Verdict::StableTo, delta, reason); }
OrbitVerdict UnresolvedVerdict(PetscReal bound, const std::string &reason) { return Make(Verdict::Unresolved, bound, reason); }

std::string VerdictLabel(const OrbitVerdict &v)
{
  static const char *cls[] = {"-", "B-B", "B-E", "E-E"};
  char b[160];
  switch (v.code) {
  case Verdict::UnstableLocalized:
  case Verdict::UnstableExtended:
    std::snprintf(b, sizeof b, "%s(|mu| = %.7f, %s, e-folding %.3g periods)", VerdictName(v.code), (double)std::hypot(v.mu_re, v.mu_im),
                  cls[v.cls >= 0 && v.cls <= 3 ? v.cls : 0], (double)v.efold);
    break;
  case Verdict::Stable: std::snprintf(b, sizeof b, "stable(|mu| <= 1 + %.1e)", (double)v.bound); break;
  case Verdict::StableTo: std::snprintf(b, sizeof b, "stable-to(%.1e)", (double)v.bound); break;
  default: std::snprintf(b, sizeof b, "unresolved(bound %.1e)", (double)v.bound); break;
  }
  return b;
}

OrbitVerdict UnstableVerdict(std::complex<PetscReal> mu, PetscInt cls, const std::string &reason)
{
  OrbitVerdict v;
  v.code = cls >= 2 ? Verdict::UnstableLocalized : Verdict::UnstableExtended;
  v.cls = cls;
  v.mu_re = mu.real();
  v.mu_im = std::abs(mu.imag());
  v.bound = std::abs(mu) - 1;
  v.efold = 1 / std::log(std::abs(mu));
  v.reason = reason;
  return v;
}

// |x|^2 + |y|^2 (y may be null) over every entry, or over the (u, v) entries of
// the sites window[0]..window[1] (natural order). Collective.
static PetscErrorCode PairNorm(const Lattice &lat, Vec x, Vec y, const PetscInt *window, PetscReal *n)
{
  const PetscInt xs = lat.OwnedStart(), xm = lat.OwnedCount();
  PetscReal sum = 0;
  PetscFunctionBeginUser;
  for (Vec q : {x, y}) {
    if (!q) continue;
    const PetscScalar *a;
    PetscCall(VecGetArrayRead(q, &a));
    const PetscInt lo = window ? std::max(window[0], xs) : xs, hi = window ? std::min(window[1], xs + xm - 1) : xs + xm - 1;
    for (PetscInt i = lo; i <= hi; i++) sum += a[i - xs] * a[i - xs] + a[xm + i - xs] * a[xm + i - xs];
    PetscCall(VecRestoreArrayRead(q, &a));
  }
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &sum, 1, MPIU_REAL, MPI_SUM, lat.Comm()));
  *n = std::sqrt(sum);
  PetscFunctionReturn(0);
}

PetscErrorCode ConfirmGrowth(PeriodicFlow &flow, Vec z0, PetscReal T, PetscReal beta, Vec vr, Vec vi, const FloquetOptions &o, OrbitVerdict *v,
                             const PetscInt *window)
{
  OwnedVec x, y, w, zT;
  PetscReal n0, nk;
  PetscFunctionBeginUser;
  if (v->code != Verdict::UnstableLocalized && v->code != Verdict::UnstableExtended) PetscFunctionReturn(0);
  PetscCall(VecDuplicate(vr, x.out()));
  PetscCall(VecDuplicate(vr, w.out()));
  PetscCall(VecDuplicate(z0, zT.out()));
  PetscCall(VecCopy(vr, x));
  if (vi) {
    PetscCall(VecDuplicate(vi, y.out()));
    PetscCall(VecCopy(vi, y));
  }
  PetscCall(PairNorm(flow.Lat(), x, y, window, &n0));
  // M^k v for the real and imaginary parts: their joint norm grows exactly as |mu|^k for an eigenvector.
  for (PetscInt k = 0; k < o.confirm_periods; k++) {
    PetscCall(flow.IntegrateWithTangent(z0, T, beta, x, 0, 0, zT, w));
    PetscCall(VecCopy(w, x));
    if (y) {
      PetscCall(flow.IntegrateWithTangent(z0, T, beta, y, 0, 0, zT, w));
      PetscCall(VecCopy(w, y));
    }
  }
  PetscCall(PairNorm(flow.Lat(), x, y, window, &nk));
  const PetscReal rate = std::log(nk / n0) / o.confirm_periods, expect = std::log(std::hypot(v->mu_re, v->mu_im));
  const char *what = window ? "the eigenvector's window norm" : "the eigenvector";
  v->confirmed_rate = rate;
  std::ostringstream s;
  if (!(std::abs(rate - expect) <= o.confirm_rtol * expect)) {
    s << VerdictName(v->code) << " not confirmed: over " << o.confirm_periods << " periods of the undamped lattice " << what << " grew at " << rate
      << " per period where ln|mu| = " << expect << " (-floquet_confirm_rtol " << o.confirm_rtol << "); " << v->reason;
    v->code = Verdict::Unresolved; // bound stays |mu| - 1: growth this large is neither shown nor excluded
    v->efold = std::numeric_limits<PetscReal>::infinity();
  } else
    s << v->reason << "; confirmed on the undamped lattice: " << what << " grew at " << rate << " per period over " << o.confirm_periods
      << " periods (ln|mu| = " << expect << ")";
  v->reason = s.str();
  PetscFunctionReturn(0);
}

// The dense route's verdict: stable, or unstable with the most unstable eigenvector's class, confirmed.
PetscErrorCode DenseVerdict(PeriodicFlow &flow, Vec z0, PetscReal T, PetscReal beta, const FloquetOptions &o, bool stable, PetscReal max_modulus,
                                   std::complex<PetscReal> mu, PetscInt cls, Vec vr, Vec vi, OrbitVerdict *v)
{
  char b[200];
  PetscFunctionBeginUser;
  if (stable) {
    std::snprintf(b, sizeof b, "dense monodromy: every multiplier within 1 + %.1e (max |mu| - 1 = %.1e)", (double)o.tol, (double)(max_modulus - 1));
    *v = StableVerdict(o.tol, b);
    PetscFunctionReturn(0);
  }
  if (cls < 1) { // no eigenvector (inverse iteration failed): the class is unknown and nothing can be confirmed
    std::snprintf(b, sizeof b, "dense monodromy: |mu| = %.7f beyond 1 + %.1e, but its eigenvector was not found", (double)std::abs(mu), (double)o.tol);
    *v = UnresolvedVerdict(std::abs(mu) - 1, b);
    PetscFunctionReturn(0);
  }
  std::snprintf(b, sizeof b, "dense monodromy: |mu| = %.7f beyond 1 + %.1e, eigenvector edge class %s", (double)std::abs(mu), (double)o.tol,
                cls == 3 ? "E-E" : cls == 2 ? "B-E" : "B-B");
  *v = UnstableVerdict(mu, cls, b);
  PetscCall(ConfirmGrowth(flow, z0, T, beta, vr, vi, o, v));
  PetscFunctionReturn(0);
}

} // namespace nltopo
