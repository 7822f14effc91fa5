// The localized Floquet route (issue 35 item 2) on the orbits of the insulated
// branch, against the dense route on the same orbits (benchmarks/README.md
// "Issue 35: the localized route").
//
// The driver continues the branch exactly as `-study continuation` does (same
// options: e.g. -options_file options/fep_long.opts -lattice_cells 250
// -cont_energy_max 10) and keeps every orbit. Then, for the selected points
// (-bench_points, default all):
//  loc    FloquetLocalized for each -bench_configs W:R:c (window cells, ramp
//         cells, damping; default the -floquet_loc_* options): the leading
//         multipliers, their edge and window shares, the verdict, the time
//  check  with -bench_check: LocalizedIndependence (W and c halved and doubled)
//  confirm with -bench_confirm: for an unstable verdict of the first config,
//         ConfirmLocalizedGrowth (the window norm) and ConfirmGrowth (the whole
//         vector's norm) over -floquet_confirm_periods on the undamped lattice
//  simulate with -bench_simulate K: for an unstable verdict of the first
//         config, the orbit and the orbit plus 1e-8 of it along the
//         eigenvector run side by side by direct simulation (-sim_ts_*) for K
//         periods; the growth of their distance on the window's sites, fitted
//         (stability/growth.hpp), against ln|mu|
//  dense  with -bench_dense (point indices, -1 all): the dense route's leading
//         pairs (FloquetLeadingDense, -floquet_mf_nev of them)
// One line per point and method (bench: ...), to be read by a script.
#include "bench_clock.hpp"
#include "core/log.hpp"
#include "stability/floquet_localized.hpp"
#include "stability/growth.hpp"
#include "studies/nnm_setup.hpp"
#include "timeint/ts_rkn.hpp"
#include "timeint/ts_symsplit.hpp"
#include <slepcsys.h>
#include <cmath>
#include <cstdio>

using namespace nltopo;

namespace {

struct Orbit {
  OwnedVec z0;
  PetscReal T = 0;
};

class KeepOrbits : public PointHook {
public:
  PetscErrorCode Point(Vec z0, PetscReal T, PetscReal, Vec) override
  {
    Orbit o;
    PetscFunctionBeginUser;
    PetscCall(VecDuplicate(z0, o.z0.out()));
    PetscCall(VecCopy(z0, o.z0));
    o.T = T;
    orbits.push_back(std::move(o));
    PetscFunctionReturn(0);
  }
  std::vector<Orbit> orbits;
};

} // namespace

