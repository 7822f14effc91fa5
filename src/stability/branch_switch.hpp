#pragma once
// -cont_switch: the family born at a located branch point or period doubling
// (docs/continuation.md "Branch switching"). At the event's orbit X* = (z*, T*, beta*)
// the new family leaves along the critical eigenvector phi of M:
//   branch point (kind 2, a pair through +1): the new pair's direction at +1;
//     the new orbits have period ~ T*;
//   period doubling (kind 3, a pair through -1): M phi = -phi, so z* + eps phi
//     returns to z* - eps phi after T* and to itself after 2 T*: the new
//     orbits have period ~ 2 T*. Traversed twice, the parent's orbit is a
//     fixed point of the 2 T* map with the multiplier (-1)^2 = +1 there, so
//     the doubled family branches off it as at a branch point. The two sides
//     of phi are one family (each orbit passes near z* + eps phi and, T*
//     later, near z* - eps phi).
// The first orbit is found by the shooting Newton with the pinning
// constraint phi . (z0 - z*) = eps (an arclength constraint along
// (phi, 0, 0)), which keeps it off the parent family (whose own tangent is
// orthogonal to phi at a symmetry-breaking pitchfork, and transversal to it
// otherwise). The two orbits X* (at period m T*) and X1 then start a
// continuation exactly as a resume does (orbits/continuation.hpp): the first
// step along the chord X1 - X*, of its length.
#include "stability/bifurcation_locator.hpp"
#include "stability/floquet_hooks.hpp"
#include <functional>
#include <string>
#include <vector>

