#pragma once
// Periodic orbits by shooting on SNES (prefix -nnm_): unknowns X = (z0, T, beta)
// (2N + 2 entries; the last rank also owns T and beta), residual
//   H   = z(T; z0, beta) - z0                 (2N)
//   p   = f(z_ref) . (z0 - z_ref)             (1)  Poincare phase condition:
//         z0 lies on the section through z_ref orthogonal to the flow there,
//         which removes the time-shift freedom of autonomous orbits
//   c   = E(z0) - E_target                    (1)  on the first point, or
//   c   = t_ref . (X - X_pred)                     pseudo-arclength afterwards.
// beta is the unfolding parameter of flow.hpp (0 at every periodic orbit), so
// the system is square and regular along an NNM family.
//
// Jacobian (-nnm_jacobian): "dense" assembles [[M - I, f(z(T)), dz/dbeta],
// [f(z_ref)^T, 0, 0], [c_X^T]] from forward sensitivities (small N); "mf" is a
// MATSHELL whose product integrates one tangent-linear direction (any N;
// GMRES, preconditioned by -nnm_mf_pc: "linear" applies the exact inverse of
// M_lin - I of the linear lattice to the state rows, "averaged" the same with
// the orbit's time-averaged tangent stiffness, "parametric" adds its 2 omega
// term near the 1:1 resonance; orbits/linear_monodromy_pc.hpp);
// -nnm_snes_mf gives finite differences.
#include "orbits/flow.hpp"
#include "orbits/linear_monodromy_pc.hpp"
#include <string>
#include <vector>

namespace nltopo {

enum class ShootingJacobian { Dense = 0, MatrixFree = 1 };
enum class MatrixFreePC { None = 0, Linear = 1, Averaged = 2, Parametric = 3 };

struct ShootingOptions {
  ShootingJacobian jacobian = ShootingJacobian::Dense;
  PetscInt start_dense_max = 4000; // 2N up to which the first orbit uses the dense SVD start solver
  MatrixFreePC mf_pc = MatrixFreePC::Parametric;
  PetscReal parametric_weight = 0.95; // scale of the 2 omega term in -nnm_mf_pc parametric (linear_monodromy_pc.hpp)
  PetscReal orbit_rtol = 0; // Newton also converged once |F| <= orbit_rtol |z0| (0: off)
};
PetscErrorCode ShootingOptionsFromOptions(MPI_Comm comm, ShootingOptions *o);

class Shooting {
public:
  PetscErrorCode Setup(PeriodicFlow &flow, const ShootingOptions &o);

  PetscErrorCode CreateUnknowns(Vec *X) const;
  PetscErrorCode Pack(Vec z, PetscReal T, PetscReal beta, Vec X) const;
  PetscErrorCode Unpack(Vec X, Vec z, PetscReal *T, PetscReal *beta) const;

  // Constraint for the next solve.
  PetscErrorCode SetEnergyConstraint(Vec zref, PetscReal energy);
  PetscErrorCode SetArclengthConstraint(Vec zref, Vec tangent, Vec Xpred);
  PetscErrorCode SetPeriodConstraint(Vec zref, PetscReal period); // the orbit of a given period

  // Newton from X (in/out). converged false when SNES failed (X then holds the last iterate).
  PetscErrorCode Solve(Vec X, bool *converged, PetscInt *its);
  // Why the last Solve stopped: SNES's reason name, e.g. DIVERGED_LINEAR_SOLVE
  // (GMRES hit -nnm_ksp_max_it) or DIVERGED_MAX_IT (-nnm_snes_max_it).
  const char *LastReason() const { return SNESConvergedReasons[reason_]; }
  // Tangent of the family at the last solution: J t = e_last with the last
  // Jacobian (dense route) or a fresh solve (mf route); normalised, t . t_prev > 0.
  PetscErrorCode Tangent(Vec X, Vec t_prev, Vec t);

  PeriodicFlow &Flow() { return *flow_; }
  PetscInt JacobianEvaluations() const { return njac_; }
  PetscInt ResidualEvaluations() const { return nres_; }
  PetscInt TangentProducts() const { return nlin_; } // matrix-free Jacobian products
  PetscInt KrylovIterations() const { return nkrylov_; } // linear iterations of all solves so far
  Mat Operator() const { return Jshell_ ? Jshell_.get() : Jdense_.get(); } // the main solver's Jacobian

  // SNES callbacks.
  PetscErrorCode InDomain(Vec X, PetscBool *ok); // T > 0 (collective)
  PetscErrorCode Residual(Vec X, Vec F);
  PetscErrorCode Jacobian(Vec X, Mat J);
  PetscErrorCode ShellMult(Vec x, Vec y);
  PetscErrorCode PCApply(Vec r, Vec x);
  // SNESConvergedDefault, plus |F| <= -nnm_orbit_rtol |z0|; on the mf route
  // it also keeps GMRES's atol at half of the threshold in force.
  PetscErrorCode Converged(SNES snes, PetscInt it, PetscReal xnorm, PetscReal snorm, PetscReal fnorm, SNESConvergedReason *reason);

private:

  PeriodicFlow *flow_ = nullptr;
  const Lattice *lat_ = nullptr;
  ShootingOptions opt_;
  PetscMPIInt rank_ = 0, size_ = 1;
  PetscInt n_ = 0, nlocx_ = 0; // 2N, local size of X
  OwnedSNES snes_, snes_start_;
  OwnedMat Jdense_, Jshell_, S_;
  OwnedVec z_, zT_, fref_, zref_, g_, tan_, Xpred_, work_, w_, F_;
  PetscErrorCode SetBorderRows(Mat J);
  PetscErrorCode SetPhaseReference(Vec zref);
  PetscBool snes_mf_ = PETSC_FALSE;          // -nnm_snes_mf: finite-difference Jacobian
  enum class Constraint { Energy, Arclength, Period } kind_ = Constraint::Energy;
  PetscReal period_target_ = 0;
  bool fresh_ = false; // fresh_: the KSP holds this solve's last Jacobian
  PetscReal energy_target_ = 0;
  // linearisation point of the matrix-free product
  OwnedVec zlin_;
  OwnedVec fT_; // the dense route's T column, f_beta(z(T))
  PetscReal Tlin_ = 0, blin_ = 0;
  std::vector<PetscReal> fr_, cr_; // gathered phase and constraint rows
  PetscInt njac_ = 0, nres_ = 0, nlin_ = 0, nkrylov_ = 0;
  SNESConvergedReason reason_ = SNES_CONVERGED_ITERATING;
  PetscReal snes_atol_ = 0;         // -nnm_snes_atol of the main solver
  PetscBool ksp_atol_set_ = PETSC_FALSE; // -nnm_ksp_atol given: GMRES's atol is the user's
  PetscReal tangent_rtol_ = 1e-10; // GMRES tolerance of the tangent solve (the configured -nnm_ksp_rtol)
  LinearMonodromyPC lin_pc_;
  StiffnessHarmonics kharm_; // K_T(u(t)) over the orbit (-nnm_mf_pc averaged, parametric)
};

} // namespace nltopo
