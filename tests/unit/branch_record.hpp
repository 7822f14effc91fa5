#pragma once
// A continued branch's dense Floquet data point by point (the input of
// BifurcationLocator::Locate), and its z0 rows on every rank.
#include "core/gather.hpp"
#include "helpers.hpp"
#include "orbits/continuation.hpp"
#include "stability/bifurcation_locator.hpp"
#include "stability/floquet_hooks.hpp"

namespace nltopo::test {

// The -floquet hook of the continuation study at the default options.
struct Record : public FloquetHook {
  explicit Record(PeriodicFlow &f) : FloquetHook(f, FloquetOptions()) {}
};

// Rank 0's z0 rows of a branch, on every rank.
inline std::vector<PetscReal> AllRows(const Branch &b)
{
  std::vector<PetscReal> z0(b.z0);
  PCHK(BroadcastFromRoot(PETSC_COMM_WORLD, MPIU_REAL, &z0));
  return z0;
}

// The events of branch b from its recorded Floquet data, located to 1e-9 in
// omega by loc (set up on shoot here; it stays usable for OrbitAt).
inline PetscErrorCode LocateRecorded(BifurcationLocator &loc, Shooting &shoot, const Branch &b, const Record &rec, const char *name,
                                     std::vector<BifurcationEvent> *ev)
{
  BifurcationOptions bo;
  PetscFunctionBeginUser;
  bo.tol = 1e-9;
  PetscCall(loc.Setup(shoot, FloquetOptions(), bo));
  PetscCall(loc.Locate(b, rec.c.re, rec.c.im, rec.c.edge, name, ev));
  PetscFunctionReturn(0);
}

} // namespace nltopo::test
