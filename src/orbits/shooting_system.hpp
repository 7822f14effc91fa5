#pragma once
// The shooting system of a periodic orbit: unknowns X = (z0, T, beta) (2N + 2
// entries; the last rank also owns T and beta), residual
//   H   = z(T; z0, beta) - z0                 (2N)
//   p   = f(z_ref) . (z0 - z_ref)             (1)  Poincare phase condition:
//         z0 lies on the section through z_ref orthogonal to the flow there,
//         which removes the time-shift freedom of autonomous orbits
//   c   = E(z0) - E_target                    (1)  on the first point, or
//   c   = t_ref . (X - X_pred)                     pseudo-arclength afterwards, or
//   c   = T - T_target                             the orbit of a given period.
// beta is the unfolding parameter of flow.hpp (0 at every periodic orbit), so
// the system is square and regular along an NNM family.
//
// Its Jacobian [[M - I, dz(T)/dT, dz(T)/dbeta], [f(z_ref)^T, 0, 0], [c_X^T]]
// (M the monodromy) is either assembled from forward sensitivities
// (AssembleJacobian, small N) or applied one tangent-linear integration per
// product at the point of the last Linearise (ShellMult, any N). How the system
// is solved: orbits/shooting_solver.hpp.
#include "orbits/flow.hpp"
#include <vector>

namespace nltopo {

// Refuses a dense shooting Jacobian of a lattice of `sites` sites (rows of
// this rank: `local_rows` of X) that would not fit in memory. Called before
// any work that precedes the Jacobian (NnmSetup::Build), and again when it
// is created.
PetscErrorCode CheckDenseJacobianMemory(MPI_Comm comm, PetscInt sites, PetscInt local_rows);

class ShootingSystem {
public:
  PetscErrorCode Setup(PeriodicFlow &flow);

  PetscErrorCode CreateUnknowns(Vec *X) const;
  PetscErrorCode Pack(Vec z, PetscReal T, PetscReal beta, Vec X) const;
  PetscErrorCode Unpack(Vec X, Vec z, PetscReal *T, PetscReal *beta) const;
  // x's phase and constraint entries (2N, 2N + 1) copied to y's.
  PetscErrorCode CopyBorder(Vec x, Vec y) const;
  // |z0| of X (collective).
  PetscErrorCode StateNorm(Vec X, PetscReal *norm) const;

  // Constraint for the next solve; each also sets the phase reference z_ref.
  PetscErrorCode SetEnergyConstraint(Vec zref, PetscReal energy) { return SetTargetConstraint(zref, Constraint::Energy, energy); }
  PetscErrorCode SetArclengthConstraint(Vec zref, Vec tangent, Vec Xpred);
  PetscErrorCode SetPeriodConstraint(Vec zref, PetscReal period) { return SetTargetConstraint(zref, Constraint::Period, period); }
  bool EnergyConstrained() const { return kind_ == Constraint::Energy; }

  PetscErrorCode InDomain(Vec X, PetscBool *ok); // T > 0 (collective)
  PetscErrorCode Residual(Vec X, Vec F);

  // The assembled Jacobian: a dense-pattern AIJ matrix (refused when it would
  // not fit in memory, CheckDenseJacobianMemory), filled at X by AssembleJacobian.
  PetscErrorCode CreateDenseJacobian(Mat *J);
  PetscErrorCode AssembleJacobian(Vec X, Mat J);
  // The same at X with a given monodromy S (from CreateSensitivityMatrix, of a
  // nearby orbit, possibly at another parameter value) instead of X's own: a
  // chord Jacobian for ShootingSolver::SeedJacobian. One trajectory, no
  // sensitivities; not counted as a Jacobian evaluation.
  PetscErrorCode AssembleJacobianFrom(Vec X, Mat S, Mat J);
  // The matrix-free Jacobian: a MATSHELL whose product (ShellMult) is taken at
  // the point of the last Linearise.
  PetscErrorCode CreateShellJacobian(Mat *J);
  PetscErrorCode Linearise(Vec X);
  PetscErrorCode ShellMult(Vec x, Vec y);
  Vec LinearisationState() const { return zlin_; }
  PetscReal LinearisationPeriod() const { return Tlin_; }
  PetscReal LinearisationBeta() const { return blin_; }

  PeriodicFlow &Flow() { return *flow_; }
  const Lattice &Lat() const { return *lat_; }
  PetscInt Size() const { return n_ + 2; } // global length of X
  PetscInt JacobianEvaluations() const { return njac_; }
  PetscInt ResidualEvaluations() const { return nres_; }
  PetscInt TangentProducts() const { return nlin_; }

private:
  enum class Constraint { Energy, Arclength, Period };
  PetscErrorCode SetPhaseReference(Vec zref);
  PetscErrorCode SetTargetConstraint(Vec zref, Constraint kind, PetscReal target); // c = E(z0) - target or T - target
  PetscErrorCode GatherBorderRows(Vec X, PetscReal *T, PetscReal *beta);
  PetscErrorCode SetBorderRows(Mat J);
  PetscErrorCode FillJacobian(Mat S, Mat J); // J from S, fT_ and the gathered border rows
  PetscErrorCode SetRows(Vec a, Vec b, PetscReal p, PetscReal c, Vec y) const;

  PeriodicFlow *flow_ = nullptr;
  const Lattice *lat_ = nullptr;
  PetscMPIInt rank_ = 0, size_ = 1;
  PetscInt n_ = 0, nlocx_ = 0; // 2N, local size of X
  OwnedMat S_;                 // [dz(T)/dz0 | dz(T)/dbeta] of the assembled Jacobian
  OwnedVec z_, zT_, fref_, zref_, g_, tan_, Xpred_, work_, w_;
  Constraint kind_ = Constraint::Energy;
  PetscReal target_ = 0; // E_target or T_target
  OwnedVec zlin_;        // linearisation point of the matrix-free product
  OwnedVec fT_;          // the assembled T column, f_beta(z(T))
  PetscReal Tlin_ = 0, blin_ = 0;
  std::vector<PetscReal> fr_, cr_; // gathered phase and constraint rows
  PetscInt njac_ = 0, nres_ = 0, nlin_ = 0;
};

} // namespace nltopo
