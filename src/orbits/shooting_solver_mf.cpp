// The matrix-free strategy of ShootingSolver (-nnm_jacobian mf): inexact
// Newton, GMRES on the shell Jacobian, right-preconditioned by the linear
// monodromy preconditioner (-nnm_mf_pc) on the state rows.
#include "core/log.hpp"
#include "orbits/shooting_solver.hpp"

namespace nltopo {

namespace {
PetscErrorCode ShootPCApply(PC pc, Vec r, Vec x)
{
  void *s;
  PetscFunctionBeginUser;
  PetscCall(PCShellGetContext(pc, &s));
  PetscCall(static_cast<ShootingSolver *>(s)->PCApply(r, x));
  PetscFunctionReturn(0);
}
} // namespace

PetscErrorCode ShootingSolver::SetupMatrixFree(KSP ksp, PC pc)
{
  PetscFunctionBeginUser;
  PetscCall(sys_->CreateShellJacobian(Jshell_.out()));
  PetscCall(VecDuplicate(sys_->LinearisationState(), zT_.out()));
  PetscCall(KSPSetType(ksp, KSPGMRES));
  if (opt_.mf_pc != MatrixFreePC::None) {
    PetscCall(lin_pc_.Setup(sys_->Lat()));
    PetscCall(PCSetType(pc, PCSHELL));
    PetscCall(PCShellSetContext(pc, this));
    PetscCall(PCShellSetApply(pc, ShootPCApply));
    const char *name =
        opt_.mf_pc == MatrixFreePC::Linear ? "exact inverse of M_lin - I (linear lattice) on the state rows, identity on the border"
        : opt_.mf_pc == MatrixFreePC::Averaged
            ? "exact inverse of M_avg - I (linear lattice with the orbit's time-averaged tangent stiffness) on the state rows, identity on the border"
            : "inverse of M_avg - I plus the rotating-wave 2 omega parametric block near the 1:1 resonance on the state rows, identity on the border";
    PetscCall(PCShellSetName(pc, name));
    PetscCall(KSPSetPCSide(ksp, PC_RIGHT)); // GMRES minimises the true residual
  } else PetscCall(PCSetType(pc, PCNONE));
  PetscCall(KSPSetTolerances(ksp, 1e-10, 1e-14, PETSC_DEFAULT, 400));
  PetscCall(KSPGMRESSetRestart(ksp, 100)); // no restarts within the iteration counts the preconditioner gives
  // Classical Gram-Schmidt loses orthogonality on the nearly singular M - I of
  // long lattices in a band; at a restart PETSc then finds the recursion's
  // residual far from the true one and stops with DIVERGED_BREAKDOWN. A second
  // pass when needed costs O(k N) per iteration, nothing beside a tangent
  // integration.
  PetscCall(KSPGMRESSetCGSRefinementType(ksp, KSP_GMRES_CGS_REFINE_IFNEEDED));
  // Inexact Newton (Eisenstat-Walker forcing terms): GMRES is converged only as
  // far as the Newton step needs. Inside the bands, where resonant modes make
  // the preconditioned operator far from the identity, this saves most GMRES
  // iterations per point (docs/long-lattices.md).
  PetscCall(SNESKSPSetUseEW(snes_, PETSC_TRUE));
  PetscFunctionReturn(0);
}

// The preconditioner at the linearisation point: -nnm_mf_pc averaged and
// parametric take the harmonics of the tangent stiffness along the orbit
// through it (one integration); linear and none need no integration.
PetscErrorCode ShootingSolver::UpdatePreconditioner()
{
  PeriodicFlow &flow = sys_->Flow();
  Vec z = sys_->LinearisationState();
  const PetscReal T = sys_->LinearisationPeriod(), beta = sys_->LinearisationBeta();
  PetscFunctionBeginUser;
  if (opt_.mf_pc == MatrixFreePC::Averaged || opt_.mf_pc == MatrixFreePC::Parametric) {
    kharm_.parametric = opt_.mf_pc == MatrixFreePC::Parametric;
    PetscCall(flow.IntegrateAveragingStiffness(z, T, beta, zT_, &kharm_));
    PetscCall(lin_pc_.SetStiffness(kharm_.d0, kharm_.o0));
    if (kharm_.parametric) PetscCall(lin_pc_.SetParametricTerm(kharm_.dc, kharm_.oc, kharm_.ds, kharm_.os, opt_.parametric_weight));
  }
  if (opt_.mf_pc != MatrixFreePC::None) PetscCall(lin_pc_.SetPeriod(T));
  PetscFunctionReturn(0);
}

// State rows: the linear monodromy preconditioner; the phase and constraint rows: identity.
PetscErrorCode ShootingSolver::PCApply(Vec r, Vec x)
{
  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(Log().mf_pc, 0, 0, 0, 0));
  PetscCall(lin_pc_.Apply(r, x));
  PetscCall(sys_->CopyBorder(r, x));
  PetscCall(PetscLogEventEnd(Log().mf_pc, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

} // namespace nltopo
