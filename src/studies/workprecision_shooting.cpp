// -wp_scene shooting: what accuracy costs for one orbit of the insulated NNM
// branch (studies/workprecision.hpp).
#include "stability/floquet.hpp"
#include "studies/nnm_setup.hpp"
#include "studies/workprecision.hpp"
#include "core/gather.hpp"
#include "studies/wp_configs.hpp"
#include "core/cost.hpp"
#include <memory>

namespace nltopo {

namespace {

using namespace wp;

const char *const kShootObservables[4] = {"omega", "closure", "max_modulus", "det"};

// Keeps the last orbit of a continued branch.
class LastOrbit : public PointHook {
public:
  PetscErrorCode Point(Vec z0, PetscReal T, PetscReal, Vec) override
  {
    PetscFunctionBeginUser;
    if (!z) PetscCall(VecDuplicate(z0, z.out()));
    PetscCall(VecCopy(z0, z));
    period = T;
    PetscFunctionReturn(0);
  }
  OwnedVec z;
  PetscReal period = 0;
};

// One shooting solve of the orbit at energy E from (z_guess, T_guess), with
// the options as they stand (the configuration's integrator), and its
// monodromy: a fresh flow and shooting system, so that the configuration's
// -nnm_ts_* and -nnm_steps_per_period are read.
struct Orbit {
  OwnedVec z0;
  PetscReal T = 0, omega = 0, max_modulus = 0, det = 0, wall = 0;
  PetscInt newton = 0;
};

PetscErrorCode SolveOrbit(const EffectList &fx, Vec z_guess, PetscReal T_guess, PetscReal E, Orbit *orb, std::unique_ptr<PeriodicFlow> *keep_flow = nullptr)
{
  const Lattice &lat = fx.Lat();
  MPI_Comm comm = lat.Comm();
  FlowOptions fo;
  ShootingOptions so;
  FloquetOptions flo;
  auto owned = std::make_unique<PeriodicFlow>();
  PeriodicFlow &flow = *owned;
  Shooting shoot;
  OwnedVec X, zT;
  OwnedMat S;
  PetscReal beta;
  bool converged;
  PetscLogDouble t0, t1;
  PetscFunctionBeginUser;
  PetscCall(FlowOptionsFromOptions(comm, &fo));
  PetscCall(ShootingOptionsFromOptions(comm, &so));
  PetscCall(FloquetOptionsFromOptions(comm, &flo));
  PetscCall(flow.Setup(fx, fo));
  PetscCall(shoot.Setup(flow, so));
  PetscCall(shoot.CreateUnknowns(X.out()));
  if (!orb->z0) PetscCall(VecDuplicate(z_guess, orb->z0.out()));
  PetscCall(VecDuplicate(z_guess, zT.out()));
  PetscCallMPI(MPI_Barrier(comm));
  PetscCall(PetscTime(&t0));
  PetscCall(shoot.SetEnergyConstraint(z_guess, E));
  PetscCall(shoot.Pack(z_guess, T_guess, 0, X));
  PetscCall(shoot.Solve(X, &converged, &orb->newton));
  PetscCheck(converged, comm, PETSC_ERR_NOT_CONVERGED, "-study workprecision: the shooting Newton did not converge at E = %g (%s)", (double)E,
             shoot.LastReason());
  PetscCall(shoot.Unpack(X, orb->z0, &orb->T, &beta));
  FloquetResult r;
  PetscCall(flow.CreateSensitivityMatrix(S.out()));
  PetscCall(flow.IntegrateWithMonodromy(orb->z0, orb->T, flow.FloquetBeta(beta), zT, S));
  PetscCall(FloquetAnalysis(lat, S, flo, &r));
  PetscCall(PetscTime(&t1));
  double w = t1 - t0;
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &w, 1, MPI_DOUBLE, MPI_MAX, comm));
  orb->wall = w;
  orb->omega = 2 * PETSC_PI / orb->T;
  orb->max_modulus = r.max_modulus;
  orb->det = r.det_error;
  if (keep_flow) *keep_flow = std::move(owned); // the reference flow integrates the configurations' orbits
  PetscFunctionReturn(0);
}

// |z(T) - z0| / |z0| of an orbit integrated by the given flow (beta = 0).
PetscErrorCode Closure(PeriodicFlow &flow, const Orbit &orb, PetscReal *c)
{
  OwnedVec zT;
  PetscFunctionBeginUser;
  PetscCall(VecDuplicate(orb.z0, zT.out()));
  PetscCall(flow.Integrate(orb.z0, orb.T, 0, zT));
  PetscCall(StateDistance(zT, orb.z0, c));
  PetscFunctionReturn(0);
}

} // namespace

