#pragma once
// The flow of the free lattice over one period, for periodic orbits (NNMs):
//   z' = f(z) + beta grad E(z),   grad E = [K u + f_NL(u), v] = [-f_v, f_u],
// where beta is the unfolding parameter of Munoz-Almaraz et al. (Physica D 181,
// 2003): E is conserved by f, so dE/dt = beta |grad E|^2 and periodic orbits
// exist only at beta = 0; as an unknown it makes the shooting system square and
// regular along a family of orbits.
//
// Integration uses PETSc TS (prefix -nnm_ts_) with FIXED steps dt = T / n:
// PETSc 3.18's forward sensitivities are wrong with adaptive RK (guide
// section b), and fixed steps make the flow a smooth function of T. By default
// (-nnm_ts_type symsplit, scheme bm4) the flow is a symplectic splitting and
// beta enters as one map at the end (orbits/variational_symplectic.hpp): the
// monodromy at beta = 0 is then symplectic to rounding. -nnm_ts_type rk (5dp
// unless -nnm_ts_rk_type) integrates the state and variational equations.
// The monodromy and the beta column come from TS forward sensitivities with
// the assembled state Jacobian (the "dense" route), or one tangent direction at
// a time (the "matrix-free" route).
#include "effects/rhs.hpp"
#include "orbits/variational.hpp"
#include "orbits/variational_symplectic.hpp"
#include <memory>
#include <vector>

namespace nltopo {

enum class MonodromyRoute { Variational = 0, TSForward = 1 };

// The tangent stiffness along a periodic orbit (period T, w = 2 pi / T, t from
// z0), to its 2 w harmonic: K_T(u(t)) ~ K0 + Kc cos(2 w t) + Ks sin(2 w t).
// Tridiagonal (nearest-neighbour chain), owned rows: d*[i - xs] = (i, i),
// o*[i - xs] = (i, i + 1). K0 = <K_T>; Kc, Ks = (2/T) int K_T cos, sin(2 w t) dt,
// filled only when `parametric` is set.
struct StiffnessHarmonics {
  std::vector<PetscReal> d0, o0, dc, oc, ds, os;
  bool parametric = false;
};

struct FlowOptions {
  PetscInt steps = 128; // fixed steps per period
  MonodromyRoute route = MonodromyRoute::Variational;
};
PetscErrorCode FlowOptionsFromOptions(MPI_Comm comm, FlowOptions *o);

class PeriodicFlow {
public:
  ~PeriodicFlow();
  // fx: the scene's effects, conservative (kept by reference).
  PetscErrorCode Setup(const EffectList &fx, const FlowOptions &o);

  // zT = z(T; z0, beta).
  PetscErrorCode Integrate(Vec z0, PetscReal T, PetscReal beta, Vec zT);
  // Also S = [dz(T)/dz0 | dz(T)/dbeta] (dense 2N x (2N+1), from CreateSensitivityMatrix).
  PetscErrorCode IntegrateWithMonodromy(Vec z0, PetscReal T, PetscReal beta, Vec zT, Mat S);
  // Also w = dz(T)/dz0 dz + dz(T)/dbeta dbeta + dz(T)/dT dT (one tangent-linear
  // direction). On the variational route (default) w is the exact derivative of
  // the fixed-step discrete map, T column included (variational.hpp); on the
  // TSForward route the T column is f_beta(z(T)).
  PetscErrorCode IntegrateWithTangent(Vec z0, PetscReal T, PetscReal beta, Vec dz, PetscReal dbeta, PetscReal dT, Vec zT, Vec w);
  // Blocked products: w[j] = dz(T)/dz0 dz[j] for s = dz.size() start vectors
  // (w preallocated like z0), with dbeta = dT = 0: the single version's w with
  // its beta and T sources zero, B_beta's derivative applied at beta (at
  // beta = 0, w[j] = M dz[j]). On the symplectic route one pass over the orbit
  // integrates all s columns, sharing the orbit state and K_T(u) (issue 35,
  // item 5); on the other routes it is s single products.
  PetscErrorCode IntegrateWithTangents(Vec z0, PetscReal T, PetscReal beta, const std::vector<Vec> &dz, Vec zT, std::vector<Vec> &w);
  // Integrate, and also the harmonics of the tangent stiffness K_T(u(t)) along
  // the orbit (h->parametric chooses whether the 2 w ones too). The trapezoidal
  // rule on the fixed steps is spectrally accurate for a periodic orbit.
  PetscErrorCode IntegrateAveragingStiffness(Vec z0, PetscReal T, PetscReal beta, Vec zT, StiffnessHarmonics *h);
  PetscErrorCode CreateSensitivityMatrix(Mat *S) const;

