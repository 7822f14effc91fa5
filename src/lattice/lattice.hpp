#pragma once
// The lattice on PETSc: a 1D DMDA over the sites (dof 1: u-only vectors, ghost
// exchange, K), the linear stiffness K and the state operator
// L = [[0, I], [-K, 0]] as AIJ matrices, and the kernels of model.md (cubic
// bond forces on ghosted local arrays, energy, tangent stiffness, state
// Jacobian). The same code runs on 1 or P ranks.
//
// State layout: z = [u, v] with each rank owning [u_local | v_local] for its
// sites (on one rank exactly [u_1..u_N, v_1..v_N]). Both halves are
// contiguous per rank, so the u and v parts are zero-copy sub-vectors (the
// position/momentum split of symplectic TS) with the SiteDM layout.
#include "core/handle.hpp"
#include "lattice/params.hpp"
#include <vector>

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
  DM SiteDM() const { return da_; }    // u-only vectors and K
  Mat K() const { return K_; }         // N x N linear stiffness
  Mat L() const { return L_; }         // 2N x 2N linear state operator
  PetscInt OwnedStart() const { return xs_; }
  PetscInt OwnedCount() const { return xm_; }
  bool HasCubic() const { return p_.Gamma != 0.0; }
  bool Serial() const { return size_ == 1; }

  PetscErrorCode CreateStateVector(Vec *z) const;
  PetscErrorCode CreateStateMatrix(Mat *A) const; // the pattern of L / the state Jacobian
  IS PositionIS() const { return is_u_; }         // global indices of the u part
  IS MomentumIS() const { return is_v_; }         // global indices of the v part
  PetscInt StateIndexU(PetscInt site) const;      // global state index of u_site
  PetscInt StateIndexV(PetscInt site) const { return StateIndexU(site) + OwnerCount(site); }

  // Ghosted local array of the u part of x (a state vector or a SiteDM vector),
  // indexed by GLOBAL site (valid for xs-1 .. xs+xm). Serial: x's own array,
  // no copy (*ul = NULL). Pair every Get with a Restore of the same arguments.
  PetscErrorCode GetGhostedU(Vec x, Vec *ul, const PetscScalar **u) const;
  PetscErrorCode RestoreGhostedU(Vec x, Vec *ul, const PetscScalar **u) const;

  // a[i] = -(K u)_i for owned sites i (the linear coupling as a stencil over the
  // same bond rule that assembles K); u ghosted and a indexed by global site.
  void LinearAcceleration(const PetscScalar *u, PetscScalar *a) const;
  // Adds the restoring cubic acceleration -f_NL(u) (model.md) to a[i] for owned
  // sites i; u ghosted and a indexed by global site.
  void AddCubicAcceleration(const PetscScalar *u, PetscScalar *a) const;

  // Energy parts of the state z (collective).
  PetscErrorCode Energy(Vec z, EnergyParts *e) const;

  // Tangent stiffness K_T(u) = K + sum_stiff 3 Gamma d^2 (e_i - e_j)(e_i - e_j)^T
  // into a SiteDM matrix; u a SiteDM vector (NULL: K itself).
  PetscErrorCode AssembleTangentStiffness(Vec u, Mat KT) const;
  // State Jacobian A = [[0, I], [-K_T(u), 0]] at the state z (NULL: L). With
  // beta != 0, the Jacobian (I + beta [[0, -I], [I, 0]]) A of the unfolded
  // field f + beta grad E used by the periodic-orbit solver (orbits/flow.hpp).
  PetscErrorCode AssembleStateJacobian(Vec z, Mat A, PetscReal beta = 0) const;

  // Row i of K_T(u) (u ghosted, by global site; NULL: K): coefficients of u_{i-1}, u_i, u_{i+1}.
  void TangentRow(PetscInt i, const PetscScalar *u, PetscScalar c[3]) const;

private:
  PetscInt OwnerCount(PetscInt site) const; // sites owned by the owner of site
  PetscErrorCode FillStiffness(const PetscScalar *u, Mat M, bool state_form, PetscReal beta) const;

  MPI_Comm comm_ = MPI_COMM_NULL;
  PetscMPIInt size_ = 1;
  LatticeParams p_;
  OwnedDM da_;
  OwnedMat K_, L_;
  OwnedIS is_u_, is_v_;
  PetscInt xs_ = 0, xm_ = 0;
  std::vector<PetscInt> starts_; // first site of every rank, plus N
  std::vector<PetscReal> kb_;    // k of bonds xs-1 .. xs+xm-1 (0 outside the chain): kb_[b - xs + 1]
  std::vector<PetscReal> gb_;    // Gamma of bonds xs-1 .. xs+xm-1 (0 if not stiff or outside): gb_[b - xs + 1]
  std::vector<PetscReal> kd_;    // diagonal of K at the owned sites: kd_[i - xs] (k_hat unless perturbed)
};

} // namespace nltopo
