// The verdict vocabulary (stability/verdict.hpp) on known truth: the coupled
// dimers' stable lower family and their upper family past the pitchfork (a real
// multiplier whose size first-order averaging predicts, test_floquet.cpp), through
// the hooks the continuation study uses; and the k-period confirmation, which must
// refuse a vector that is not the unstable eigenvector.
#include "dimers.hpp"
#include "helpers.hpp"
#include "stability/floquet_hooks.hpp"
#include "stability/verdict.hpp"
#include <cmath>

using namespace nltopo;
using namespace nltopo::test;

namespace {
// The real hook, and the last orbit (to confirm by hand).
struct VerdictCapture : public PointHook {
  FloquetHook hook;
  OwnedVec z;
  PetscReal T = 0, beta = 0;
  VerdictCapture(PeriodicFlow &f, const FloquetOptions &o) : hook(f, o) {}
  PetscErrorCode Point(Vec z0, PetscReal TT, PetscReal b, Vec dz0) override
  {
    PetscFunctionBeginUser;
    if (!z) PetscCall(VecDuplicate(z0, z.out()));
    PetscCall(VecCopy(z0, z));
    T = TT, beta = b;
    PetscCall(hook.Point(z0, TT, b, dz0));
    PetscFunctionReturn(0);
  }
};
} // namespace

TEST_CASE("verdicts: stable on the dimers' stable family, unstable-extended and confirmed past their pitchfork", "[floquet][verdict][once]")
{
  // [once]: at 2 ranks the same continuation of the upper family through the real hook (Floquet,
  // verdict, class and confirmation of every orbit) runs in "ConfirmGrowth accepts ..." below, which
  // checks its last orbit's verdict columns; here the same code at 2 ranks only repeats the physics.
  CoupledDimers d;
  PCHK(d.Setup());
  const auto &w = d.modes.Omega();
  const PetscReal lam_hi = w[3] * w[3], kappa = (lam_hi - w[2] * w[2]) / 2;
  FloquetOptions o;
  o.confirm_periods = 8;
  for (PetscInt j : {2, 3}) {
    VerdictCapture cap(d.flow, o);
    PCHK(d.Continue(j, std::sqrt(lam_hi + 3 * kappa), &cap));
    const FloquetColumns &c = cap.hook.c;
    REQUIRE(c.verdict.size() == c.stable.size());
    REQUIRE(c.verdict.size() > 10);
    PetscInt unstable = 0;
    for (size_t i = 0; i < c.verdict.size(); i++) {
      INFO("mode " << j << ", point " << i << ": " << c.verdict_reason[i]);
      if (c.stable[i]) { // the dense route's stable: bound = -floquet_tol, no growth
        REQUIRE(c.verdict[i] == (PetscInt)Verdict::Stable);
        REQUIRE(c.verdict_bound[i] == o.tol);
        REQUIRE(std::isinf(c.verdict_efold[i]));
        continue;
      }
      // no interface in this lattice: the eigenvector is extended (B-B), and the growth is confirmed
      REQUIRE(c.verdict[i] == (PetscInt)Verdict::UnstableExtended);
      REQUIRE(c.instability[i] == 1);
      REQUIRE(std::abs(c.verdict_bound[i] - (c.max_modulus[i] - 1)) <= 1e-12);
      REQUIRE(std::abs(c.verdict_efold[i] * std::log(c.max_modulus[i]) - 1) <= 1e-12);
      REQUIRE(c.verdict_reason[i].find("confirmed") != std::string::npos);
      unstable++;
    }
    if (j == 2) REQUIRE(unstable == 0);
    else REQUIRE(unstable >= 3);
  }
}

TEST_CASE("ConfirmGrowth accepts the unstable eigenvector and refuses another vector or a wrong modulus", "[floquet][verdict]")
{
  CoupledDimers d;
  PCHK(d.Setup());
  const auto &w = d.modes.Omega();
  const PetscReal lam_hi = w[3] * w[3], kappa = (lam_hi - w[2] * w[2]) / 2;
  FloquetOptions o;
  o.confirm_periods = 10;
  VerdictCapture cap(d.flow, o);
  PCHK(d.Continue(3, std::sqrt(lam_hi + 3 * kappa), &cap));
  REQUIRE(!cap.hook.c.stable.back());
  // the hook's verdict of that orbit (the 2-rank check of "verdicts: ..." above): unstable-extended, B-B, confirmed
  REQUIRE(cap.hook.c.verdict.back() == (PetscInt)Verdict::UnstableExtended);
  REQUIRE(cap.hook.c.instability.back() == 1);
  REQUIRE(cap.hook.c.verdict_reason.back().find("confirmed") != std::string::npos);
  // the last orbit's monodromy and its most unstable eigenvector
  OwnedMat S;
  OwnedVec zT, vr, vi, other;
  PCHK(d.flow.CreateSensitivityMatrix(S.out()));
  PCHK(VecDuplicate(cap.z, zT.out()));
  PCHK(VecDuplicate(cap.z, vr.out()));
  PCHK(VecDuplicate(cap.z, vi.out()));
  PCHK(VecDuplicate(cap.z, other.out()));
  PCHK(d.flow.IntegrateWithMonodromy(cap.z, cap.T, cap.beta, zT, S));
  FloquetResult r;
  PCHK(FloquetAnalysis(d.flow.Lat(), S, o, &r, nullptr, nullptr, -1, vr, vi));
  REQUIRE(!r.stable);
  const std::complex<PetscReal> mu(r.worst_re, r.worst_im);
  OrbitVerdict v = UnstableVerdict(mu, 1, "test");
  PCHK(ConfirmGrowth(d.flow, cap.z, cap.T, cap.beta, vr, vi, o, &v));
  INFO(v.reason);
  REQUIRE(v.code == Verdict::UnstableExtended);
  REQUIRE(std::abs(v.confirmed_rate / std::log(std::abs(mu)) - 1) < 1e-6); // an exact eigenvector grows exactly as |mu|^k
  // A vector along the orbit's own tangent f(z0) (the trivial multiplier 1) does not grow: refused.
  PCHK(d.flow.Field(cap.z, other));
  OrbitVerdict u = UnstableVerdict(mu, 1, "test");
  PCHK(ConfirmGrowth(d.flow, cap.z, cap.T, cap.beta, other, nullptr, o, &u));
  REQUIRE(u.code == Verdict::Unresolved);
  REQUIRE(u.reason.find("not confirmed") != std::string::npos);
  REQUIRE(u.bound == std::abs(mu) - 1);
  // The right vector with a claimed modulus twice as far from the circle: refused too.
  OrbitVerdict x = UnstableVerdict(1.0 + 2.0 * (mu - 1.0), 1, "test");
  PCHK(ConfirmGrowth(d.flow, cap.z, cap.T, cap.beta, vr, vi, o, &x));
  REQUIRE(x.code == Verdict::Unresolved);
}
