#include "stability/verdict.hpp"
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

// |x|^2 + |y|^2 (y may be null), collective.
static PetscErrorCode PairNorm(Vec x, Vec y, PetscReal *n)
{
  PetscReal a, b = 0;
  PetscFunctionBeginUser;
  PetscCall(VecNorm(x, NORM_2, &a));
  if (y) PetscCall(VecNorm(y, NORM_2, &b));
  *n = std::sqrt(a * a + b * b);
  PetscFunctionReturn(0);
}

PetscErrorCode ConfirmGrowth(PeriodicFlow &flow, Vec z0, PetscReal T, PetscReal beta, Vec vr, Vec vi, const FloquetOptions &o, OrbitVerdict *v)
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
  PetscCall(PairNorm(x, y, &n0));
  // M^k v for the real and imaginary parts: their joint norm grows exactly as |mu|^k for an eigenvector.
  for (PetscInt k = 0; k < o.confirm_periods; k++) {
    PetscCall(flow.IntegrateWithTangent(z0, T, beta, x, 0, 0, zT, w));
    PetscCall(VecCopy(w, x));
    if (y) {
      PetscCall(flow.IntegrateWithTangent(z0, T, beta, y, 0, 0, zT, w));
      PetscCall(VecCopy(w, y));
    }
  }
  PetscCall(PairNorm(x, y, &nk));
  const PetscReal rate = std::log(nk / n0) / o.confirm_periods, expect = std::log(std::hypot(v->mu_re, v->mu_im));
  v->confirmed_rate = rate;
  if (!(std::abs(rate - expect) <= o.confirm_rtol * expect)) {
    std::ostringstream s;
    s << VerdictName(v->code) << " not confirmed: over " << o.confirm_periods << " periods the eigenvector grew at " << rate
      << " per period where ln|mu| = " << expect << " (-floquet_confirm_rtol " << o.confirm_rtol << "); " << v->reason;
    v->reason = s.str();
    v->code = Verdict::Unresolved; // bound stays |mu| - 1: growth this large is neither shown nor excluded
    v->efold = std::numeric_limits<PetscReal>::infinity();
  } else {
    std::ostringstream s;
    s << v->reason << "; confirmed: the eigenvector grew at " << rate << " per period over " << o.confirm_periods << " periods (ln|mu| = " << expect << ")";
    v->reason = s.str();
  }
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
