#pragma once
// The Floquet data of every orbit of a continued branch, as a PointHook of
// ContinueBranch (orbits/continuation.hpp) collecting the columns that
// /continuation/<branch> stores: every multiplier from the dense monodromy
// (-floquet), or the -floquet_mf_nev leading pairs (-floquet_mf).
#include "orbits/continuation.hpp"
#include "stability/floquet.hpp"
#include "stability/floquet_mf.hpp"
#include "stability/verdict.hpp"
#include <string>
#include <vector>

namespace nltopo {

// The Floquet columns of a branch, one entry (or row) per orbit (dense route:
// all 2N multipliers, krein and instability; matrix-free: the -floquet_mf_nev
// leading ones, products and unconverged).
struct FloquetColumns {
  std::vector<PetscReal> re, im, max_modulus, det_error;
  std::vector<PetscInt> krein, stable, instability;
  std::vector<PetscReal> edge; // dense route: each eigenvector's edge share (kept in memory for -cont_bifurcations, not written)
  PetscInt products = 0, unconverged = 0;
  // issue 35 (scaling with N): per orbit, the leading nontrivial eigenvector's participation ratio over
  // sites and edge share (floquet.hpp LeadingIndex, DisplacementParticipation); NaN matrix-free
  std::vector<PetscReal> leading_participation, leading_edge;
  std::string route; // matrix-free hook: "dense" (2N <= -floquet_mf_dense_max) or "matrix-free"
  // The verdict of each orbit (stability/verdict.hpp): code, bound, e-folding time in periods, reason.
  std::vector<PetscInt> verdict;
  std::vector<PetscReal> verdict_bound, verdict_efold;
  std::vector<std::string> verdict_reason;
  void AddVerdict(const OrbitVerdict &v);
};

// -floquet: the multipliers, Krein signatures and stability of every orbit
// (FloquetAnalysis of the monodromy integrated at the converged orbit).
class FloquetHook : public PointHook {
public:
  FloquetHook(PeriodicFlow &flow, const FloquetOptions &o) : flow_(flow), opt_(o) {}
  PetscErrorCode Point(Vec z0, PetscReal T, PetscReal beta, Vec dz0) override;
  void Clear() { c = FloquetColumns(); }
  FloquetColumns c;

private:
  PeriodicFlow &flow_;
  FloquetOptions opt_;
  OwnedMat S_;
  OwnedVec zT_, vr_, vi_; // vr_, vi_: the most unstable eigenvector (ConfirmGrowth)
};

// -floquet_mf (long lattices): the -floquet_mf_nev leading multipliers of
// every orbit, matrix-free (stability/floquet_mf.hpp), or from the dense
// monodromy where 2N <= -floquet_mf_dense_max (then with their Krein
// signatures and the leading instability's class; -1 and 0 matrix-free). The
// `stable` column holds the route's verdict: only the dense route can say
// "stable" (1); the matrix-free one says "unstable" (0) or "not decided" (-1).
// The Floquet routes a continuation can take and what their summary says (a
// trait table, FloquetRouteTraitsOf): the full dense analysis (-floquet), and
// the -floquet_mf routes.
enum class FloquetRoute { Full = 0, Dense = 1, Localized = 2, MatrixFree = 3 };
struct FloquetRouteTraits {
  const char *name;    // written as the route (the `route` attribute)
  const char *summary; // after "Floquet" in the branch's summary line
  bool det_error;      // the summary reports max |det M - 1| (all 2N multipliers known)
  bool undecided;      // the summary counts the orbits it could not decide, and the products
};
const FloquetRouteTraits &FloquetRouteTraitsOf(FloquetRoute r);

class FloquetMfHook : public PointHook {
public:
  FloquetMfHook(PeriodicFlow &flow, const FloquetOptions &o, const FloquetMfOptions &mo) : flow_(flow), opt_(o), mopt_(mo) {}
  bool Dense() const { return 2 * flow_.Lat().N() <= mopt_.dense_max; }
  bool Localized() const { return !Dense() && mopt_.which == FloquetMfWhich::Localized; }
  FloquetRoute RouteKind() const { return Dense() ? FloquetRoute::Dense : Localized() ? FloquetRoute::Localized : FloquetRoute::MatrixFree; }
  const char *Route() const { return FloquetRouteTraitsOf(RouteKind()).name; }
  // The route's line at the start of a run: what it computes and can say.
  PetscErrorCode Announce() const;
  PetscErrorCode Point(Vec z0, PetscReal T, PetscReal beta, Vec dz0) override;
  void Clear() { c = FloquetColumns(), c.route = Route(), warm_.clear(); }
  FloquetColumns c;
  // The localized route's verdict of the last orbit and, when unstable, its
  // eigenvector (real, imaginary part; full-lattice state layout) for ConfirmGrowth.
  OrbitVerdict loc_verdict;
  OwnedVec loc_vr, loc_vi;

private:
  PeriodicFlow &flow_;
  FloquetOptions opt_;
  FloquetMfOptions mopt_;
  std::vector<OwnedVec> warm_; // the previous orbit's eigenvectors: the next solve's initial space
  OwnedMat S_;                 // the dense route's sensitivity matrix
  OwnedVec zT_, vr_, vi_;      // vr_, vi_: the leading eigenvector (ConfirmGrowth)
  PetscErrorCode RouteVerdict(Vec z0, PetscReal T, PetscReal beta, const LeadingMultipliers &r, OrbitVerdict *v);
};

// A branch's one-line Floquet summary: how many of its orbits are stable at
// -floquet_tol tol, and the dense route's largest |det M - 1| or the
// matrix-free route's undecided orbits and monodromy products, as the
// route's traits say.
// Then the verdicts: a count per verdict and a line per unstable or
// unresolved orbit (at most 12; energy: the orbits' energies, optional).
PetscErrorCode PrintFloquetSummary(MPI_Comm comm, const std::string &label, const FloquetColumns &f, PetscReal tol, FloquetRoute route,
                                   const std::vector<PetscReal> *energy = nullptr);

} // namespace nltopo
