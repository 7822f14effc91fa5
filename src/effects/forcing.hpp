#pragma once
// The Gaussian tone burst of model.md ("Forcing"):
//   F(t) = eta * S * cos(omega t) * exp(-((t - t0)/tau)^2),  tau = tau_periods * 2 pi/omega, t0 = t0_taus * tau,
// switched off for good the first time E(t) >= E*. eta is a profile vector.
#include "effects/effect.hpp"
#include <vector>

namespace nltopo {

class LinearModes;

// exponential: eta_n = a e^{b |n - m|} (-1)^{n/2} on the even sites n (1-based)
// around the interface site m, a and b fitted to the linear insulated mode
// (paper, "exponential forcing"; docs/model.md).
enum class ForceProfile { Site = 0, Mode = 1, None = 2, Exponential = 3 };

struct ToneBurstOptions {
  ForceProfile profile = ForceProfile::Site;
  PetscReal omega = 0;      // omega_ext (default sqrt(k_hat): the insulated frequency)
  PetscReal energy = 1.0;   // E*
  PetscReal amplitude = -1; // S; < 0 means "use the amplitude rule"
  PetscReal safety = 2.0;   // amplitude rule: linear burst energy = safety * E*
  PetscInt retries = 8;     // amplitude rule: repeats with a larger S when E* is missed
  PetscReal tau_periods = 25, t0_taus = 5;
  PetscInt site = -1; // 0-based forced site for profile site (default m+1)
  PetscInt mode = -1; // linear mode index for profile mode
};

PetscErrorCode ToneBurstOptionsFromOptions(MPI_Comm comm, const LatticeParams &lp, ToneBurstOptions *o);

class ToneBurst {
public:
  // Builds eta on the owned sites. modes may be NULL unless the profile or
  // the amplitude rule needs the linear modes.
  PetscErrorCode Setup(const Lattice &lat, const ToneBurstOptions &o, const LinearModes *modes);

  bool Present() const { return opt_.profile != ForceProfile::None; }
  PetscReal Omega() const { return opt_.omega; }
  PetscReal EnergyStar() const { return opt_.energy; }
  PetscReal Amplitude() const { return S_; }
  PetscReal Tau() const { return tau_; }
  PetscReal T0() const { return t0_; }
  bool AmplitudeFromRule() const { return from_rule_; }
  void ScaleAmplitude(PetscReal f) { S_ *= f; }
  const ToneBurstOptions &Options() const { return opt_; }
  // Fit of the exponential profile (0 for the other profiles).
  PetscReal ExponentialA() const { return exp_a_; }
  PetscReal ExponentialB() const { return exp_b_; }
  // The profile eta of every site (0-based), on every rank of the lattice's communicator.
  PetscErrorCode Profile(const Lattice &lat, std::vector<PetscReal> *eta) const;

  // Scalar signal S cos(omega t) exp(-((t - t0)/tau)^2).
  PetscReal Signal(PetscReal t) const;
  // a[i] += eta_i * Signal(t) on owned sites with eta_i != 0 (a indexed by global site).
  void Add(PetscReal t, PetscScalar *a) const;

private:
  ToneBurstOptions opt_;
  PetscReal S_ = 0, tau_ = 0, t0_ = 0, exp_a_ = 0, exp_b_ = 0;
  bool from_rule_ = false;
  std::vector<PetscInt> idx_; // owned sites with eta != 0 (global index)
  std::vector<PetscScalar> eta_;
};

// The tone burst as an effect: a[i] += eta_i S g(t), non-conservative, no
// tangent. The simulation switches it off at the cut-off (effects/rhs.hpp).
class ForcingEffect : public Effect {
public:
  explicit ForcingEffect(ToneBurst *b) : b_(b) {}
  const char *Name() const override { return "forcing"; }
  const char *LogName() const override { return "RhsForcing"; }
  std::string EnabledBy() const override { return "-force_profile"; }
  bool Conservative() const override { return false; }
  void AddAcceleration(PetscReal t, const PetscScalar *, const PetscScalar *, PetscScalar *a) const override { b_->Add(t, a); }
  ToneBurst *Burst() const { return b_; }

private:
  ToneBurst *b_;
};

// Amplitude rule (docs/model.md "The amplitude rule"): the energy a unit-amplitude
// burst leaves in the LINEAR lattice, e1 = sum_j (phi_j . eta)^2 pi tau^2 / 8 *
// |exp(-tau^2 (omega - omega_j)^2 / 4) + exp(-tau^2 (omega + omega_j)^2 / 4) e^{-2 i omega t0}|^2,
// plus the peak energy of the quasi-static off-resonant response; S = sqrt(safety E* / e1).
// Least-squares fit log|phi_n| = log a + b |n - m| over the even sites (1-based)
// where the insulated mode phi is not negligible.
PetscErrorCode FitExponentialProfile(const Lattice &lat, Vec insulated, PetscReal *a, PetscReal *b);

PetscReal BurstUnitEnergy(const std::vector<PetscReal> &omega_j, const std::vector<PetscReal> &proj2, PetscReal omega, PetscReal tau, PetscReal t0);

} // namespace nltopo
