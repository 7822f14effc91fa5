#include "stability/floquet_hooks.hpp"
#include "stability/floquet_localized.hpp"
#include <algorithm>
#include <cstring>

namespace nltopo {

PetscErrorCode FloquetHook::Point(Vec z0, PetscReal T, PetscReal beta, Vec)
{
  FloquetResult r;
  PetscFunctionBeginUser;
  if (!S_) {
    PetscCall(flow_.CreateSensitivityMatrix(S_.out()));
    PetscCall(VecDuplicate(z0, zT_.out()));
  }
  PetscCall(flow_.IntegrateWithMonodromy(z0, T, flow_.FloquetBeta(beta), zT_, S_)); // at the converged orbit
  PetscCall(FloquetAnalysis(flow_.Lat(), S_, opt_, &r));
  c.re.insert(c.re.end(), r.re.begin(), r.re.end());
  c.im.insert(c.im.end(), r.im.begin(), r.im.end());
  c.krein.insert(c.krein.end(), r.krein.begin(), r.krein.end());
  c.edge.insert(c.edge.end(), r.edge.begin(), r.edge.end());
  c.max_modulus.push_back(r.max_modulus);
  c.det_error.push_back(r.det_error);
  c.stable.push_back(r.stable);
  c.instability.push_back(r.instability);
  PetscFunctionReturn(0);
}

PetscErrorCode FloquetMfHook::Point(Vec z0, PetscReal T, PetscReal beta, Vec dz0)
{
  LeadingMultipliers r;
  const MPI_Comm comm = flow_.Lat().Comm();
  PetscFunctionBeginUser;
  if (Dense()) {
    if (!S_) {
      PetscCall(flow_.CreateSensitivityMatrix(S_.out()));
      PetscCall(VecDuplicate(z0, zT_.out()));
    }
    PetscCall(flow_.IntegrateWithMonodromy(z0, T, flow_.FloquetBeta(beta), zT_, S_));
    PetscCall(FloquetLeadingDense(flow_.Lat(), S_, mopt_.nev, opt_, &r));
  } else if (Localized()) { // the localized route: its verdict and (unstable) eigenvector in loc_verdict, loc_vr, loc_vi
    if (!loc_vr) {
      PetscCall(VecDuplicate(z0, loc_vr.out()));
      PetscCall(VecDuplicate(z0, loc_vi.out()));
    }
    PetscCall(FloquetLocalized(flow_, z0, T, flow_.FloquetBeta(beta), opt_, mopt_.loc, mopt_.nev, &r, &loc_verdict, loc_vr, loc_vi));
    PetscCall(PetscPrintf(comm, "  Floquet (localized) at omega %.6f: %s, bound %.2e | %s\n", (double)(2 * PETSC_PI / T), VerdictName(loc_verdict.code),
                          (double)loc_verdict.bound, loc_verdict.reason.c_str()));
  } else {
    PetscCall(FloquetLeading(flow_, z0, T, flow_.FloquetBeta(beta), mopt_, &r, &warm_, dz0));
    r.verdict = MatrixFreeVerdict(r, opt_.tol);
  }
  c.re.insert(c.re.end(), r.re.begin(), r.re.end());
  c.im.insert(c.im.end(), r.im.begin(), r.im.end());
  c.max_modulus.push_back(r.max_modulus);
  c.stable.push_back(r.verdict);
  r.krein.resize(mopt_.nev, 0); // matrix-free: not computed
  c.krein.insert(c.krein.end(), r.krein.begin(), r.krein.end());
  c.instability.push_back(r.instability);
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

PetscErrorCode PrintFloquetSummary(MPI_Comm comm, const std::string &label, const FloquetColumns &f, PetscReal tol, const char *mf_route)
{
  const bool mf = mf_route != nullptr, dense = !mf || !std::strcmp(mf_route, "dense");
  PetscInt ns = 0, nu = 0;
  PetscFunctionBeginUser;
  for (PetscInt s : f.stable) ns += s == kStable, nu += s == kUndecided;
  PetscCall(PetscPrintf(comm, "  [%s] Floquet%s: %" PetscInt_FMT " of %zu orbits stable (|mu| <= 1 + %g)", label.c_str(),
                        !mf     ? ""
                        : dense ? " (-floquet_mf, dense: 2N <= -floquet_mf_dense_max)"
                                : " (matrix-free, leading pairs)",
                        ns, f.stable.size(), (double)tol));
  if (mf) {
    if (!dense)
      PetscCall(PetscPrintf(comm, ", %" PetscInt_FMT " not decided (a complex quadruplet cannot be excluded matrix-free), %" PetscInt_FMT " monodromy products",
                            nu, f.products));
  } else {
    PetscReal dmax = 0;
    for (PetscReal x : f.det_error) dmax = std::max(dmax, x); // NaN (resumed from an older file) ignored
    PetscCall(PetscPrintf(comm, ", max |det M - 1| = %.1e", (double)dmax));
  }
  PetscCall(PetscPrintf(comm, "\n"));
  PetscFunctionReturn(0);
}

} // namespace nltopo
