// The scene's effect list: the lattice's own effects, the forcing, and the
// optional effects, each of which reads its own options and creates itself
// when they enable it (a new effect: one file defining
// <Name>FromOptions(comm, lat, &effect), plus its name in the list below).
#include "effects/effect.hpp"
#include "effects/forcing.hpp"
#include "effects/lattice_effects.hpp"

namespace nltopo {

// lat NULL: read (and so declare) the options only.
using EffectFromOptions = PetscErrorCode (*)(MPI_Comm comm, const Lattice *lat, std::unique_ptr<Effect> *e);

#define NLTOPO_OPTIONAL_EFFECTS(X) X(Damping)

#define NLTOPO_DECLARE_EFFECT(Name) PetscErrorCode Name##FromOptions(MPI_Comm, const Lattice *, std::unique_ptr<Effect> *);
NLTOPO_OPTIONAL_EFFECTS(NLTOPO_DECLARE_EFFECT)
#define NLTOPO_LIST_EFFECT(Name) Name##FromOptions,
static const std::vector<EffectFromOptions> kOptionalEffects = {NLTOPO_OPTIONAL_EFFECTS(NLTOPO_LIST_EFFECT)};

PetscErrorCode EffectOptionsFromOptions(MPI_Comm comm)
{
  PetscFunctionBeginUser;
  for (EffectFromOptions f : kOptionalEffects) {
    std::unique_ptr<Effect> e;
    PetscCall(f(comm, nullptr, &e));
  }
  PetscFunctionReturn(0);
}

PetscErrorCode LatticeModelFromOptions(MPI_Comm comm, LatticeParams *p)
{
  PetscFunctionBeginUser;
  PetscCall(LatticeParamsFromOptions(comm, p));
  PetscCall(CubicBondsOptionsFromOptions(comm, p));
  PetscCall(EffectOptionsFromOptions(comm)); // every study reads them, so a conservative one can refuse them by name
  PetscFunctionReturn(0);
}

PetscErrorCode BuildLatticeEffects(const Lattice &lat, EffectList *fx)
{
  PetscFunctionBeginUser;
  PetscCall(fx->Add(CreateLinearCoupling(lat))); // first: it sets the acceleration, the others add
  PetscCall(fx->Add(CreateCubicBonds(lat)));
  PetscFunctionReturn(0);
}

PetscErrorCode BuildEffects(const Lattice &lat, ToneBurst *burst, EffectList *fx)
{
  PetscFunctionBeginUser;
  PetscCall(BuildLatticeEffects(lat, fx));
  if (burst && burst->Present()) PetscCall(fx->Add(std::make_unique<ForcingEffect>(burst)));
  for (EffectFromOptions f : kOptionalEffects) {
    std::unique_ptr<Effect> e;
    PetscCall(f(lat.Comm(), &lat, &e));
    PetscCall(fx->Add(std::move(e)));
  }
  PetscFunctionReturn(0);
}

} // namespace nltopo
