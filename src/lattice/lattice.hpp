#pragma once
// The lattice on PETSc: the geometry and the springs of model.md. A 1D DMDA
// over the sites (dof 1: u-only vectors, ghost exchange), the springs of the
// linear stiffness K (bonds and diagonal, possibly perturbed), K as an AIJ
// matrix, and the assembly of nearest-neighbour operators (K, K_T, state
// Jacobians) from per-site and per-bond values. The forces, tangents and
// energies are the effects' (effects/effect.hpp). The same code runs on 1 or
// P ranks.
//
// State layout: z = [u, v] with each rank owning [u_local | v_local] for its
// sites (on one rank exactly [u_1..u_N, v_1..v_N]). Both halves are
// contiguous per rank, so the u and v parts are zero-copy sub-vectors (the
// position/momentum split of symplectic TS) with the SiteDM layout.
#include "core/handle.hpp"
#include "lattice/params.hpp"
#include <cmath>
#include <vector>

namespace nltopo {

struct EnergyParts {
  PetscReal kinetic = 0, linear = 0, quartic = 0; // 1/2 v.v, 1/2 u.K u, sum_stiff Gamma d^4 / 4
  PetscReal Total() const { return kinetic + linear + quartic; }
};

// Refuses a lattice of N sites on comm that would not fit in memory (Setup
// checks it; a study checks it from its options before any set-up, Study::CheckResources).
PetscErrorCode CheckLatticeMemory(MPI_Comm comm, PetscInt N);

class Lattice {
public:
  PetscErrorCode Setup(MPI_Comm comm, const LatticeParams &p);

  const LatticeParams &Params() const { return p_; }
  PetscInt N() const { return p_.N(); }
  MPI_Comm Comm() const { return comm_; }
  DM SiteDM() const { return da_; } // u-only vectors and K
  Mat K() const { return K_; }      // N x N linear stiffness
  PetscInt OwnedStart() const { return xs_; }
  PetscInt OwnedCount() const { return xm_; }
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

  // The springs of K: BondSprings()[b] = k of bond b for the bonds xs-1 ..
  // xs+xm-1 (0 outside the chain), DiagonalSprings()[i] = K(i, i) for the
  // owned sites (k_hat unless perturbed), both indexed globally.
  const PetscReal *BondSprings() const { return kb_.data() - xs_ + 1; }
  const PetscReal *DiagonalSprings() const { return kd_.data() - xs_; }
  // Row i (owned) of K: the coefficients of u_{i-1}, u_i, u_{i+1}.
  void KRow(PetscInt i, PetscScalar c[3]) const;

  // A nearest-neighbour operator from its values: kd[i] = M(i, i) for the
  // owned sites, kb[b] = M(b, b+1) = M(b+1, b) for the bonds xs-1 .. xs+xm-1.
  // site_form: into a SiteDM matrix. Otherwise the state form
  // (I + beta [[0, -I], [I, 0]]) [[0, I], [-M, -diag(c)]] (c NULL: 0) into a
  // matrix from CreateStateMatrix.
  PetscErrorCode AssembleNearestNeighbour(const PetscScalar *kd, const PetscScalar *kb, const PetscScalar *c, Mat M, bool site_form, PetscReal beta) const;

private:
  PetscInt OwnerCount(PetscInt site) const; // sites owned by the owner of site

  MPI_Comm comm_ = MPI_COMM_NULL;
  PetscMPIInt size_ = 1;
  LatticeParams p_;
  OwnedDM da_;
  OwnedMat K_;
  OwnedIS is_u_, is_v_;
  OwnedVec u_view_; // (ranks > 1) a site vector without an array of its own: a state vector's u part in GetGhostedU
  PetscInt xs_ = 0, xm_ = 0;
  std::vector<PetscInt> starts_; // first site of every rank, plus N
  std::vector<PetscReal> kb_;    // k of bonds xs-1 .. xs+xm-1 (0 outside the chain): kb_[b - xs + 1]
  std::vector<PetscReal> kd_;    // diagonal of K at the owned sites: kd_[i - xs] (k_hat unless perturbed)
};

// Sums over the displacement parts u, w of two states a, b (collective):
// u.w, u.u, w.w and sum u^4: the shape correlation |u.w| / (|u| |w|) and the
// MCR of u (sum u^4 / (u.u)^2, docs/model.md) come from them.
struct DisplacementSums {
  PetscReal uw = 0, uu = 0, ww = 0, u4 = 0;
  PetscReal Correlation() const { return uu > 0 && ww > 0 ? std::abs(uw) / std::sqrt(uu * ww) : 0; }
  PetscReal Mcr() const { return uu > 0 ? u4 / (uu * uu) : 0; }
};
PetscErrorCode SumDisplacements(const Lattice &lat, Vec a, Vec b, DisplacementSums *s);

} // namespace nltopo
