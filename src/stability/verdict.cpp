#include "stability/verdict.hpp"
#include "core/option_table.hpp"
#include <cmath>
#include <sstream>

namespace nltopo {

static const auto &kVerdictTable = DeclareOptionTable<VerdictOptions>(
    "floquet_confirm_", "Confirmation of unstable Floquet verdicts (integrate the eigenvector k periods)", [](OptionTable<VerdictOptions> &t) {
      t.Int("periods", &VerdictOptions::confirm_periods, Closed(1, 100000),
            "Periods k the unstable eigenvector is integrated to confirm |M^k v| = |mu|^k |v| (2k tangent integrations for a complex pair)")
          .Real("rtol", &VerdictOptions::confirm_rtol, Open(0, 1), "The measured growth rate per period must match ln|mu| to this relative tolerance");
    });

PetscErrorCode VerdictOptionsFromOptions(MPI_Comm comm, VerdictOptions *o)
{
  PetscFunctionBeginUser;
  PetscCall(kVerdictTable.Read(comm, o));
  PetscFunctionReturn(0);
}

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

PetscErrorCode ConfirmGrowth(PeriodicFlow &flow, Vec z0, PetscReal T, PetscReal beta, Vec vr, Vec vi, const VerdictOptions &o, OrbitVerdict *v)
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
    v->efold = PETSC_INFINITY;
  }
  PetscFunctionReturn(0);
}

} // namespace nltopo
