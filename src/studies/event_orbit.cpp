#include "studies/event_orbit.hpp"
#include "core/gather.hpp"
#include "effects/effect.hpp"

namespace nltopo {

PetscErrorCode EventOrbit(MPI_Comm comm, BifurcationLocator &loc, NnmSetup &nnm, const BifurcationEvent &e, Codim2Start *st, bool *found)
{
  OwnedVec X, z;
  EnergyParts en;
  PetscFunctionBeginUser;
  *st = Codim2Start();
  PetscCall(nnm.shoot.CreateUnknowns(X.out()));
  PetscCall(nnm.lat.CreateStateVector(z.out()));
  PetscCall(loc.OrbitAt(e.point, e.sigma, X, found));
  if (!*found) PetscFunctionReturn(0);
  PetscCall(nnm.shoot.Unpack(X, z, &st->period, &st->beta));
  st->omega = 2 * PETSC_PI / st->period;
  PetscCall(nnm.flow.Effects().Energy(z, &en));
  st->energy = en.Total();
  PetscCall(AppendStateRow(nnm.lat, z, &st->z0));
  PetscCall(BroadcastFromRoot(comm, MPIU_REAL, &st->z0));
  PetscFunctionReturn(0);
}

} // namespace nltopo
