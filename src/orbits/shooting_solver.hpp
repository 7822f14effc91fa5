#pragma once
// Newton on the shooting system (orbits/shooting_system.hpp), SNES prefix
// -nnm_. -nnm_jacobian chooses the strategy:
//   dense: the assembled Jacobian, factored by a pivoting LU (MUMPS; small N);
//   mf:    the MATSHELL Jacobian, one tangent-linear integration per product
//          (any N), by inexact Newton with GMRES preconditioned by -nnm_mf_pc:
//          "linear" applies the exact inverse of M_lin - I of the linear
//          lattice to the state rows, "averaged" the same with the orbit's
//          time-averaged tangent stiffness, "parametric" adds its 2 omega term
//          near the 1:1 resonance (orbits/linear_monodromy_pc.hpp).
// -nnm_snes_mf gives finite differences. The first orbit of a branch (energy
// constraint) uses the start solver (prefix -nnm_start_) while 2N is at most
// -nnm_start_dense_max: the assembled Jacobian, pseudo-inverted by SVD.
#include "orbits/linear_monodromy_pc.hpp"
#include "orbits/shooting_system.hpp"

namespace nltopo {

enum class ShootingJacobian { Dense = 0, MatrixFree = 1 };
enum class MatrixFreePC { None = 0, Linear = 1, Averaged = 2, Parametric = 3 };

struct ShootingOptions {
  ShootingJacobian jacobian = ShootingJacobian::Dense;
  PetscInt start_dense_max = 4000; // 2N up to which the first orbit uses the dense SVD start solver
  MatrixFreePC mf_pc = MatrixFreePC::Parametric;
  PetscReal parametric_weight = 0.95; // scale of the 2 omega term in -nnm_mf_pc parametric (linear_monodromy_pc.hpp)
  PetscReal orbit_rtol = 0;           // Newton also converged once |F| <= orbit_rtol |z0| (0: off)
};
PetscErrorCode ShootingOptionsFromOptions(MPI_Comm comm, ShootingOptions *o);

class ShootingSolver {
public:
  PetscErrorCode Setup(ShootingSystem &sys, const ShootingOptions &o);

  // Newton from X (in/out). converged false when SNES failed (X then holds the last iterate).
  PetscErrorCode Solve(Vec X, bool *converged, PetscInt *its);
  // Why the last Solve stopped: SNES's reason name.
  const char *LastReason() const { return SNESConvergedReasons[reason_]; }
  // Normalised solution of J t = e_last at X, t . t_prev > 0.
  PetscErrorCode Tangent(Vec X, Vec t_prev, Vec t);
  PetscInt KrylovIterations() const { return nkrylov_; }
  // Energy-constrained solves use the start solver (SVD pseudo-inverse: a
  // branch's first orbit near the linear limit, or a Jacobian singular at the
  // solution) unless this is off: then the main solver's pivoting LU, an
  // order of magnitude cheaper at 2N = 404, for orbits whose Jacobian is
  // regular and whose guess is near (codim-2 curves of kinds 3 and 5).
  void SetEnergyStartSolver(bool on) { energy_start_ = on; }
  // Chord Newton for the next Solve by the main solver (dense route): the
  // Jacobian assembled at X (the guess, its constraint set) from the monodromy
  // S of a nearby orbit (ShootingSystem::AssembleJacobianFrom), kept while each
  // iteration cuts |F| by kChordRate, then fresh Jacobians. A chord solve that
  // fails is repeated from X by plain Newton. Saves the monodromies of a
  // solve whose guess is near an orbit whose monodromy is already known.
  PetscErrorCode SeedJacobian(Vec X, Mat S);
  bool Seedable() const { return opt_.jacobian == ShootingJacobian::Dense && !snes_mf_ && Jdense_; }
  Mat Operator() const { return Jshell_ ? Jshell_.get() : Jdense_.get(); }
  ShootingSystem &System() { return *sys_; }

  // SNES callbacks.
  PetscErrorCode Jacobian(Vec X, Mat J);                // J: the assembled or the shell Jacobian
  PetscErrorCode SnesJacobian(SNES snes, Vec X, Mat J); // Jacobian, or the chord's kept while it contracts
  PetscErrorCode PCApply(Vec r, Vec x);
  PetscErrorCode Converged(SNES snes, PetscInt it, PetscReal xnorm, PetscReal snorm, PetscReal fnorm, SNESConvergedReason *reason);

private:
  PetscErrorCode SetupDirect(KSP ksp, PC pc);
  PetscErrorCode SetupMatrixFree(KSP ksp, PC pc);
  PetscErrorCode SetupStart();
  PetscErrorCode UpdatePreconditioner();
  PetscErrorCode SolveOnce(SNES snes, Vec X);

  ShootingSystem *sys_ = nullptr;
  ShootingOptions opt_;
  OwnedSNES snes_, snes_start_;
  OwnedMat Jdense_, Jshell_;
  OwnedVec F_, rhs_, zT_;           // residual; right-hand side of the tangent solve; scratch state
  PetscBool snes_mf_ = PETSC_FALSE; // -nnm_snes_mf: finite-difference Jacobian
  bool fresh_ = false;              // the KSP holds this solve's last Jacobian
  bool energy_start_ = true;        // energy-constrained solves by the start solver (SetEnergyStartSolver)
  bool chord_ = false;              // the next or current solve keeps the seeded Jacobian (SeedJacobian)
  PetscReal chord_fnorm_ = 0;       // |F| at the chord's last iteration
  OwnedVec Xseed_;                  // the seeded solve's guess (a failed chord is repeated from it)
  PetscInt nkrylov_ = 0;            // linear iterations of all solves so far
  SNESConvergedReason reason_ = SNES_CONVERGED_ITERATING;
  PetscReal snes_atol_ = 0;              // -nnm_snes_atol of the main solver
  PetscBool ksp_atol_set_ = PETSC_FALSE; // -nnm_ksp_atol given: GMRES's atol is the user's
  PetscReal tangent_rtol_ = 1e-10;       // GMRES tolerance of the tangent solve (the configured -nnm_ksp_rtol)
  LinearMonodromyPC lin_pc_;
  StiffnessHarmonics kharm_; // K_T(u(t)) over the orbit (-nnm_mf_pc averaged, parametric)
};

} // namespace nltopo