PetscErrorCode RunWorkPrecisionShooting(MPI_Comm comm, const WorkPrecisionOptions &o, WorkPrecisionResult *res)
{
  NnmSetup nnm;
  LastOrbit last;
  Branch b;
  OptionPairs ref_opts;
  const int nq = 4;
  PetscFunctionBeginUser;
  *res = WorkPrecisionResult();
  res->observables.assign(kShootObservables, kShootObservables + nq);
  res->reference_change.assign(nq, 0.0);
  res->reference_value.assign(nq, 0.0);
  res->spread.assign(nq, 0.0);
  PetscCall(ParseConfig(comm, "-wp_nnm_reference", o.nnm_reference, &ref_opts, true));

  // The guess: the insulated branch of the scene continued to the energy.
  PetscCall(nnm.ReadOptions(comm));
  PetscCall(nnm.Build(comm, "-study workprecision -wp_scene shooting"));
  PetscCheck(nnm.modes.Insulated(), comm, PETSC_ERR_USER, "-wp_scene shooting follows the insulated branch, and this lattice has no insulated mode: %s",
             NoInsulatedModeReason(nnm.lat.Params()).c_str());
  PetscBool verbose_given; // the branch is quiet unless -cont_verbose asks otherwise
  PetscCall(PetscOptionsHasName(NULL, NULL, "-cont_verbose", &verbose_given));
  if (!verbose_given) nnm.co.verbose = PETSC_FALSE;
  nnm.co.energy_max = o.nnm_energy; // (-cont_energy_max is refused: workprecision_study.cpp)
  PetscCall(ContinueBranch(nnm.shoot, nnm.modes.Insulated(), 2 * PETSC_PI / nnm.modes.Named().insulated_omega, nnm.co, "insulated", &b, &last));
  PetscCheck(last.z, comm, PETSC_ERR_NOT_CONVERGED, "-wp_scene shooting: the insulated branch has no orbit (%s)", b.stop_reason.c_str());

  // The reference: the reference integrator at n, 2n, ... steps per period
  // until two successive orbits agree in omega and the leading modulus.
  Orbit ref, prev;
  std::unique_ptr<PeriodicFlow> ref_flow;
  bool have_prev = false;
  PetscInt n = o.nnm_reference_steps;
  for (;;) {
    OptionPairs opts = ref_opts;
    opts.push_back({"-nnm_steps_per_period", std::to_string(n)});
    ScopedConfig sc;
    PetscCall(sc.Apply(opts));
    PetscCall(SolveOrbit(nnm.fx, last.z, last.period, o.nnm_energy, &ref, &ref_flow));
    PetscCall(sc.Restore());
    res->reference = o.nnm_reference + " -nnm_steps_per_period " + std::to_string(n);
    res->reference_wall = ref.wall;
    if (have_prev) {
      res->reference_change[0] = Rel(prev.omega, ref.omega);
      res->reference_change[2] = Rel(prev.max_modulus, ref.max_modulus);
      res->reference_change[3] = std::abs(prev.det - ref.det);
      if (res->reference_change[0] <= o.reference_agreement && res->reference_change[2] <= o.reference_agreement) { // (false for NaN)
        res->reference_converged = true;
        break;
      }
    }
    if (n >= 16 * o.nnm_reference_steps) break;
    std::swap(prev, ref);
    have_prev = true;
    n *= 2;
  }
  res->reference_value = {ref.omega, 0, ref.max_modulus, ref.det};
  PetscCall(Closure(*ref_flow, ref, &res->reference_value[1]));
  PetscCall(GatherVec(ref.z0, true, &res->reference_z));
  // The floor: an isolated periodic orbit at a given energy is a well-posed
  // problem (nothing amplifies a perturbation), so below the reference's own
  // last change an error means nothing.
  res->spread = res->reference_change;

  // Every configuration from the same guess.
  for (size_t c = 0; c < o.configs.size(); c++) {
    WorkPrecisionRow row;
    Orbit orb;
    PetscInt s0 = 0, e0 = 0, s1 = 0, e1 = 0;
    PetscCall(TimeConfiguration(
        comm, o.configs[c], true, o.repeats,
        [&](PetscReal *w) -> PetscErrorCode {
          PetscFunctionBeginUser;
          CostTotals(&s0, &e0);
          PetscCall(SolveOrbit(nnm.fx, last.z, last.period, o.nnm_energy, &orb));
          CostTotals(&s1, &e1);
          *w = orb.wall;
          PetscFunctionReturn(0);
        },
        &row));
    PetscInt work[2] = {s1 - s0, e1 - e0}; // one solve's integration steps and force evaluations (rank 0 counts them)
    PetscCallMPI(MPI_Bcast(work, 2, MPIU_INT, 0, comm));
    row.steps = work[0];
    row.rhs_evals = work[1];
    PetscReal closure;
    PetscCall(Closure(*ref_flow, orb, &closure));
    row.error = {Rel(orb.omega, ref.omega), closure, Rel(orb.max_modulus, ref.max_modulus), orb.det};
    row.value = {orb.omega, closure, orb.max_modulus, orb.det};
    PetscCall(GatherVec(orb.z0, true, &row.z_final));
    PetscCall(PetscPrintf(comm, "  %-40s %-12s %9.4f s  omega error %.2e  closure %.2e  max|mu| error %.2e  |det M - 1| %.1e\n", row.method.c_str(),
                          row.accuracy.c_str(), (double)row.wall, (double)row.error[0], (double)row.error[1], (double)row.error[2], (double)row.error[3]));
    res->rows.push_back(row);
  }
  PetscFunctionReturn(0);
}

} // namespace nltopo