  // f(z) of the free lattice (beta = 0) and grad E(z).
  PetscErrorCode Field(Vec z, Vec f);
  PetscErrorCode GradEnergy(Vec z, Vec g);

  const Lattice &Lat() const { return *lat_; }
  const EffectList &Effects() const { return *fx_; }
  // The orbits integrated are m times as long as the family's the step size
  // was chosen for (a period-doubled family, -cont_switch at a period
  // doubling: m = 2): every integration takes m times -nnm_steps_per_period
  // steps, so the doubled orbit has its parent's step size and the parent's
  // orbit traversed m times is a fixed point of the same discrete map.
  // A divisor d > 1 integrates 1/d of the family's period with the same step
  // size (the half period of an orbit with a half-period symmetry); the steps
  // must divide by it.
  void SetPeriodMultiple(PetscInt m, PetscInt d = 1) { multiple_ = m, divisor_ = d; }
  PetscInt PeriodMultiple() const { return multiple_; }
  PetscInt PeriodDivisor() const { return divisor_; }
  PetscInt Steps() const { return opt_.steps * multiple_ / divisor_; } // fixed steps per integrated period
  // The symplectic route (-nnm_ts_type symsplit): Floquet multipliers are
  // taken at beta = 0, where the discrete monodromy is exactly symplectic.
  bool Symplectic() const { return symplectic_; }
  // The beta the monodromy of a converged orbit is taken at: 0 on the
  // symplectic route (Newton leaves |beta| ~ its tolerance, and B_beta's
  // derivative would move det M off 1 by ~ beta T tr Hess E), else beta.
  PetscReal FloquetBeta(PetscReal beta) const { return symplectic_ ? 0.0 : beta; }

  // TS callbacks (public for the C trampolines).
  PetscErrorCode EvalRhs(PetscReal t, Vec z, Vec f);
  PetscErrorCode EvalJacobian(Vec z, Mat A);
  PetscErrorCode EvalJacobianP(Vec z, Mat Jp);
  PetscErrorCode AccumulateStiffness(PetscInt step, Vec z);

private:
  PetscReal beta_ = 0; // the unfolding parameter of the integration under way
  PetscErrorCode CreateTS(TS *ts, Mat jacp);
  PetscErrorCode Run(TS ts, Vec z0, PetscReal T, Vec zT);
  PetscErrorCode Unfold(Vec zT, PetscReal T, PetscReal beta); // zT += beta T grad E(zT) (symplectic route)

  const EffectList *fx_ = nullptr;
  const Lattice *lat_ = nullptr;
  FlowOptions opt_;
  std::unique_ptr<Rhs> rhs_;
  OwnedTS ts_, ts_mono_, ts_tlm_;
  OwnedMat J_, Jp_mono_, Jp_tlm_, S_tlm_;
  std::unique_ptr<VariationalFlow> var_dense_, var_tlm_; // created on first use
  std::unique_ptr<SymplecticVariationalFlow> sym_dense_, sym_tlm_;
  std::unique_ptr<SymplecticVariationalFlow> sym_block_; // IntegrateWithTangents: set up for the last block size
  PetscInt sym_block_cols_ = 0;
  bool symplectic_ = false;
  PetscInt multiple_ = 1, divisor_ = 1; // SetPeriodMultiple
  OwnedVec wb_;
  StiffnessHarmonics *harm_ = nullptr; // set while averaging K_T
  std::vector<PetscScalar> kd_, kb_;   // K_T at one step of the averaging (scratch)
};

// SetPeriodMultiple for one scope (a period-doubled family; a half period),
// restored on leaving it.
class PeriodMultipleScope {
public:
  PeriodMultipleScope(PeriodicFlow &flow, PetscInt m, PetscInt d = 1) : flow_(flow), saved_(flow.PeriodMultiple()), saved_d_(flow.PeriodDivisor())
  {
    flow.SetPeriodMultiple(m, d);
  }
  ~PeriodMultipleScope() { flow_.SetPeriodMultiple(saved_, saved_d_); }
  PeriodMultipleScope(const PeriodMultipleScope &) = delete;
  PeriodMultipleScope &operator=(const PeriodMultipleScope &) = delete;

private:
  PeriodicFlow &flow_;
  PetscInt saved_, saved_d_;
};

} // namespace nltopo