namespace nltopo {

// One -cont_switch item: an event of a branch, by its index in the branch's
// event list (<branch>:<index>) or by its kind and nearest omega
// (<branch>:<kind>@<omega>, kind bp or branch_point, pd or period_doubling,
// the names of /bifurcations "kind"): indices move when the locator learns
// new kinds of events, a kind and a frequency do not.
struct SwitchSpec {
  std::string text;                        // the item as given (messages)
  std::string branch;                      // a -cont_branch entry (name or mode<k>) or a switched family's label
  PetscInt index = -1;                     // >= 0: by index
  EventKind kind = EventKind::BranchPoint; // index < 0: by kind and nearest omega
  PetscReal omega = 0;
  bool used = false; // its branch was continued and its event looked up
  bool ByIndex() const { return index >= 0; }
};
// The -cont_switch items; a malformed one, or one given twice, is refused
// with one line naming the option and the item.
PetscErrorCode ParseSwitchSpecs(MPI_Comm comm, const std::vector<std::string> &items, std::vector<SwitchSpec> *specs);
// Whether a -cont_switch item's branch names the branch given as name (a
// -cont_branch entry as given, or as its label mode<k> for k; a label).
bool SwitchNames(const std::string &branch, const std::string &name);
// Every spec on a branch that will be continued: one of -cont_branch (among),
// or a family another spec starts (by index: exactly; by kind: any index).
PetscErrorCode CheckSwitchParents(MPI_Comm comm, const std::vector<SwitchSpec> &specs, const std::function<bool(const std::string &)> &among);
// Whether branch will be continued: one of -cont_branch (among), or a family
// a spec starts on such a branch (-cont_codim2 on a switched family).
bool WillBeFollowed(const std::vector<SwitchSpec> &specs, const std::string &branch, const std::function<bool(const std::string &)> &among);
// The event of ev (branch label's located events) that s selects: by index,
// or the event of s's kind nearest s.omega, at most half as far from it as
// the next one of that kind. None, out of range or ambiguous: one line
// naming -cont_switch and the item.
PetscErrorCode SelectSwitchEvent(MPI_Comm comm, const SwitchSpec &s, const std::vector<BifurcationEvent> &ev, const std::string &label, PetscInt *index);
// The by-kind rule of SelectSwitchEvent for any option (-cont_switch, -cont_codim2; text: the item as given).
PetscErrorCode SelectEventNearest(MPI_Comm comm, const char *option, const std::string &text, EventKind kind, PetscReal omega,
                                  const std::vector<BifurcationEvent> &ev, const std::string &label, PetscInt *index);

// -cont_switch (ParseSwitchSpecs) and -cont_switch_step; check: each item on
// a branch that will be continued (CheckSwitchParents; among: whether a branch
// is one of -cont_branch).
PetscErrorCode SwitchOptionsFromOptions(MPI_Comm comm, bool check, const std::function<bool(const std::string &)> &among, std::vector<SwitchSpec> *specs,
                                        PetscReal *step);

// After the run: a warning for each spec whose branch was not followed (its
// switch failed, or the event its parent's selected had another kind or index).
PetscErrorCode WarnUnusedSwitches(MPI_Comm comm, const std::vector<SwitchSpec> &specs);

// One family to follow, typed: the parent branch, its event, the event's kind
// and the period multiple the kind gives. The output names are generated
// from it, never parsed back.
struct SwitchPlan {
  std::string parent; // the parent branch's label
  PetscInt event = 0; // the index of the event among the parent's
  EventKind kind = EventKind::BranchPoint;
  PetscInt period_multiple = 1; // SwitchedPeriodMultiple(kind)
  // The attribute `parent` of the families: "<parent>:<event>".
  std::string ParentAttribute() const { return parent + ":" + std::to_string(event); }
  // A period doubling starts one family (from +phi, else -phi), a branch point one on each side.
  bool OneFamily() const { return period_multiple == 2; }
  // <parent>_bp<event>_plus / _minus (sign +1 / -1), or <parent>_pd<event>.
  std::string Label(PetscInt sign) const;
  const char *What() const { return OneFamily() ? "period doubling" : "branch point"; }
};
// A plan with the event and its orbit X* on the parent (BifurcationLocator::OrbitAt).
struct SwitchJob {
  SwitchPlan plan;
  BifurcationEvent e;
  OwnedVec Xs;
};
// The jobs of the specs naming the branch just continued (given as name,
// labelled label, its located events ev; loc still holds it): each event
// selected and its orbit solved again on the parent, before any family is
// followed. An orbit not found again is a warning and no job. Marks the specs used.
PetscErrorCode PlanSwitches(BifurcationLocator &loc, Shooting &shoot, std::vector<SwitchSpec> &specs, const std::string &name, const std::string &label,
                            const std::vector<BifurcationEvent> &ev, std::vector<SwitchJob> *jobs);
// The start of job's family on side sign (StartSwitchedBranch at step |z*|,
// its messages) and the two start points' Floquet data in floquet (cleared
// first). The flow integrates with the family's period multiple.
// *pinned false: no orbit found there (warned); nothing else is done.
PetscErrorCode StartFamily(Shooting &shoot, const SwitchJob &job, PetscReal step, PetscInt sign, FloquetHook &floquet, Branch *start, bool *pinned);

// The period of the family born at an event of this kind, in periods of the
// parent orbit: 1 at a branch point, 2 at a period doubling, 0 for a kind
// that starts no family (folds, collisions).
PetscInt SwitchedPeriodMultiple(EventKind k);

// The start of the family born at event e (a branch point or a period
// doubling) whose orbit on the parent is Xs (BifurcationLocator::OrbitAt at
// the event, period T*), on the side sign (+1 or -1) of phi, with
// |eps| = step |z*|: a Branch of two points (X* at period m T*, m =
// SwitchedPeriodMultiple(e.kind), and X1; z0 rows on rank 0) with the step
// to take next, for ContinueBranch's resume argument. The flow must
// integrate with m times the parent's period multiple (PeriodMultipleScope,
// orbits/flow.hpp) here and for the whole family, so that its orbits have
// the parent's step size and X* is an orbit of the same discrete map. *pinned: the residual of
// X1's Newton converged; *away: |phi . (z1 - z*)| / |z1 - z*|, the share of
// the first step along phi (1: straight off the parent).
PetscErrorCode StartSwitchedBranch(Shooting &shoot, Vec Xs, const BifurcationEvent &e, PetscReal step, PetscInt sign, Branch *start, bool *pinned,
                                   PetscReal *away);

} // namespace nltopo
