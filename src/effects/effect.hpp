#pragma once
// The physics as one list of effects (model.md "Equations of motion"): every
// term of u'' = a(t, u, v) is an Effect that knows its acceleration, its
// tangent (stiffness -da/du, damping -da/dv) and, when it derives from a
// potential, its energy. The TS right-hand side (effects/rhs.hpp), the
// variational and tangent flows of the orbit solver (orbits/), the state
// Jacobian and the energy all iterate over one EffectList, so a term the scene
// did not enable is computed nowhere, and a new term is one new file
// (effects/registry.cpp).
//
// Array conventions (the lattice's, lattice/lattice.hpp): u is ghosted and
// indexed by GLOBAL site (valid for xs-1 .. xs+xm); v and a are indexed by
// global site over the owned sites xs .. xs+xm-1; per-bond arrays (bond b
// joins sites b and b+1) by global bond over xs-1 .. xs+xm-1.
#include "lattice/lattice.hpp"
#include <memory>
#include <string>
#include <vector>

namespace nltopo {

class ToneBurst;

class Effect {
public:
  virtual ~Effect() = default;
  virtual const char *Name() const = 0;    // "linear", "cubic", "forcing", "damping"
  virtual const char *LogName() const = 0; // its -log_view event, e.g. "RhsCubic"
  // What enabled it, as the user wrote it, for errors ("-lattice_damping 0.1").
  virtual std::string EnabledBy() const = 0;
  // Derives from a potential: then AddEnergy adds that potential energy and
  // the stiffness is its Hessian.
  virtual bool Conservative() const = 0;
  virtual bool VelocityDependent() const { return false; }
  virtual PetscLogDouble FlopsPerSite() const { return 0; }

  // a[i] += this effect's acceleration at owned site i (v may be NULL when no
  // effect of the list depends on velocity).
  virtual void AddAcceleration(PetscReal t, const PetscScalar *u, const PetscScalar *v, PetscScalar *a) const = 0;
  // a[i] = the acceleration, overwriting a (saves the zeroing pass when the
  // effect is first in the list); false if the effect only adds.
  virtual bool SetAcceleration(PetscReal t, const PetscScalar *u, const PetscScalar *v, PetscScalar *a) const { return false; }
  // Tangent stiffness K_T = -da/du, symmetric and nearest-neighbour:
  // kd[i] += K_T(i, i) (owned sites), kb[b] += K_T(b, b+1) (bonds xs-1 .. xs+xm-1).
  // u NULL: at u = 0.
  virtual void AddStiffness(const PetscScalar *u, PetscScalar *kd, PetscScalar *kb) const {}
  // Damping C = -da/dv (diagonal): c[i] += C(i, i) for owned sites.
  virtual void AddDamping(PetscScalar *c) const {}
  // This rank's share of the effect's potential energy, into its part of e
  // (bond b counts on the owner of site b).
  virtual void AddEnergy(const PetscScalar *u, EnergyParts *e) const {}
};

// Which effects of a list are evaluated, and how often each was (per run:
// the forcing is switched off at the cut-off).
struct EffectCalls {
  std::vector<char> on;
  std::vector<PetscInt> count;
};

class EffectList {
public:
  explicit EffectList(const Lattice &lat) : lat_(&lat) {}
  EffectList(const EffectList &) = delete;
  EffectList &operator=(const EffectList &) = delete;

  PetscErrorCode Add(std::unique_ptr<Effect> e);
  // Drops the effect called name (a test's or a study's variant of a scene).
  void Remove(const char *name);

  const Lattice &Lat() const { return *lat_; }
  size_t Size() const { return fx_.size(); }
  const Effect &At(size_t k) const { return *fx_[k]; }
  const Effect *Find(const char *name) const;
  bool Has(const char *name) const { return Find(name) != nullptr; }
  bool Conservative() const;
  bool VelocityDependent() const;
  // The tone burst of the forcing effect, NULL if the scene has none.
  ToneBurst *Burst() const { return burst_; }
  // One line naming the first effect that is not conservative, for studies
  // whose method needs a conservative system (who: "-study continuation ...").
  PetscErrorCode RequireConservative(const char *who) const;
  // One line naming the first velocity-dependent effect, for integrators of u'' = a(t, u).
  PetscErrorCode RequirePositionOnly(const char *who) const;

  // a = the sum of the effects (those on in calls, all when calls is NULL; its
  // counts are incremented), each inside its log event.
  PetscErrorCode Acceleration(PetscReal t, const PetscScalar *u, const PetscScalar *v, PetscScalar *a, EffectCalls *calls = nullptr) const;
  // K_T(u) = the sum of the stiffnesses: kd over the owned sites, kb over the
  // bonds xs-1 .. xs+xm-1 (0 outside the chain); u NULL: at rest.
  void Stiffness(const PetscScalar *u, PetscScalar *kd, PetscScalar *kb) const;
  // C = the sum of the dampings over the owned sites.
  void Damping(PetscScalar *c) const;
  // Energy parts of the state z: kinetic (unit masses) plus every effect's (collective).
  PetscErrorCode Energy(Vec z, EnergyParts *e) const;

  // K_T(u) into a SiteDM matrix (u a SiteDM vector; NULL: at rest).
  PetscErrorCode AssembleTangentStiffness(Vec u, Mat KT) const;
  // State Jacobian A = [[0, I], [-K_T(u), -C]] at z (NULL: at rest). With beta
  // != 0, (I + beta [[0, -I], [I, 0]]) A: the unfolded field f + beta grad E of
  // the periodic-orbit solver (orbits/flow.hpp).
  PetscErrorCode AssembleStateJacobian(Vec z, Mat A, PetscReal beta = 0) const;

  EffectCalls AllOn() const { return EffectCalls{std::vector<char>(fx_.size(), 1), std::vector<PetscInt>(fx_.size(), 0)}; }

private:
  PetscErrorCode Assemble(const PetscScalar *u, Mat M, bool state_form, PetscReal beta) const;
  const Lattice *lat_;
  std::vector<std::unique_ptr<Effect>> fx_;
  std::vector<PetscLogEvent> events_;
  ToneBurst *burst_ = nullptr;
};

// "-name value" with the value as %g, for EnabledBy().
std::string OptionText(const char *name, PetscReal value);

// The scene's effects (effects/registry.cpp): linear coupling (always), cubic
// bonds (Gamma != 0), the tone burst when burst is present, and every optional
// effect its options enable.
PetscErrorCode BuildEffects(const Lattice &lat, ToneBurst *burst, EffectList *fx);
// The lattice's own effects only (linear coupling, cubic bonds): tests and tools.
PetscErrorCode BuildLatticeEffects(const Lattice &lat, EffectList *fx);
// The lattice model a study runs: the -lattice_* geometry and springs
// (lattice/params.hpp), the cubic bonds' -lattice_cubic and the optional
// effects' options (-lattice_damping, ...), validated.
PetscErrorCode LatticeModelFromOptions(MPI_Comm comm, LatticeParams *p);
// The options of every optional effect (the studies' options functions).
PetscErrorCode EffectOptionsFromOptions(MPI_Comm comm);

} // namespace nltopo
