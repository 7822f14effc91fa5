#include "orbits/shooting_solver.hpp"
#include "core/log.hpp"
#include "core/option_table.hpp"
#include <algorithm>

namespace nltopo {

static const char *const kJacobianNames[] = {"dense", "mf"};
static const char *const kMfPcNames[] = {"none", "linear", "averaged", "parametric"};

static const auto &kShootingTable = DeclareOptionTable<
    ShootingOptions>("nnm_", "Shooting Newton (SNES options: -nnm_snes_*, -nnm_ksp_*, -nnm_pc_*)", [](OptionTable<ShootingOptions> &t) {
  t.Enum(
       "jacobian", &ShootingOptions::jacobian, kJacobianNames, 2,
       "Shooting Jacobian: dense (monodromy by forward sensitivities) or mf (one tangent-linear integration per product); -nnm_snes_mf for finite differences")
      .Int("start_dense_max", &ShootingOptions::start_dense_max, Closed(0, 20000),
           "Largest 2N for which the first orbit of a branch uses the dense SVD start solver (-nnm_start_*); default 4000 for the "
           "dense Jacobian, 0 for mf (its preconditioner already treats the edge-mode direction exactly)")
      .Default("4000 (dense), 0 (mf)")
      .Enum("mf_pc", &ShootingOptions::mf_pc, kMfPcNames, 4,
            "Preconditioner of the mf shooting Jacobian: linear (exact inverse of M_lin - I of the linear lattice, O(N) per "
            "application), averaged (the same with K replaced by the orbit's time-averaged tangent stiffness), parametric (averaged "
            "plus the orbit's 2 omega parametric term on the band modes near omega, rotating-wave approximation) or none (plain GMRES)")
      .Real("mf_pc_parametric_weight", &ShootingOptions::parametric_weight, LeftOpen(0, 1),
            "Scale of the 2 omega term in -nnm_mf_pc parametric; below 1 it keeps the block regular along the orbit's own phase "
            "direction (1 makes GMRES break down at converged orbits)")
      .Real("orbit_rtol", &ShootingOptions::orbit_rtol, RightOpen(0, 1),
            "Newton also stops once |z(T) - z0| <= this times |z0| (0: only -nnm_snes_atol and -nnm_snes_rtol); for branches whose "
            "amplitude grows by decades, where one absolute tolerance is too tight at the top or too loose at the bottom");
});

PetscErrorCode ShootingOptionsFromOptions(MPI_Comm comm, ShootingOptions *o)
{
  std::vector<PetscBool> set;
  PetscFunctionBeginUser;
  PetscCall(kShootingTable.Read(comm, o, &set));
  if (!kShootingTable.Given(set, "start_dense_max") && o->jacobian == ShootingJacobian::MatrixFree) o->start_dense_max = 0;
  PetscFunctionReturn(0);
}

namespace {
// A Newton iterate with T <= 0 (a failing step far from the branch) is outside
// the domain: SNES stops with DIVERGED_FUNCTION_DOMAIN and the continuation
// rejects the step, instead of integrating backwards or failing at SetPeriod.
PetscErrorCode ShootResidual(SNES snes, Vec X, Vec F, void *ctx)
{
  ShootingSystem *sys = static_cast<ShootingSystem *>(ctx);
  PetscBool ok;
  PetscFunctionBeginUser;
  PetscCall(sys->InDomain(X, &ok));
  if (!ok) {
    PetscCall(SNESSetFunctionDomainError(snes));
    PetscFunctionReturn(0);
  }
  PetscCall(sys->Residual(X, F));
  PetscFunctionReturn(0);
}
PetscErrorCode ShootJacobian(SNES snes, Vec X, Mat A, Mat P, void *ctx)
{
  ShootingSolver *s = static_cast<ShootingSolver *>(ctx);
  PetscBool ok;
  PetscFunctionBeginUser;
  PetscCall(s->System().InDomain(X, &ok));
  if (!ok) {
    PetscCall(SNESSetJacobianDomainError(snes));
    PetscFunctionReturn(0);
  }
  PetscCall(s->SnesJacobian(snes, X, P));
  if (A != P) {
    PetscCall(MatAssemblyBegin(A, MAT_FINAL_ASSEMBLY));
    PetscCall(MatAssemblyEnd(A, MAT_FINAL_ASSEMBLY));
  }
  PetscFunctionReturn(0);
}
PetscErrorCode ShootConverged(SNES snes, PetscInt it, PetscReal xnorm, PetscReal snorm, PetscReal fnorm, SNESConvergedReason *reason, void *ctx)
{
  PetscFunctionBeginUser;
  PetscCall(static_cast<ShootingSolver *>(ctx)->Converged(snes, it, xnorm, snorm, fnorm, reason));
  PetscFunctionReturn(0);
}
} // namespace

PetscErrorCode ShootingSolver::Setup(ShootingSystem &sys, const ShootingOptions &o)
{
  MPI_Comm comm = sys.Lat().Comm();
  KSP ksp;
  PC pc;
  PetscFunctionBeginUser;
  sys_ = &sys;
  opt_ = o;
  PetscCall(sys.CreateUnknowns(F_.out()));
  PetscCall(VecDuplicate(F_, rhs_.out()));
  PetscCall(SNESCreate(comm, snes_.out()));
  PetscCall(SNESSetOptionsPrefix(snes_, "nnm_"));
  PetscCall(SNESSetFunction(snes_, F_, ShootResidual, sys_));
  PetscCall(SNESGetKSP(snes_, &ksp));
  PetscCall(KSPGetPC(ksp, &pc));
  // The assembled Jacobian: the dense route, and the start solver of every
  // route while 2N is small enough to hold it.
  if (o.jacobian == ShootingJacobian::Dense || sys.Size() - 2 <= o.start_dense_max) PetscCall(sys.CreateDenseJacobian(Jdense_.out()));
  if (o.jacobian == ShootingJacobian::Dense) PetscCall(SetupDirect(ksp, pc));
  else PetscCall(SetupMatrixFree(ksp, pc));
  PetscCall(SNESSetJacobian(snes_, Operator(), Operator(), ShootJacobian, this));
  PetscCall(SNESSetTolerances(snes_, 1e-12, 1e-10, 1e-14, 12, PETSC_DEFAULT));
  PetscCall(SNESSetFromOptions(snes_));
  PetscCall(SNESGetTolerances(snes_, &snes_atol_, NULL, NULL, NULL, NULL));
  if (o.jacobian == ShootingJacobian::MatrixFree) {
    // No GMRES iterations beyond what Newton's own threshold asks for
    // (-nnm_snes_atol here, or -nnm_orbit_rtol |z0| once larger: Converged): a
    // linear residual below half of it makes the next |F| (linear residual +
    // O(|step|^2)) meet it. Eisenstat-Walker alone asks the last solve for a
    // fixed relative reduction, which near the band edge of long lattices costs
    // many iterations on a residual already close to atol (benchmarks/README.md).
    PetscCall(PetscOptionsHasName(NULL, "nnm_", "-ksp_atol", &ksp_atol_set_));
    if (!ksp_atol_set_) PetscCall(KSPSetTolerances(ksp, PETSC_DEFAULT, 0.5 * snes_atol_, PETSC_DEFAULT, PETSC_DEFAULT));
  }
  PetscCall(SNESSetConvergenceTest(snes_, ShootConverged, this, NULL));
  PetscCall(KSPGetTolerances(ksp, &tangent_rtol_, NULL, NULL, NULL)); // before Eisenstat-Walker changes it
  PetscCall(PetscOptionsHasName(NULL, "nnm_", "-snes_mf", &snes_mf_));
  if (Jdense_) PetscCall(SetupStart());
  PetscFunctionReturn(0);
}

// Newton with the assembled Jacobian; a pivoting LU, since the bordered
// Jacobian has zero diagonal entries: MUMPS.
PetscErrorCode ShootingSolver::SetupDirect(KSP ksp, PC pc)
{
  PetscFunctionBeginUser;
  PetscCall(KSPSetType(ksp, KSPPREONLY));
  PetscCall(PCSetType(pc, PCLU));
  PetscCall(PCFactorSetMatSolverType(pc, MATSOLVERMUMPS));
  PetscFunctionReturn(0);
}

// Start solver (prefix -nnm_start_) for the first orbit of a branch:
// pseudo-inverse by SVD with tiny singular values dropped. At the linear limit
// of the insulated branch the left-end edge mode has the same period (model.md
// "Trap"): a near-null direction of the shooting Jacobian, its singular value
// orders of magnitude below the others, that an LU would follow off the
// branch. Dropping it keeps Newton quadratic and on the insulated family;
// along the branch the hardening detunes the edge mode and the main solver's
// pivoting LU is used.
PetscErrorCode ShootingSolver::SetupStart()
{
  KSP ksp;
  PC pc;
  PetscBool has;
  PetscFunctionBeginUser;
  PetscCall(PetscOptionsHasName(NULL, "nnm_start_", "-pc_svd_zero_sing", &has));
  if (!has) PetscCall(PetscOptionsSetValue(NULL, "-nnm_start_pc_svd_zero_sing", "1e-9")); // PCSVD has no setter in 3.18
  PetscCall(SNESCreate(sys_->Lat().Comm(), snes_start_.out()));
  PetscCall(SNESSetOptionsPrefix(snes_start_, "nnm_start_"));
  PetscCall(SNESSetFunction(snes_start_, F_, ShootResidual, sys_));
  PetscCall(SNESSetJacobian(snes_start_, Jdense_, Jdense_, ShootJacobian, this));
  PetscCall(SNESGetKSP(snes_start_, &ksp));
  PetscCall(KSPSetType(ksp, KSPPREONLY));
  PetscCall(KSPGetPC(ksp, &pc));
  PetscCall(PCSetType(pc, PCSVD));
  PetscCall(SNESSetTolerances(snes_start_, 1e-12, 1e-10, 1e-14, 20, PETSC_DEFAULT));
  PetscCall(SNESSetFromOptions(snes_start_));
  PetscFunctionReturn(0);
}

PetscErrorCode ShootingSolver::Jacobian(Vec X, Mat J)
{
  PetscFunctionBeginUser;
  if (J != Jshell_.get()) {
    PetscCall(sys_->AssembleJacobian(X, J));
    PetscFunctionReturn(0);
  }
  PetscCall(sys_->Linearise(X));
  PetscCall(UpdatePreconditioner());
  PetscCall(MatAssemblyBegin(J, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(J, MAT_FINAL_ASSEMBLY));
  PetscFunctionReturn(0);
}

// SNESConvergedDefault, plus |F| <= -nnm_orbit_rtol |z0|; on the mf route it
// also keeps GMRES's atol at half of the threshold in force.
PetscErrorCode ShootingSolver::Converged(SNES snes, PetscInt it, PetscReal xnorm, PetscReal snorm, PetscReal fnorm, SNESConvergedReason *reason)
{
  PetscFunctionBeginUser;
  PetscCall(SNESConvergedDefault(snes, it, xnorm, snorm, fnorm, reason, NULL));
  if (opt_.orbit_rtol <= 0 || *reason != SNES_CONVERGED_ITERATING) PetscFunctionReturn(0);
  Vec X;
  PetscReal zn;
  PetscCall(SNESGetSolution(snes, &X));
  PetscCall(sys_->StateNorm(X, &zn));
  const PetscReal thr = std::max(snes_atol_, opt_.orbit_rtol * zn);
  if (fnorm <= thr) {
    PetscCall(PetscInfo(snes, "|F| = %g <= -nnm_orbit_rtol |z0| = %g\n", (double)fnorm, (double)thr));
    *reason = SNES_CONVERGED_FNORM_ABS;
  } else if (opt_.jacobian == ShootingJacobian::MatrixFree && !ksp_atol_set_) {
    KSP ksp; // the next GMRES solve: no further than half of the threshold (see Setup)
    PetscCall(SNESGetKSP(snes, &ksp));
    PetscCall(KSPSetTolerances(ksp, PETSC_DEFAULT, 0.5 * thr, PETSC_DEFAULT, PETSC_DEFAULT));
  }
  PetscFunctionReturn(0);
}

// The chord's contraction: kept while |F| falls by this factor per iteration
// (to -nnm_snes_atol from a guess's |F| within the default -nnm_snes_max_it).
static constexpr PetscReal kChordRate = 0.1;

PetscErrorCode ShootingSolver::SeedJacobian(Vec X, Mat S)
{
  PetscFunctionBeginUser;
  PetscCheck(opt_.jacobian == ShootingJacobian::Dense && !snes_mf_, sys_->Lat().Comm(), PETSC_ERR_PLIB, "SeedJacobian: the dense route only");
  PetscCall(sys_->AssembleJacobianFrom(X, S, Jdense_));
  if (!Xseed_) PetscCall(VecDuplicate(X, Xseed_.out()));
  PetscCall(VecCopy(X, Xseed_));
  chord_ = true, chord_fnorm_ = 0;
  PetscFunctionReturn(0);
}

PetscErrorCode ShootingSolver::SnesJacobian(SNES snes, Vec X, Mat J)
{
  PetscFunctionBeginUser;
  if (chord_) {
    PetscInt it;
    PetscReal fnorm;
    PetscCall(SNESGetIterationNumber(snes, &it));
    PetscCall(SNESGetFunctionNorm(snes, &fnorm));
    if (it == 0 || fnorm <= kChordRate * chord_fnorm_) { // J unchanged: the LU is kept too (PCSetUp sees the same state)
      chord_fnorm_ = fnorm;
      PetscFunctionReturn(0);
    }
    chord_ = false; // contracting too slowly: Newton from here
  }
  PetscCall(Jacobian(X, J));
  PetscFunctionReturn(0);
}

PetscErrorCode ShootingSolver::SolveOnce(SNES snes, Vec X)
{
  PetscInt lits;
  PetscFunctionBeginUser;
  PetscCall(SNESSolve(snes, NULL, X));
  PetscCall(SNESGetConvergedReason(snes, &reason_));
  PetscCall(SNESGetLinearSolveIterations(snes, &lits));
  nkrylov_ += lits;
  if (reason_ <= 0) { // e.g. a zero pivot at a bifurcation: start the next factorisation afresh
    KSP ksp;
    PC pc;
    PetscCall(SNESGetKSP(snes, &ksp));
    PetscCall(KSPGetPC(ksp, &pc));
    PetscCall(PCReset(pc));
  }
  PetscFunctionReturn(0);
}

PetscErrorCode ShootingSolver::Solve(Vec X, bool *converged, PetscInt *its)
{
  // The first orbit of a branch (energy constraint) uses the start solver.
  SNES snes = sys_->EnergyConstrained() && energy_start_ && snes_start_ ? snes_start_.get() : snes_.get();
  PetscFunctionBeginUser;
  if (snes != snes_.get()) chord_ = false; // (a seed is the main solver's)
  const bool seeded = chord_;
  const PetscInt j0 = sys_->JacobianEvaluations();
  PetscCall(SolveOnce(snes, X));
  PetscCall(SNESGetIterationNumber(snes, its));
  if (seeded && reason_ <= 0) { // the chord failed: plain Newton from the guess
    PetscInt more;
    chord_ = false;
    PetscCall(VecCopy(Xseed_, X));
    PetscCall(SolveOnce(snes, X));
    PetscCall(SNESGetIterationNumber(snes, &more));
    *its += more;
  }
  chord_ = false;
  *converged = reason_ > 0;
  fresh_ = *converged && sys_->JacobianEvaluations() > j0 && snes == snes_.get() && opt_.jacobian == ShootingJacobian::Dense && !snes_mf_;
  PetscFunctionReturn(0);
}

PetscErrorCode ShootingSolver::Tangent(Vec X, Vec t_prev, Vec t)
{
  KSP ksp;
  PetscReal nrm, d;
  PetscFunctionBeginUser;
  // J t = e_last with the Jacobian of the last Newton iterate (already
  // factored; one step from the solution), or a new one at the solution when
  // Newton needed no iteration or the route is matrix-free.
  PetscCall(SNESGetKSP(snes_, &ksp));
  if (snes_mf_) { // -nnm_snes_mf: the finite-difference operator, based at the solution
    Mat A;
    PetscCall(SNESGetJacobian(snes_, &A, NULL, NULL, NULL));
    PetscCall(SNESComputeFunction(snes_, X, F_));
    PetscCall(MatMFFDSetBase(A, X, F_));
    PetscCall(KSPSetOperators(ksp, A, A));
  } else if (!fresh_) {
    Mat J = opt_.jacobian == ShootingJacobian::Dense ? Jdense_.get() : Jshell_.get();
    PetscCall(Jacobian(X, J));
    PetscCall(KSPSetOperators(ksp, J, J));
  }
  PetscInt lo, hi;
  const PetscInt last = sys_->Size() - 1;
  PetscCall(VecZeroEntries(rhs_));
  PetscCall(VecGetOwnershipRange(rhs_, &lo, &hi));
  if (last >= lo && last < hi) PetscCall(VecSetValue(rhs_, last, 1.0, INSERT_VALUES));
  PetscCall(VecAssemblyBegin(rhs_));
  PetscCall(VecAssemblyEnd(rhs_));
  PetscReal rtol, atol, dtol;
  PetscInt maxit;
  PetscCall(KSPGetTolerances(ksp, &rtol, &atol, &dtol, &maxit)); // the last Eisenstat-Walker forcing term: too loose for the predictor
  PetscCall(KSPSetTolerances(ksp, tangent_rtol_, atol, dtol, maxit));
  PetscCall(KSPSolve(ksp, rhs_, t));
  PetscCall(KSPSetTolerances(ksp, rtol, atol, dtol, maxit));
  if (opt_.jacobian == ShootingJacobian::MatrixFree) {
    PetscInt lits;
    PetscCall(KSPGetIterationNumber(ksp, &lits));
    nkrylov_ += lits;
  }
  PetscCall(VecNormalize(t, &nrm));
  if (t_prev) {
    PetscCall(VecDot(t, t_prev, &d));
    if (d < 0) PetscCall(VecScale(t, -1.0));
  }
  PetscFunctionReturn(0);
}

} // namespace nltopo
