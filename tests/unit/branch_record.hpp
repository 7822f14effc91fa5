#pragma once
// A continued branch's dense Floquet data point by point (the input of
// BifurcationLocator::Locate), and its z0 rows on every rank.
#include "core/gather.hpp"
#include "helpers.hpp"
#include "orbits/continuation.hpp"
#include "stability/bifurcation_locator.hpp"
#include "stability/floquet.hpp"

namespace nltopo::test {

struct Record : public PointHook {
  PeriodicFlow &flow;
  OwnedMat S;
  OwnedVec zT;
  std::vector<PetscReal> re, im, edge;
  std::vector<PetscInt> krein;
  explicit Record(PeriodicFlow &f) : flow(f) {}
  PetscErrorCode Point(Vec z0, PetscReal T, PetscReal beta, Vec) override
  {
    FloquetResult r;
    PetscFunctionBeginUser;
    if (!S) {
      PetscCall(flow.CreateSensitivityMatrix(S.out()));
      PetscCall(VecDuplicate(z0, zT.out()));
    }
    PetscCall(flow.IntegrateWithMonodromy(z0, T, flow.FloquetBeta(beta), zT, S));
    PetscCall(FloquetAnalysis(flow.Lat(), S, FloquetOptions(), &r));
    re.insert(re.end(), r.re.begin(), r.re.end());
    im.insert(im.end(), r.im.begin(), r.im.end());
    edge.insert(edge.end(), r.edge.begin(), r.edge.end());
    krein.insert(krein.end(), r.krein.begin(), r.krein.end());
    PetscFunctionReturn(0);
  }
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
  PetscCall(loc.Locate(b, rec.re, rec.im, rec.edge, name, ev));
  PetscFunctionReturn(0);
}

} // namespace nltopo::test