int main(int argc, char **argv)
{
  PetscCall(SlepcInitialize(&argc, &argv, NULL, "floquet_localized_bench: the localized Floquet route against the dense one\n"));
  {
    MPI_Comm comm = PETSC_COMM_WORLD;
    PetscCall(LogRegister());
    PetscCall(TSSymSplitRegister());
    PetscCall(TSRknRegister());
    NnmSetup nnm;
    PetscCall(nnm.ReadOptions(comm));
    FloquetOptions fo;
    PetscCall(FloquetOptionsFromOptions(comm, &fo));
    FloquetMfOptions mo;
    PetscCall(FloquetMfOptionsFromOptions(comm, &mo));
    PetscInt points[1000], npoints = 1000, dense[1000], ndense = 1000;
    PetscBool has_points, has_dense, check = PETSC_FALSE, confirm = PETSC_FALSE;
    FloquetOptions vo = fo; // -floquet_confirm_periods, -floquet_confirm_rtol
    PetscCall(PetscOptionsGetIntArray(NULL, NULL, "-bench_points", points, &npoints, &has_points));
    PetscCall(PetscOptionsGetIntArray(NULL, NULL, "-bench_dense", dense, &ndense, &has_dense));
    PetscCall(PetscOptionsGetBool(NULL, NULL, "-bench_check", &check, NULL));
    PetscCall(PetscOptionsGetBool(NULL, NULL, "-bench_confirm", &confirm, NULL));
    PetscInt simulate = 0; // -bench_simulate K: the growth by direct simulation over K periods (unstable verdicts)
    PetscCall(PetscOptionsGetInt(NULL, NULL, "-bench_simulate", &simulate, NULL));
    SimulationOptions sim;
    PetscCall(SimulationOptionsFromOptions(comm, &sim));
    char cfg[100][64], *cfgp[100];
    PetscInt ncfg = 100;
    for (PetscInt i = 0; i < 100; i++) cfgp[i] = cfg[i];
    PetscCall(PetscOptionsGetStringArray(NULL, NULL, "-bench_configs", cfgp, &ncfg, NULL));
    std::vector<LocalizedOptions> configs;
    for (PetscInt i = 0; i < ncfg; i++) {
      LocalizedOptions lo = mo.loc;
      int w, r;
      double c;
      PetscCheck(std::sscanf(cfgp[i], "%d:%d:%lf", &w, &r, &c) == 3, comm, PETSC_ERR_USER, "-bench_configs: W:R:c, got %s", cfgp[i]);
      lo.window = w, lo.ramp = r, lo.damping = c;
      configs.push_back(lo);
      PetscCall(PetscFree(cfgp[i]));
    }
    if (configs.empty()) configs.push_back(mo.loc);

    PetscCall(nnm.Build(comm, "-study continuation"));
    PeriodicFlow &flow = nnm.flow;
    const PetscInt N = nnm.lat.N();
    OwnedVec u, vr, vi;
    PetscCall(VecDuplicate(nnm.modes.Insulated(), u.out()));
    PetscCall(VecCopy(nnm.modes.Insulated(), u));
    KeepOrbits keep;
    Branch b;
    double t0 = Now();
    PetscCall(ContinueBranch(nnm.shoot, u, 2 * PETSC_PI / nnm.modes.Named().insulated_omega, nnm.co, "insulated", &b, &keep));
    PetscCall(PetscPrintf(comm, "bench: branch N %d points %d seconds %.2f\n", (int)N, (int)b.energy.size(), Now() - t0));
    const PetscInt np = (PetscInt)keep.orbits.size();
    if (!has_points) {
      npoints = np;
      for (PetscInt p = 0; p < np; p++) points[p] = p;
    }
    PetscCall(VecDuplicate(keep.orbits[0].z0, vr.out()));
    PetscCall(VecDuplicate(keep.orbits[0].z0, vi.out()));
    for (PetscInt i = 0; i < npoints; i++) {
      const PetscInt p = points[i];
      if (p < 0 || p >= np) continue;
      const Orbit &o = keep.orbits[p];
      for (const LocalizedOptions &lo : configs) {
        LeadingMultipliers r;
        OrbitVerdict v;
        t0 = Now();
        PetscCall(FloquetLocalized(flow, o.z0, o.T, 0.0, fo, lo, mo.nev, &r, &v, vr, vi));
        const double dt = Now() - t0;
        PetscCall(PetscPrintf(comm, "bench: loc point %d E %.6g W %d R %d c %g verdict %s bound %.6e seconds %.3f cols %d", (int)p, (double)b.energy[p],
                              (int)lo.window, (int)lo.ramp, (double)lo.damping, VerdictName(v.code), (double)v.bound, dt, (int)r.products));
        for (size_t k = 0; k < r.re.size(); k++)
          PetscCall(PetscPrintf(comm, " mu %.10f %.10f %.10f", (double)r.re[k], (double)r.im[k], (double)std::hypot(r.re[k], r.im[k])));
        PetscCall(PetscPrintf(comm, " | %s\n", v.reason.c_str()));
        if (confirm && &lo == &configs[0] && (v.code == Verdict::UnstableLocalized || v.code == Verdict::UnstableExtended)) {
          OrbitVerdict cw = v, cf = v;
          t0 = Now();
          PetscCall(ConfirmLocalizedGrowth(flow, o.z0, o.T, 0.0, vr, vi, lo, vo, &cw));
          PetscCall(ConfirmGrowth(flow, o.z0, o.T, 0.0, vr, vi, vo, &cf));
          PetscCall(PetscPrintf(comm, "bench: confirm point %d E %.6g ln|mu| %.6e window_rate %.6e %s whole_rate %.6e %s periods %d seconds %.2f\n", (int)p,
                                (double)b.energy[p], (double)std::log(std::hypot(v.mu_re, v.mu_im)), (double)cw.confirmed_rate, VerdictName(cw.code),
                                (double)cf.confirmed_rate, VerdictName(cf.code), (int)vo.confirm_periods, Now() - t0));
        }
        if (simulate > 0 && &lo == &configs[0] && (v.code == Verdict::UnstableLocalized || v.code == Verdict::UnstableExtended)) {
          // direct nonlinear simulation (-sim_ts_*): the orbit and the orbit plus 1e-8 of it along Re v, side by side, the
          // distance measured on the window's sites (stability/growth.hpp)
          const LocalizedRegion reg = MakeLocalizedRegion(N, nnm.lat.Params().InterfaceSite(), lo);
          PetscInt win[2] = {-1, -1};
          for (PetscInt s = 0; s < reg.Sites(); s++)
            if (reg.InWindow(s)) win[0] = win[0] < 0 ? reg.lo + s : win[0], win[1] = reg.lo + s;
          GrowthMeasurement g;
          t0 = Now();
          PetscCall(MeasureGrowth(nnm.fx, sim, o.z0, o.T, vr, simulate, 1e-8, &g, win));
          PetscCall(PetscPrintf(comm, "bench: simulate point %d E %.6g ln|mu| %.6e window %d..%d rate %.6e ratio %.4f periods_fitted %d of %d seconds %.2f\n",
                                (int)p, (double)b.energy[p], (double)std::log(std::hypot(v.mu_re, v.mu_im)), (int)win[0], (int)win[1], (double)g.rate,
                                (double)(g.rate / std::log(std::hypot(v.mu_re, v.mu_im))), (int)g.fitted, (int)simulate, Now() - t0));
        }
      }
      if (check) {
        LocalizedIndependenceResult ind;
        t0 = Now();
        PetscCall(LocalizedIndependence(flow, o.z0, o.T, 0.0, fo, configs[0], mo.nev, &ind));
        PetscCall(PetscPrintf(comm, "bench: check point %d E %.6g mu0 %.10f %.10f |mu0| %.10f", (int)p, (double)b.energy[p], (double)ind.mu0.real(),
                              (double)ind.mu0.imag(), (double)std::abs(ind.mu0)));
        const char *names[4] = {"W/2", "2W", "c/2", "2c"};
        for (int k = 0; k < 4; k++) PetscCall(PetscPrintf(comm, " %s %.10f dmu %.3e", names[k], (double)std::abs(ind.mu[k]), (double)ind.change[k]));
        PetscCall(PetscPrintf(comm, " max %.3e max_modulus %.3e seconds %.2f\n", (double)ind.max_change, (double)ind.max_modulus_change, Now() - t0));
      }
      bool want = false;
      for (PetscInt k = 0; has_dense && k < ndense; k++) want = want || dense[k] == p || dense[k] < 0;
      if (want) {
        OwnedMat S;
        OwnedVec zT;
        LeadingMultipliers r;
        t0 = Now();
        PetscCall(flow.CreateSensitivityMatrix(S.out()));
        PetscCall(VecDuplicate(o.z0, zT.out()));
        PetscCall(flow.IntegrateWithMonodromy(o.z0, o.T, 0.0, zT, S));
        PetscCall(FloquetLeadingDense(nnm.lat, S, mo.nev, fo, &r));
        PetscCall(PetscPrintf(comm, "bench: dense point %d E %.6g max %.10f class %d seconds %.2f", (int)p, (double)b.energy[p], (double)r.max_modulus,
                              (int)r.instability, Now() - t0));
        for (size_t k = 0; k < r.re.size(); k++)
          PetscCall(PetscPrintf(comm, " mu %.10f %.10f %.10f", (double)r.re[k], (double)r.im[k], (double)std::hypot(r.re[k], r.im[k])));
        PetscCall(PetscPrintf(comm, "\n"));
      }
    }
  }
  PetscCall(SlepcFinalize());
  return 0;
}
