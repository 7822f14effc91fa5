#pragma once
// Periodic orbits by shooting: the system (orbits/shooting_system.hpp:
// unknowns X = (z0, T, beta), residual, constraints, Jacobian) and Newton on it
// (orbits/shooting_solver.hpp: options -nnm_*, the dense, matrix-free and
// start strategies), behind the one interface the continuation and the
// studies use.
#include "orbits/shooting_solver.hpp"

namespace nltopo {

class Shooting {
public:
  PetscErrorCode Setup(PeriodicFlow &flow, const ShootingOptions &o)
  {
    PetscFunctionBeginUser;
    PetscCall(system_.Setup(flow));
    PetscCall(solver_.Setup(system_, o));
    PetscFunctionReturn(0);
  }

  PetscErrorCode CreateUnknowns(Vec *X) const { return system_.CreateUnknowns(X); }
  PetscErrorCode Pack(Vec z, PetscReal T, PetscReal beta, Vec X) const { return system_.Pack(z, T, beta, X); }
  PetscErrorCode Unpack(Vec X, Vec z, PetscReal *T, PetscReal *beta) const { return system_.Unpack(X, z, T, beta); }

  // Constraint for the next solve.
  PetscErrorCode SetEnergyConstraint(Vec zref, PetscReal energy) { return system_.SetEnergyConstraint(zref, energy); }
  PetscErrorCode SetArclengthConstraint(Vec zref, Vec tangent, Vec Xpred) { return system_.SetArclengthConstraint(zref, tangent, Xpred); }
  PetscErrorCode SetPeriodConstraint(Vec zref, PetscReal period) { return system_.SetPeriodConstraint(zref, period); } // the orbit of a given period

  // Newton from X (in/out). converged false when SNES failed (X then holds the last iterate).
  PetscErrorCode Solve(Vec X, bool *converged, PetscInt *its) { return solver_.Solve(X, converged, its); }
  // Energy-constrained solves by the start solver (default) or the main solver's LU (ShootingSolver::SetEnergyStartSolver).
  void SetEnergyStartSolver(bool on) { solver_.SetEnergyStartSolver(on); }
  // Chord Newton for the next solve from the monodromy S of a nearby orbit (ShootingSolver::SeedJacobian; Seedable: the dense route).
  PetscErrorCode SeedJacobian(Vec X, Mat S) { return solver_.SeedJacobian(X, S); }
  bool Seedable() const { return solver_.Seedable(); }
  // Why the last Solve stopped: SNES's reason name, e.g. DIVERGED_LINEAR_SOLVE
  // (GMRES hit -nnm_ksp_max_it) or DIVERGED_MAX_IT (-nnm_snes_max_it).
  const char *LastReason() const { return solver_.LastReason(); }
  // Tangent of the family at the last solution: J t = e_last with the last
  // Jacobian (dense route) or a fresh solve (mf route); normalised, t . t_prev > 0.
  PetscErrorCode Tangent(Vec X, Vec t_prev, Vec t) { return solver_.Tangent(X, t_prev, t); }

  PeriodicFlow &Flow() { return system_.Flow(); }
  PetscInt JacobianEvaluations() const { return system_.JacobianEvaluations(); }
  PetscInt ResidualEvaluations() const { return system_.ResidualEvaluations(); }
  PetscInt TangentProducts() const { return system_.TangentProducts(); }   // matrix-free Jacobian products
  PetscInt KrylovIterations() const { return solver_.KrylovIterations(); } // linear iterations of all solves so far

  // The residual, and the main solver's Jacobian (Operator) evaluated at X.
  PetscErrorCode Residual(Vec X, Vec F) { return system_.Residual(X, F); }
  PetscErrorCode Jacobian(Vec X, Mat J) { return solver_.Jacobian(X, J); }
  Mat Operator() const { return solver_.Operator(); }

private:
  ShootingSystem system_;
  ShootingSolver solver_;
};

} // namespace nltopo
