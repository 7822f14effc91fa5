#include "lattice/lattice.hpp"
#include "core/log.hpp"
#include <petscdmda.h>

namespace nltopo {

PetscErrorCode Lattice::Setup(MPI_Comm comm, const LatticeParams &p)
{
  PetscMPIInt size;
  PetscFunctionBeginUser;
  PetscCall(LogRegister());
  comm_ = comm;
  p_ = p;
  const PetscInt N = p.N();
  PetscCallMPI(MPI_Comm_size(comm, &size));
  PetscCheck(N >= size, comm, PETSC_ERR_USER, "-lattice_cells %" PetscInt_FMT " gives N = %" PetscInt_FMT " sites, fewer than the %d MPI ranks",
             p.cells, N, (int)size);
  PetscCall(DMDACreate1d(comm, DM_BOUNDARY_NONE, N, 2, 1, NULL, da2_.out()));
  PetscCall(DMSetUp(da2_));
  PetscCall(DMDASetFieldName(da2_, 0, "u"));
  PetscCall(DMDASetFieldName(da2_, 1, "v"));
  PetscCall(DMDACreateCompatibleDMDA(da2_, 1, da1_.out()));
  PetscCall(DMDAGetCorners(da1_, &xs_, NULL, NULL, &xm_, NULL, NULL));

  PetscCall(DMCreateMatrix(da1_, K_.out()));
  PetscCall(PetscObjectSetName((PetscObject)K_.get(), "K"));
  PetscCall(AssembleTangentStiffness(NULL, K_));
  PetscCall(CreateStateMatrix(L_.out()));
  PetscCall(PetscObjectSetName((PetscObject)L_.get(), "L"));
  PetscCall(AssembleStateJacobian(NULL, L_));
  PetscFunctionReturn(0);
}

PetscErrorCode Lattice::CreateStateMatrix(Mat *A) const
{
  PetscFunctionBeginUser;
  // Exact pattern (PETSc ordering of a 1D DMDA is natural: row 2i is u_i, 2i+1
  // is v_i): u_i' = v_i, v_i' couples to u_{i-1}, u_i, u_{i+1}; both diagonals
  // are stored (as zeros) so implicit TS types can shift the matrix.
  PetscCall(MatCreateAIJ(comm_, 2 * xm_, 2 * xm_, 2 * p_.N(), 2 * p_.N(), 4, NULL, 1, NULL, A));
  PetscCall(MatSetOption(*A, MAT_NEW_NONZERO_ALLOCATION_ERR, PETSC_TRUE));
  PetscFunctionReturn(0);
}

void Lattice::AddCubicAcceleration(const PetscScalar *u, PetscInt su, PetscScalar *f, PetscInt sf) const
{
  const PetscReal G = p_.Gamma;
  const PetscInt N = p_.N();
  for (PetscInt i = xs_; i < xs_ + xm_; i++) {
    PetscScalar a = 0;
    if (i > 0 && p_.Stiff(i - 1)) {
      const PetscScalar d = u[(i - 1) * su] - u[i * su];
      a += G * d * d * d;
    }
    if (i < N - 1 && p_.Stiff(i)) {
      const PetscScalar d = u[i * su] - u[(i + 1) * su];
      a -= G * d * d * d;
    }
    f[i * sf] += a;
  }
}

EnergyParts Lattice::LocalEnergy(const PetscScalar *z) const
{
  EnergyParts e;
  const PetscReal G = p_.Gamma, kh = p_.KHat();
  const PetscInt N = p_.N();
  for (PetscInt i = xs_; i < xs_ + xm_; i++) {
    const PetscScalar u = z[2 * i], v = z[2 * i + 1];
    e.kinetic += 0.5 * v * v;
    e.linear += 0.5 * kh * u * u;
    if (i < N - 1) { // bond i is owned by the rank owning site i
      const PetscScalar un = z[2 * i + 2];
      e.linear -= p_.Bond(i) * u * un; // 1/2 u.K u: the two off-diagonal entries of bond i
      if (p_.Stiff(i)) {
        const PetscScalar d = u - un;
        e.quartic += 0.25 * G * d * d * d * d;
      }
    }
  }
  return e;
}

PetscErrorCode Lattice::Energy(Vec z, EnergyParts *e) const
{
  const PetscScalar *a;
  EnergyParts loc;
  PetscMPIInt size;
  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(Log().energy, 0, 0, 0, 0));
  PetscCallMPI(MPI_Comm_size(comm_, &size));
  if (size == 1) { // one rank: the global array holds every neighbour
    PetscCall(VecGetArrayRead(z, &a));
    loc = LocalEnergy(a);
    PetscCall(VecRestoreArrayRead(z, &a));
    *e = loc;
  } else {
    Vec zl;
    PetscInt gxs;
    PetscCall(DMGetLocalVector(da2_, &zl));
    PetscCall(DMGlobalToLocalBegin(da2_, z, INSERT_VALUES, zl));
    PetscCall(DMGlobalToLocalEnd(da2_, z, INSERT_VALUES, zl));
    PetscCall(DMDAGetGhostCorners(da2_, &gxs, NULL, NULL, NULL, NULL, NULL));
    PetscCall(VecGetArrayRead(zl, &a));
    loc = LocalEnergy(a - 2 * gxs);
    PetscCall(VecRestoreArrayRead(zl, &a));
    PetscCall(DMRestoreLocalVector(da2_, &zl));
    PetscReal in[3] = {loc.kinetic, loc.linear, loc.quartic}, out[3];
    PetscCall(MPIU_Allreduce(in, out, 3, MPIU_REAL, MPIU_SUM, comm_));
    e->kinetic = out[0];
    e->linear = out[1];
    e->quartic = out[2];
  }
  PetscCall(PetscLogEventEnd(Log().energy, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

void Lattice::TangentRow(PetscInt i, const PetscScalar *u, PetscInt su, PetscScalar c[3]) const
{
  const PetscInt N = p_.N();
  c[0] = c[2] = 0;
  c[1] = p_.KHat();
  if (i > 0) {
    c[0] = -p_.Bond(i - 1);
    if (u && p_.Stiff(i - 1)) {
      const PetscScalar d = u[(i - 1) * su] - u[i * su], s = 3 * p_.Gamma * d * d;
      c[0] -= s;
      c[1] += s;
    }
  }
  if (i < N - 1) {
    c[2] = -p_.Bond(i);
    if (u && p_.Stiff(i)) {
      const PetscScalar d = u[i * su] - u[(i + 1) * su], s = 3 * p_.Gamma * d * d;
      c[2] -= s;
      c[1] += s;
    }
  }
}

PetscErrorCode Lattice::FillStiffness(const PetscScalar *u, PetscInt su, Mat M, bool state_form) const
{
  const PetscInt N = p_.N();
  PetscFunctionBeginUser;
  PetscCall(MatZeroEntries(M));
  for (PetscInt i = xs_; i < xs_ + xm_; i++) {
    PetscScalar c[3];
    TangentRow(i, u, su, c);
    PetscInt cols[3], nc = 0;
    PetscScalar vals[3];
    for (PetscInt o = -1; o <= 1; o++) {
      const PetscInt j = i + o;
      if (j < 0 || j >= N) continue;
      cols[nc] = state_form ? 2 * j : j;
      vals[nc] = state_form ? -c[o + 1] : c[o + 1];
      nc++;
    }
    if (state_form) {
      const PetscInt ru = 2 * i, rv = 2 * i + 1, cu[2] = {2 * i, 2 * i + 1};
      const PetscScalar uvals[2] = {0.0, 1.0}, zero = 0.0;
      PetscCall(MatSetValues(M, 1, &ru, 2, cu, uvals, INSERT_VALUES)); // u' = v
      PetscCall(MatSetValues(M, 1, &rv, nc, cols, vals, INSERT_VALUES)); // v' = -K_T u
      PetscCall(MatSetValues(M, 1, &rv, 1, &rv, &zero, INSERT_VALUES)); // stored diagonal
    } else {
      PetscCall(MatSetValues(M, 1, &i, nc, cols, vals, INSERT_VALUES));
    }
  }
  PetscCall(MatAssemblyBegin(M, MAT_FINAL_ASSEMBLY));
  PetscCall(MatAssemblyEnd(M, MAT_FINAL_ASSEMBLY));
  PetscFunctionReturn(0);
}

PetscErrorCode Lattice::AssembleTangentStiffness(Vec u, Mat KT) const
{
  PetscFunctionBeginUser;
  if (!u || !HasCubic()) {
    PetscCall(FillStiffness(NULL, 1, KT, false));
    PetscFunctionReturn(0);
  }
  Vec ul;
  const PetscScalar *a;
  PetscInt gxs;
  PetscCall(DMGetLocalVector(da1_, &ul));
  PetscCall(DMGlobalToLocalBegin(da1_, u, INSERT_VALUES, ul));
  PetscCall(DMGlobalToLocalEnd(da1_, u, INSERT_VALUES, ul));
  PetscCall(DMDAGetGhostCorners(da1_, &gxs, NULL, NULL, NULL, NULL, NULL));
  PetscCall(VecGetArrayRead(ul, &a));
  PetscCall(FillStiffness(a - gxs, 1, KT, false));
  PetscCall(VecRestoreArrayRead(ul, &a));
  PetscCall(DMRestoreLocalVector(da1_, &ul));
  PetscFunctionReturn(0);
}

PetscErrorCode Lattice::AssembleStateJacobian(Vec z, Mat A) const
{
  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(Log().jacobian, 0, 0, 0, 0));
  if (!z || !HasCubic()) {
    PetscCall(FillStiffness(NULL, 2, A, true));
  } else {
    Vec zl;
    const PetscScalar *a;
    PetscInt gxs;
    PetscCall(DMGetLocalVector(da2_, &zl));
    PetscCall(DMGlobalToLocalBegin(da2_, z, INSERT_VALUES, zl));
    PetscCall(DMGlobalToLocalEnd(da2_, z, INSERT_VALUES, zl));
    PetscCall(DMDAGetGhostCorners(da2_, &gxs, NULL, NULL, NULL, NULL, NULL));
    PetscCall(VecGetArrayRead(zl, &a));
    PetscCall(FillStiffness(a - 2 * gxs, 2, A, true));
    PetscCall(VecRestoreArrayRead(zl, &a));
    PetscCall(DMRestoreLocalVector(da2_, &zl));
  }
  PetscCall(PetscLogEventEnd(Log().jacobian, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

} // namespace nltopo
