#include "effects/forcing.hpp"
#include "bands/linear_modes.hpp"
#include "core/gather.hpp"
#include "core/option_table.hpp"
#include <algorithm>
#include <cmath>
#include <complex>

namespace nltopo {

static const char *const kProfileNames[] = {"site", "mode", "none", "exponential"};

// The -force_* block. -force_site is 1-based as in model.md: the struct holds
// it 1-based while the table reads it, 0-based after.
static const auto &kForceTable = DeclareOptionTable<ToneBurstOptions>(
    "force_", "Tone-burst forcing",
    [](OptionTable<ToneBurstOptions> &t) {
      t.Enum("profile", &ToneBurstOptions::profile, kProfileNames, 4,
             "Force profile eta: site (unit force on one site), mode (a linear eigenvector), none, exponential (the insulated mode's fitted envelope)")
          .Real("omega", &ToneBurstOptions::omega, Closed(1e-6, 1e3), "Excitation frequency omega_ext (default sqrt(k_hat), the insulated frequency)")
          .Default("sqrt(k_hat)")
          .Real("energy", &ToneBurstOptions::energy, Closed(1e-12, 1e12), "Cut-off energy E*: the forcing stops for good the first time E >= E*")
          .Real("amplitude", &ToneBurstOptions::amplitude, Closed(0, 1e12), "Amplitude S; when not given the amplitude rule (docs/model.md) picks it")
          .Default("the amplitude rule")
          .OnlyIfSet()
          .Real("amplitude_safety", &ToneBurstOptions::safety, LeftOpen(0, 1e6), "Amplitude rule: S makes the linear burst energy this multiple of E*")
          .Int("amplitude_retries", &ToneBurstOptions::retries, Closed(0, 100),
               "Amplitude rule: if E* is not reached within the burst, rescale S (docs/model.md) up to this many times")
          .Real("tau_periods", &ToneBurstOptions::tau_periods, Closed(1e-3, 1e6), "Burst width tau in excitation periods")
          .Real("t0_taus", &ToneBurstOptions::t0_taus, Closed(0, 1e3), "Burst centre t0 in units of tau")
          .Int("site", &ToneBurstOptions::site, Bounds{}, "Forced site for profile site, 1-based as in model.md (default m+1, the interface even site)")
          .Default("m+1")
          .Int("mode_index", &ToneBurstOptions::mode, Bounds{}, "Linear mode (0-based, ascending frequency) for profile mode");
    },
    ToneBurstOptions{ForceProfile::Site, 1.0});

PetscErrorCode ToneBurstOptionsFromOptions(MPI_Comm comm, const LatticeParams &lp, ToneBurstOptions *o)
{
  std::vector<PetscBool> set;
  PetscFunctionBeginUser;
  if (o->omega <= 0) o->omega = std::sqrt(lp.KHat());
  if (o->site < 0 && lp.layout == Layout::Interface) o->site = lp.InterfaceSite() + 1;
  if (o->site < 0) o->site = 0;
  o->site += 1; // the option is 1-based (model.md), the code 0-based
  PetscCall(kForceTable.Read(comm, o, &set));
  o->site -= 1;
  if (!kForceTable.Given(set, "amplitude")) o->amplitude = -1;
  const PetscInt N = lp.N();
  PetscCheck(o->profile != ForceProfile::Site || (o->site >= 0 && o->site < N), comm, PETSC_ERR_USER,
             "-force_site must lie in 1..%" PetscInt_FMT ", got %" PetscInt_FMT, N, o->site + 1);
  PetscCheck(o->profile != ForceProfile::Exponential || lp.layout == Layout::Interface, comm, PETSC_ERR_USER,
             "-force_profile exponential follows the insulated mode of the interface: it needs -lattice_layout interface");
  PetscCheck(o->profile != ForceProfile::Mode || (o->mode >= 0 && o->mode < N), comm, PETSC_ERR_USER,
             "-force_profile mode needs -force_mode_index in 0..%" PetscInt_FMT ", got %" PetscInt_FMT, N - 1, o->mode);
  PetscFunctionReturn(0);
}

PetscReal BurstUnitEnergy(const std::vector<PetscReal> &omega_j, const std::vector<PetscReal> &proj2, PetscReal omega, PetscReal tau, PetscReal t0)
{
  const PetscReal pi = PETSC_PI;
  PetscReal burst = 0, quasi = 0;
  for (size_t j = 0; j < omega_j.size(); j++) {
    const PetscReal wj = omega_j[j], a2 = proj2[j];
    const PetscReal A = std::exp(-tau * tau * (omega - wj) * (omega - wj) / 4), B = std::exp(-tau * tau * (omega + wj) * (omega + wj) / 4);
    const std::complex<PetscReal> s = A + B * std::exp(std::complex<PetscReal>(0, -2 * omega * t0));
    burst += a2 * pi * tau * tau / 8 * std::norm(s);
    // Quasi-static response at the envelope peak, resonance regularised at |omega_j - omega| ~ 1/tau.
    const PetscReal d = wj * wj - omega * omega, reg = 2 * wj / tau;
    quasi += a2 * std::max(omega * omega, wj * wj) / (2 * (d * d + reg * reg));
  }
  return std::max(burst, quasi);
}

PetscErrorCode FitExponentialProfile(const Lattice &lat, Vec insulated, PetscReal *a, PetscReal *b)
{
  std::vector<PetscReal> phi;
  PetscFunctionBeginUser;
  PetscCall(GatherVec(insulated, true, &phi));
  const PetscInt m = lat.Params().InterfaceSite();
  PetscReal mx = 0;
  for (PetscReal v : phi) mx = std::max(mx, std::abs(v));
  PetscReal sx = 0, sy = 0, sxx = 0, sxy = 0;
  PetscInt n = 0;
  for (size_t i = 1; i < phi.size(); i += 2) // 0-based odd = 1-based even sites
    if (std::abs(phi[i]) > 1e-6 * mx) {      // below, the finite lattice and round-off bend the envelope
      const PetscReal x = std::abs((PetscInt)i - m), y = std::log(std::abs(phi[i]));
      sx += x, sy += y, sxx += x * x, sxy += x * y;
      n++;
    }
  PetscCheck(n >= 2, lat.Comm(), PETSC_ERR_USER, "-force_profile exponential: the insulated mode has too few even sites to fit");
  *b = (n * sxy - sx * sy) / (n * sxx - sx * sx);
  *a = std::exp((sy - *b * sx) / n);
  PetscFunctionReturn(0);
}

PetscErrorCode ToneBurst::Setup(const Lattice &lat, const ToneBurstOptions &o, const LinearModes *modes)
{
  MPI_Comm comm = lat.Comm();
  PetscFunctionBeginUser;
  opt_ = o;
  tau_ = o.tau_periods * 2 * PETSC_PI / o.omega;
  t0_ = o.t0_taus * tau_;
  idx_.clear();
  eta_.clear();
  const PetscInt xs = lat.OwnedStart(), xe = xs + lat.OwnedCount();
  OwnedVec eta; // the full profile, for the amplitude rule
  PetscCall(DMCreateGlobalVector(lat.SiteDM(), eta.out()));
  switch (o.profile) {
  case ForceProfile::None: break;
  case ForceProfile::Site:
    if (o.site >= xs && o.site < xe) PetscCall(VecSetValue(eta, o.site, 1.0, INSERT_VALUES));
    break;
  case ForceProfile::Mode:
    PetscCheck(modes, comm, PETSC_ERR_USER, "-force_profile mode needs the linear modes of the lattice");
    PetscCall(modes->CopyMode(o.mode, eta));
    break;
  case ForceProfile::Exponential: {
    PetscCheck(modes, comm, PETSC_ERR_USER, "-force_profile exponential needs the linear insulated mode of the lattice");
    PetscCheck(modes->Insulated(), comm, PETSC_ERR_USER, "-force_profile exponential fits the insulated mode, and this lattice has none: %s",
               NoInsulatedModeReason(lat.Params()).c_str());
    PetscCall(FitExponentialProfile(lat, modes->Insulated(), &exp_a_, &exp_b_));
    const PetscInt m = lat.Params().InterfaceSite();
    for (PetscInt i = xs; i < xe; i++)
      if (i % 2 == 1) { // 1-based even site n = i + 1: (-1)^{n/2}
        const PetscReal sign = ((i + 1) / 2) % 2 ? -1.0 : 1.0;
        PetscCall(VecSetValue(eta, i, exp_a_ * std::exp(exp_b_ * std::abs(i - m)) * sign, INSERT_VALUES));
      }
    break;
  }
  }
  PetscCall(VecAssemblyBegin(eta));
  PetscCall(VecAssemblyEnd(eta));
  const PetscScalar *a;
  PetscCall(VecGetArrayRead(eta, &a));
  for (PetscInt i = xs; i < xe; i++)
    if (a[i - xs] != 0.0) {
      idx_.push_back(i);
      eta_.push_back(a[i - xs]);
    }
  PetscCall(VecRestoreArrayRead(eta, &a));

  from_rule_ = Present() && o.amplitude < 0;
  S_ = Present() ? o.amplitude : 0;
  if (from_rule_) {
    PetscCheck(modes, comm, PETSC_ERR_USER, "the amplitude rule needs the linear modes; give -force_amplitude for this lattice");
    std::vector<PetscReal> proj2;
    PetscCall(modes->Projections(eta, &proj2));
    const PetscReal e1 = BurstUnitEnergy(modes->Omega(), proj2, o.omega, tau_, t0_);
    PetscCheck(e1 > 0 && std::isfinite(e1), comm, PETSC_ERR_USER, "amplitude rule: the profile does not couple to any linear mode; give -force_amplitude");
    S_ = std::sqrt(o.safety * o.energy / e1);
  }
  PetscFunctionReturn(0);
}

PetscErrorCode ToneBurst::Profile(const Lattice &lat, std::vector<PetscReal> *eta) const
{
  PetscFunctionBeginUser;
  eta->assign(lat.N(), 0.0);
  for (size_t k = 0; k < idx_.size(); k++) (*eta)[idx_[k]] = PetscRealPart(eta_[k]);
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, eta->data(), (PetscMPIInt)lat.N(), MPIU_REAL, MPIU_SUM, lat.Comm())); // each site is owned once
  PetscFunctionReturn(0);
}

PetscReal ToneBurst::Signal(PetscReal t) const
{
  const PetscReal x = (t - t0_) / tau_;
  return S_ * std::cos(opt_.omega * t) * std::exp(-x * x);
}

void ToneBurst::Add(PetscReal t, PetscScalar *a) const
{
  const PetscReal s = Signal(t);
  for (size_t k = 0; k < idx_.size(); k++) a[idx_[k]] += eta_[k] * s;
}

} // namespace nltopo
