// Blocked tangent products (issue 35, item 5): s tangent vectors integrated in
// one pass over the orbit (PeriodicFlow::IntegrateWithTangents) against s
// single tangent integrations (IntegrateWithTangent), on the symplectic route
// (-nnm_ts_type symsplit bm4, -nnm_steps_per_period steps per period).
//
// The state: the linear insulated mode's profile (even sites, factor -k2/k1
// per cell from the interface, model.md), amplitude -bench_amplitude at the
// interface, zero velocity; the period 2 pi / sqrt(k_hat). It need not be a
// periodic orbit: a product costs the same on any state. The s start vectors
// are pseudo-random. Each repeat times one block pass and the s single
// products; the medians over -bench_repeats are printed with the largest
// difference max_j |w_block[j] - w_single[j]|_inf / |w_single[j]|_inf.
//
//   ./build/benchmarks/block_tangents -lattice_cells 2500 -bench_s 8 -bench_repeats 5
// Any rank count (the products are distributed like nltopo's).
#include "bench_clock.hpp"
#include "core/handle.hpp"
#include "core/log.hpp"
#include "effects/effect.hpp"
#include "orbits/flow.hpp"
#include "timeint/ts_symsplit.hpp"
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

using namespace nltopo;

namespace {

// u at the even sites of the insulated mode's decay, amplitude a at site m + 1 (0-based m).
PetscErrorCode InsulatedState(const Lattice &lat, PetscReal a, Vec z)
{
  const LatticeParams &p = lat.Params();
  const PetscInt N = lat.N(), m = p.InterfaceSite();
  const PetscReal r = -p.K2() / p.K1();
  PetscFunctionBeginUser;
  PetscCall(VecZeroEntries(z));
  for (PetscInt i = 0; i < N; i++) {
    const PetscInt d = i - (m + 1); // distance from the interface's even site
    if (d % 2 || i < lat.OwnedStart() || i >= lat.OwnedStart() + lat.OwnedCount()) continue;
    const PetscReal x = a * std::pow(r, std::abs(d) / 2);
    if (std::abs(x) < 1e-300) continue;
    PetscCall(VecSetValue(z, lat.StateIndexU(i), x, INSERT_VALUES));
  }
  PetscCall(VecAssemblyBegin(z));
  PetscCall(VecAssemblyEnd(z));
  PetscFunctionReturn(0);
}

} // namespace

int main(int argc, char **argv)
{
  PetscCall(PetscInitialize(&argc, &argv, NULL, "block_tangents: s tangent products in one pass against s single ones\n"));
  {
    MPI_Comm comm = PETSC_COMM_WORLD;
    PetscCall(LogRegister());
    PetscCall(TSSymSplitRegister());
    PetscInt s = 8, repeats = 5;
    PetscReal amp = 0.5;
    PetscCall(PetscOptionsGetInt(NULL, NULL, "-bench_s", &s, NULL));
    PetscCall(PetscOptionsGetInt(NULL, NULL, "-bench_repeats", &repeats, NULL));
    PetscCall(PetscOptionsGetReal(NULL, NULL, "-bench_amplitude", &amp, NULL));
    PetscCheck(s >= 1 && repeats >= 1, comm, PETSC_ERR_USER, "-bench_s %" PetscInt_FMT " and -bench_repeats %" PetscInt_FMT " must be positive", s, repeats);
    LatticeParams p;
    PetscCall(LatticeParamsFromOptions(comm, &p));
    Lattice lat;
    PetscCall(lat.Setup(comm, p));
    EffectList fx(lat);
    PetscCall(BuildEffects(lat, nullptr, &fx));
    FlowOptions fo;
    PetscCall(FlowOptionsFromOptions(comm, &fo));
    PeriodicFlow flow;
    PetscCall(flow.Setup(fx, fo));
    PetscCheck(flow.Symplectic(), comm, PETSC_ERR_USER, "block_tangents measures the symplectic route (-nnm_ts_type symsplit)");
    const PetscReal T = 2 * PETSC_PI / std::sqrt(p.KHat());
    OwnedVec z0, zT;
    PetscCall(lat.CreateStateVector(z0.out()));
    PetscCall(VecDuplicate(z0, zT.out()));
    PetscCall(InsulatedState(lat, amp, z0));
    std::vector<OwnedVec> dzo(s), wbo(s), wso(s);
    std::vector<Vec> dz(s), wb(s);
    PetscRandom rnd;
    PetscCall(PetscRandomCreate(comm, &rnd));
    PetscCall(PetscRandomSetSeed(rnd, 35));
    PetscCall(PetscRandomSeed(rnd));
    for (PetscInt j = 0; j < s; j++) {
      for (OwnedVec *v : {&dzo[j], &wbo[j], &wso[j]}) PetscCall(VecDuplicate(z0, v->out()));
      PetscCall(VecSetRandom(dzo[j], rnd));
      dz[j] = dzo[j], wb[j] = wbo[j];
    }
    PetscCall(PetscRandomDestroy(&rnd));
    // warm-up: both set-ups (TS, ghost scatter) outside the timing
    PetscCall(flow.IntegrateWithTangents(z0, T, 0.0, dz, zT, wb));
    PetscCall(flow.IntegrateWithTangent(z0, T, 0.0, dz[0], 0.0, 0.0, zT, wso[0]));
    std::vector<double> tb, ts;
    PetscReal agree = 0, mnorm = 0;
    for (PetscInt r = 0; r < repeats; r++) {
      PetscCallMPI(MPI_Barrier(comm));
      double t0 = Now();
      PetscCall(flow.IntegrateWithTangents(z0, T, 0.0, dz, zT, wb));
      PetscCallMPI(MPI_Barrier(comm));
      tb.push_back(Now() - t0);
      t0 = Now();
      for (PetscInt j = 0; j < s; j++) PetscCall(flow.IntegrateWithTangent(z0, T, 0.0, dz[j], 0.0, 0.0, zT, wso[j]));
      PetscCallMPI(MPI_Barrier(comm));
      ts.push_back(Now() - t0);
      for (PetscInt j = 0; j < s; j++) {
        PetscReal nw, nd, nz;
        PetscCall(VecNorm(wso[j], NORM_INFINITY, &nw));
        PetscCall(VecNorm(dz[j], NORM_INFINITY, &nz));
        PetscCall(VecAXPY(wso[j], -1.0, wb[j]));
        PetscCall(VecNorm(wso[j], NORM_INFINITY, &nd));
        agree = std::max(agree, nd / nw), mnorm = std::max(mnorm, nw / nz);
      }
    }
    const double mb = Median(tb), ms = Median(ts);
    PetscCall(PetscPrintf(comm,
                          "block_tangents: N = %" PetscInt_FMT ", s = %" PetscInt_FMT ", %" PetscInt_FMT " steps per period, %" PetscInt_FMT
                          " repeats: block %.4f s, %" PetscInt_FMT " single %.4f s (medians), speed-up %.2f; max |w_block - w_single| / |w_single| = %.2e "
                          "(|M| >= %.3g)\n",
                          lat.N(), s, flow.Steps(), repeats, mb, s, ms, ms / mb, (double)agree, (double)mnorm));
  }
  PetscCall(PetscFinalize());
  return 0;
}
