#pragma once
// The lattice on PETSc: a 1D DMDA over the sites (dof 1 for u-only vectors,
// dof 2 for the interleaved state z = [u_i, v_i]), the linear stiffness K and
// the state operator L = [[0, I], [-K, 0]] as AIJ matrices, and the kernels of
// model.md (cubic bond forces on ghosted local arrays, energy, tangent
// stiffness, state Jacobian). The same code runs on 1 or P ranks.
#include "core/handle.hpp"
#include "lattice/params.hpp"

namespace nltopo {

struct EnergyParts {
  PetscReal kinetic = 0, linear = 0, quartic = 0; // 1/2 v.v, 1/2 u.K u, sum_stiff Gamma d^4 / 4
  PetscReal Total() const { return kinetic + linear + quartic; }
};

class Lattice {
public:
  PetscErrorCode Setup(MPI_Comm comm, const LatticeParams &p);

  const LatticeParams &Params() const { return p_; }
  PetscInt N() const { return p_.N(); }
  MPI_Comm Comm() const { return comm_; }
  DM SiteDM() const { return da1_; }   // dof 1: u-only vectors, K
  DM StateDM() const { return da2_; }  // dof 2: z = [u, v] interleaved per site
  Mat K() const { return K_; }         // N x N linear stiffness
  Mat L() const { return L_; }         // 2N x 2N linear state operator
  PetscInt OwnedStart() const { return xs_; }
  PetscInt OwnedCount() const { return xm_; }
  bool HasCubic() const { return p_.Gamma != 0.0; }

  // Creates a matrix with the state-Jacobian pattern (same as L).
  PetscErrorCode CreateStateMatrix(Mat *A) const;

  // Adds sign * (restoring cubic acceleration) to the owned sites of f:
  //   f_i += sign * (Gamma (u_{i-1}-u_i)^3 [stiff] - Gamma (u_i-u_{i+1})^3 [stiff]),
  // i.e. sign = +1 adds -f_NL (model.md). u and f are indexed by GLOBAL site
  // index with strides su, sf (u must hold ghosts xs-1 and xs+xm).
  void AddCubicAcceleration(const PetscScalar *u, PetscInt su, PetscScalar *f, PetscInt sf) const;

  // Energy parts of the state z (global, StateDM layout); collective.
  PetscErrorCode Energy(Vec z, EnergyParts *e) const;
  // Same from a ghosted local state array indexed by global site (z[2i], z[2i+1]); local sums only.
  EnergyParts LocalEnergy(const PetscScalar *z) const;

  // Tangent stiffness K_T(u) = K + sum_stiff 3 Gamma d^2 (e_i - e_j)(e_i - e_j)^T
  // into a SiteDM matrix; u is a global SiteDM vector (NULL: K itself).
  PetscErrorCode AssembleTangentStiffness(Vec u, Mat KT) const;
  // State Jacobian A = [[0, I], [-K_T(u), 0]] at the global state z (NULL: L).
  PetscErrorCode AssembleStateJacobian(Vec z, Mat A) const;

private:
  // Row i of K_T at ghosted u (NULL: linear): coefficients of u_{i-1}, u_i, u_{i+1}.
  void TangentRow(PetscInt i, const PetscScalar *u, PetscInt su, PetscScalar c[3]) const;
  PetscErrorCode FillStiffness(const PetscScalar *u, PetscInt su, Mat M, bool state_form) const;

  MPI_Comm comm_ = MPI_COMM_NULL;
  LatticeParams p_;
  OwnedDM da1_, da2_;
  OwnedMat K_, L_;
  PetscInt xs_ = 0, xm_ = 0;
};

} // namespace nltopo
