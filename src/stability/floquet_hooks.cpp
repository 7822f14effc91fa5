#include "stability/floquet_hooks.hpp"
#include "stability/floquet_localized.hpp"
#include <algorithm>
#include <cmath>
#include <string>
#include <cstdio>
#include <cstring>

namespace nltopo {

void FloquetColumns::AddVerdict(const OrbitVerdict &v)
{
  verdict.push_back((PetscInt)v.code);
  verdict_bound.push_back(v.bound);
  verdict_efold.push_back(v.efold);
  verdict_reason.push_back(v.reason);
}

PetscErrorCode FloquetHook::Point(Vec z0, PetscReal T, PetscReal beta, Vec)
{
  FloquetResult r;
  OrbitVerdict v;
  PetscFunctionBeginUser;
  if (!S_) {
    PetscCall(flow_.CreateSensitivityMatrix(S_.out()));
    PetscCall(VecDuplicate(z0, zT_.out()));
    PetscCall(VecDuplicate(z0, vr_.out()));
    PetscCall(VecDuplicate(z0, vi_.out()));
  }
  const PetscReal fb = flow_.FloquetBeta(beta);
  PetscCall(flow_.IntegrateWithMonodromy(z0, T, fb, zT_, S_)); // at the converged orbit
  PetscCall(FloquetAnalysis(flow_.Lat(), S_, opt_, &r, nullptr, nullptr, -1, vr_, vi_));
  PetscCall(DenseVerdict(flow_, z0, T, fb, opt_, r.stable, r.max_modulus, {r.worst_re, r.worst_im}, r.instability, vr_, vi_, &v));
  c.AddVerdict(v);
  c.re.insert(c.re.end(), r.re.begin(), r.re.end());
  c.im.insert(c.im.end(), r.im.begin(), r.im.end());
  c.krein.insert(c.krein.end(), r.krein.begin(), r.krein.end());
  c.edge.insert(c.edge.end(), r.edge.begin(), r.edge.end());
  c.max_modulus.push_back(r.max_modulus);
  c.det_error.push_back(r.det_error);
  c.stable.push_back(r.stable);
  c.instability.push_back(r.instability);
  c.leading_participation.push_back(r.leading_participation), c.leading_edge.push_back(r.leading_edge);
  PetscFunctionReturn(0);
}

// The verdict of a -floquet_mf route from its leading multipliers and the leading eigenvector (vr_, vi_).
PetscErrorCode FloquetMfHook::RouteVerdict(Vec z0, PetscReal T, PetscReal beta, const LeadingMultipliers &r, OrbitVerdict *v)
{
  char b[240];
  PetscFunctionBeginUser;
  if (Localized()) { // its own verdict; an unstable one confirmed on the window's norm (the mode radiates into the band)
    *v = loc_verdict;
    PetscCall(ConfirmLocalizedGrowth(flow_, z0, T, beta, loc_vr, loc_vi, mopt_.loc, opt_, v));
    PetscFunctionReturn(0);
  }
  if (Dense()) {
    std::complex<PetscReal> mu(r.re.empty() ? 1 : r.re[0], r.im.empty() ? 0 : r.im[0]);
    PetscCall(DenseVerdict(flow_, z0, T, beta, opt_, r.verdict == kStable, r.max_modulus, mu, r.instability, vr_, vi_, v));
    PetscFunctionReturn(0);
  }
  if (r.verdict == kUnstable) { // the leading accepted multiplier beyond 1 + max(tol, its resolution)
    PetscInt best = 0;
    for (PetscInt k = 1; k < r.converged; k++)
      if (std::hypot(r.re[k], r.im[k]) > std::hypot(r.re[best], r.im[best])) best = k;
    PetscReal kappa, edge;
    PetscCall(EigenvectorShares(flow_.Lat(), vr_, vi_, opt_.edge_sites, &kappa, &edge));
    const PetscInt cls = Localisation(opt_, edge);
    std::snprintf(b, sizeof b, "matrix-free (%s): |mu| = %.7f beyond 1 + %.1e, eigenvector edge class %s",
                  mopt_.which == FloquetMfWhich::Critical ? "critical" : "largest", (double)std::hypot(r.re[best], r.im[best]), (double)opt_.tol,
                  cls == 3 ? "E-E" : cls == 2 ? "B-E" : "B-B");
    *v = UnstableVerdict({r.re[best], r.im[best]}, cls, b);
    PetscCall(ConfirmGrowth(flow_, z0, T, beta, vr_, vi_, opt_, v));
  } else if (r.converged < mopt_.nev) {
    std::snprintf(b, sizeof b, "matrix-free: %" PetscInt_FMT " of %" PetscInt_FMT " leading multipliers converged; nothing is bounded", r.converged, mopt_.nev);
    *v = UnresolvedVerdict(std::numeric_limits<PetscReal>::infinity(), b);
  } else {
    std::snprintf(b, sizeof b, "matrix-free (%s): no multiplier found beyond 1 + %.1e, but a Krein quadruplet inside the spectrum cannot be excluded",
                  mopt_.which == FloquetMfWhich::Critical ? "critical" : "largest", (double)opt_.tol);
    *v = UnresolvedVerdict(std::numeric_limits<PetscReal>::infinity(), b);
  }
  PetscFunctionReturn(0);
}

PetscErrorCode FloquetMfHook::Point(Vec z0, PetscReal T, PetscReal beta, Vec dz0)
{
  LeadingMultipliers r;
  OrbitVerdict v;
  const MPI_Comm comm = flow_.Lat().Comm();
  const PetscReal fb = flow_.FloquetBeta(beta);
  PetscFunctionBeginUser;
  if (!vr_) {
    PetscCall(VecDuplicate(z0, vr_.out()));
    PetscCall(VecDuplicate(z0, vi_.out()));
  }
  if (Dense()) {
    if (!S_) {
      PetscCall(flow_.CreateSensitivityMatrix(S_.out()));
      PetscCall(VecDuplicate(z0, zT_.out()));
    }
    PetscCall(flow_.IntegrateWithMonodromy(z0, T, fb, zT_, S_));
    PetscCall(FloquetLeadingDense(flow_.Lat(), S_, mopt_.nev, opt_, &r, vr_, vi_));
  } else if (Localized()) { // the localized route: its verdict and (unstable) eigenvector in loc_verdict, loc_vr, loc_vi
    if (!loc_vr) {
      PetscCall(VecDuplicate(z0, loc_vr.out()));
      PetscCall(VecDuplicate(z0, loc_vi.out()));
    }
    PetscCall(FloquetLocalized(flow_, z0, T, fb, opt_, mopt_.loc, mopt_.nev, &r, &loc_verdict, loc_vr, loc_vi));
  } else {
    PetscCall(FloquetLeading(flow_, z0, T, fb, mopt_, &r, &warm_, dz0, vr_, vi_));
    r.verdict = MatrixFreeVerdict(r, opt_.tol);
  }
  PetscCall(RouteVerdict(z0, T, fb, r, &v));
  c.AddVerdict(v);
  c.re.insert(c.re.end(), r.re.begin(), r.re.end());
  c.im.insert(c.im.end(), r.im.begin(), r.im.end());
  c.max_modulus.push_back(r.max_modulus);
  c.stable.push_back(r.verdict);
  r.krein.resize(mopt_.nev, 0); // matrix-free: not computed
  c.krein.insert(c.krein.end(), r.krein.begin(), r.krein.end());
  c.instability.push_back(r.instability);
  c.leading_participation.push_back(r.leading_participation), c.leading_edge.push_back(r.leading_edge);
  c.products += r.products;
  c.route = Route();
  if (r.converged < mopt_.nev && !Dense() && !Localized()) {
    c.unconverged++;
    PetscCall(PetscPrintf(comm,
                          "  matrix-free Floquet: %" PetscInt_FMT " of %" PetscInt_FMT
                          " multipliers converged at omega %.6f%s (written as NaN; raise -floquet_mf_eps_max_it or -floquet_mf_eps_ncv)\n",
                          r.converged, mopt_.nev, (double)(2 * PETSC_PI / T), r.spurious ? ", spurious Ritz values rejected by their true residual" : ""));
  }
  PetscFunctionReturn(0);
}

PetscErrorCode FloquetMfHook::Announce() const
{
  const MPI_Comm comm = flow_.Lat().Comm();
  const PetscInt n2 = 2 * flow_.Lat().N();
  PetscFunctionBeginUser;
  if (Dense())
    PetscCall(PetscPrintf(comm,
                          "  Floquet: the dense monodromy (2N = %" PetscInt_FMT " <= -floquet_mf_dense_max %" PetscInt_FMT
                          "): every multiplier, a stability verdict per orbit, cost ~(2N)^3\n",
                          n2, mopt_.dense_max));
  else if (Localized())
    PetscCall(PetscPrintf(comm,
                          "  Floquet: localized (2N = %" PetscInt_FMT " > -floquet_mf_dense_max %" PetscInt_FMT
                          "): the tangent equations damped beyond %" PetscInt_FMT
                          " cells of the interface, every multiplier of the window and its absorbing layer\n",
                          n2, mopt_.dense_max, mopt_.loc.window));
  else
    PetscCall(PetscPrintf(
        comm, "  Floquet: matrix-free (2N = %" PetscInt_FMT " > -floquet_mf_dense_max %" PetscInt_FMT "): an orbit is unstable or not decided, never stable\n",
        n2, mopt_.dense_max));
  PetscFunctionReturn(0);
}

// The verdict lines of PrintFloquetSummary.
static PetscErrorCode PrintVerdicts(MPI_Comm comm, const std::string &label, const FloquetColumns &f, const std::vector<PetscReal> *energy)
{
  const size_t n = f.verdict.size();
  PetscInt count[5] = {0, 0, 0, 0, 0}, listed = 0, unknown = 0;
  PetscFunctionBeginUser;
  if (!n) PetscFunctionReturn(0);
  for (PetscInt x : f.verdict)
    if (x >= 0 && x <= 4) count[x]++;
    else unknown++;
  PetscCall(PetscPrintf(comm, "  [%s] verdicts: %" PetscInt_FMT " stable, %" PetscInt_FMT " stable-to, %" PetscInt_FMT " unstable-localized, %" PetscInt_FMT
                              " unstable-extended, %" PetscInt_FMT " unresolved",
                        label.c_str(), count[0], count[3], count[1], count[2], count[4]));
  if (unknown) PetscCall(PetscPrintf(comm, ", %" PetscInt_FMT " not computed (resumed from a file without verdicts)", unknown));
  PetscCall(PetscPrintf(comm, "\n"));
  for (size_t k = 0; k < n; k++) {
    const Verdict c = (Verdict)f.verdict[k];
    if (f.verdict[k] < 0 || c == Verdict::Stable || c == Verdict::StableTo) continue;
    if (++listed > 12) {
      PetscCall(PetscPrintf(comm, "    ... (every orbit's verdict_reason is in the output)\n"));
      break;
    }
    char e[40] = "";
    if (energy && k < energy->size()) std::snprintf(e, sizeof e, " E = %.4g", (double)(*energy)[k]);
    PetscCall(PetscPrintf(comm, "    point %zu%s: %s, bound %.2e%s%s: %s\n", k, e, VerdictName(c), (double)f.verdict_bound[k],
                          std::isfinite(f.verdict_efold[k]) ? ", e-folding (periods) " : "",
                          std::isfinite(f.verdict_efold[k]) ? std::to_string((long long)std::llround(f.verdict_efold[k])).c_str() : "",
                          f.verdict_reason[k].c_str()));
  }
  PetscFunctionReturn(0);
}

const FloquetRouteTraits &FloquetRouteTraitsOf(FloquetRoute r)
{
  static const FloquetRouteTraits table[] = {
      {"full", "", true, false},
      {"dense", " (-floquet_mf, dense: 2N <= -floquet_mf_dense_max)", false, false},
      {"localized", " (localized: the damped window's multipliers; stable means stable-to(delta), below)", false, false},
      {"matrix-free", " (matrix-free, leading pairs)", false, true},
  };
  return table[(int)r];
}

PetscErrorCode PrintFloquetSummary(MPI_Comm comm, const std::string &label, const FloquetColumns &f, PetscReal tol, FloquetRoute route,
                                   const std::vector<PetscReal> *energy)
{
  const FloquetRouteTraits &tr = FloquetRouteTraitsOf(route);
  PetscInt ns = 0, nu = 0;
  PetscFunctionBeginUser;
  for (PetscInt s : f.stable) ns += s == kStable, nu += s == kUndecided;
  PetscCall(PetscPrintf(comm, "  [%s] Floquet%s: %" PetscInt_FMT " of %zu orbits stable (|mu| <= 1 + %g)", label.c_str(), tr.summary, ns, f.stable.size(),
                        (double)tol));
  if (tr.undecided)
    PetscCall(PetscPrintf(comm, ", %" PetscInt_FMT " not decided (a complex quadruplet cannot be excluded matrix-free), %" PetscInt_FMT " monodromy products", nu,
                          f.products));
  if (tr.det_error) {
    PetscReal dmax = 0;
    for (PetscReal x : f.det_error) dmax = std::max(dmax, x); // NaN (resumed from an older file) ignored
    PetscCall(PetscPrintf(comm, ", max |det M - 1| = %.1e", (double)dmax));
  }
  PetscCall(PetscPrintf(comm, "\n"));
  PetscCall(PrintVerdicts(comm, label, f, energy));
  PetscFunctionReturn(0);
}

} // namespace nltopo
