#include "stability/branch_switch.hpp"
#include "core/gather.hpp"
#include "core/option_table.hpp"
#include <cctype>
#include <cmath>
#include <algorithm>
#include <cstdlib>

namespace nltopo {

namespace {

// One point of the start branch: orbit X's record (z0 row on rank 0).
PetscErrorCode AppendStartPoint(Shooting &shoot, Vec X, Vec z, PetscInt its, Branch *b)
{
  BranchPoint p;
  PetscFunctionBeginUser;
  PetscCall(OrbitPoint(shoot, X, z, &p));
  p.newton_its = its;
  PetscCall(AppendPoint(shoot.Flow().Lat(), z, p, b));
  PetscFunctionReturn(0);
}

// The kinds -cont_switch follows, by the names of /bifurcations "kind" (short: the family labels' tags).
struct SwitchKindName {
  const char *name, *tag;
  EventKind kind;
};
const SwitchKindName kSwitchKinds[] = {{"branch_point", "bp", EventKind::BranchPoint}, {"period_doubling", "pd", EventKind::PeriodDoubling}};

const char *KindTag(EventKind k) { return k == EventKind::PeriodDoubling ? "pd" : "bp"; }
const char *KindPlural(EventKind k)
{
  switch (k) {
  case EventKind::Fold: return "energy folds";
  case EventKind::PeriodDoubling: return "period doublings";
  case EventKind::HamiltonianHopf: return "Hamiltonian-Hopf events";
  default: return "branch points";
  }
}
// The label suffix of the family on side sign: none at a period doubling (one family).
const char *SideSuffix(EventKind k, PetscInt sign) { return k == EventKind::PeriodDoubling ? "" : sign > 0 ? "_plus" : "_minus"; }
bool AllDigits(const std::string &s)
{
  return !s.empty() && s.size() <= 6 && std::all_of(s.begin(), s.end(), [](char c) { return std::isdigit((unsigned char)c); });
}

// <branch>:<index> or <branch>:<kind>@<omega>.
PetscErrorCode ParseSwitchSpec(MPI_Comm comm, const std::string &item, SwitchSpec *s)
{
  PetscFunctionBeginUser;
  *s = SwitchSpec();
  s->text = item;
  const size_t colon = item.rfind(':');
  const std::string what = colon == std::string::npos ? "" : item.substr(colon + 1);
  const size_t at = what.find('@');
  bool ok = colon != std::string::npos && colon > 0;
  if (ok && at == std::string::npos) {
    ok = AllDigits(what);
    if (ok) s->index = (PetscInt)std::strtol(what.c_str(), nullptr, 10);
  } else if (ok) {
    const std::string kind = what.substr(0, at), w = what.substr(at + 1);
    char *end = nullptr;
    s->omega = std::strtod(w.c_str(), &end);
    ok = !w.empty() && end && !*end && std::isfinite(s->omega) && s->omega > 0;
    bool known = false;
    for (const SwitchKindName &k : kSwitchKinds)
      if (kind == k.name || kind == k.tag) known = true, s->kind = k.kind;
    ok = ok && known;
  }
  PetscCheck(ok, comm, PETSC_ERR_USER,
             "-cont_switch %s: expected <branch>:<event index> or <branch>:<kind>@<omega> (kind bp or branch_point, pd or period_doubling; omega > 0), e.g. "
             "insulated:12 or insulated:bp@2.418",
             item.c_str());
  s->branch = item.substr(0, colon);
  PetscFunctionReturn(0);
}

// Whether label is that of a family spec o starts (o by kind: any index).
bool MayStart(const SwitchSpec &o, const std::string &label)
{
  for (const std::string &stem : {o.branch, "mode" + o.branch})
    for (const SwitchKindName &k : kSwitchKinds) {
      if (!o.ByIndex() && o.kind != k.kind) continue;
      for (PetscInt sign : {1, -1}) {
        const std::string pre = stem + "_" + k.tag, suf = SideSuffix(k.kind, sign);
        if (label.size() <= pre.size() + suf.size() || label.compare(0, pre.size(), pre) || label.compare(label.size() - suf.size(), suf.size(), suf)) continue;
        const std::string mid = label.substr(pre.size(), label.size() - pre.size() - suf.size());
        if (o.ByIndex() ? mid == std::to_string(o.index) : AllDigits(mid)) return true;
      }
    }
  return false;
}

// Whether the branch of spec s will be continued (see CheckSwitchParents).
bool Followed(const std::vector<SwitchSpec> &specs, const std::string &branch, const std::function<bool(const std::string &)> &among, int depth = 0)
{
  if (among(branch)) return true;
  if (depth > 16) return false;
  for (const SwitchSpec &o : specs)
    if (MayStart(o, branch) && Followed(specs, o.branch, among, depth + 1)) return true;
  return false;
}

// The orbit X* at event e on the parent, into Xs: right at a branch point the
// shooting Jacobian is singular, a step aside if Newton fails there.
PetscErrorCode OrbitAtEvent(BifurcationLocator &loc, const BifurcationEvent &e, Vec Xs, bool *found)
{
  PetscFunctionBeginUser;
  *found = false;
  for (PetscReal aside : {0.0, -1e-6, 1e-6, -1e-4, 1e-4}) {
    PetscCall(loc.OrbitAt(e.point, e.sigma + aside, Xs, found));
    if (*found) break;
  }
  PetscFunctionReturn(0);
}

} // namespace

PetscErrorCode ParseSwitchSpecs(MPI_Comm comm, const std::vector<std::string> &items, std::vector<SwitchSpec> *specs)
{
  PetscFunctionBeginUser;
  specs->clear();
  for (const std::string &item : items) {
    SwitchSpec s;
    PetscCall(ParseSwitchSpec(comm, item, &s));
    for (const SwitchSpec &o : *specs)
      PetscCheck(!(SwitchNames(o.branch, s.branch) && o.index == s.index && (s.ByIndex() || (o.kind == s.kind && o.omega == s.omega))), comm, PETSC_ERR_USER,
                 "-cont_switch %s: given twice", item.c_str());
    specs->push_back(s);
  }
  PetscFunctionReturn(0);
}

bool SwitchNames(const std::string &branch, const std::string &name) { return branch == name || branch == "mode" + name || "mode" + branch == name; }

bool WillBeFollowed(const std::vector<SwitchSpec> &specs, const std::string &branch, const std::function<bool(const std::string &)> &among)
{
  return Followed(specs, branch, among);
}

PetscErrorCode CheckSwitchParents(MPI_Comm comm, const std::vector<SwitchSpec> &specs, const std::function<bool(const std::string &)> &among)
{
  PetscFunctionBeginUser;
  // each on a branch of -cont_branch, or on the family another switch starts
  // (insulated:34,insulated_bp34_plus:7 at N = 22: the period doubling of a switched family)
  for (const SwitchSpec &s : specs)
    PetscCheck(Followed(specs, s.branch, among), comm, PETSC_ERR_USER,
               "-cont_switch %s: no branch %s among -cont_branch or the families of the other -cont_switch events", s.text.c_str(), s.branch.c_str());
  PetscFunctionReturn(0);
}

namespace {
struct SwitchOptions {
  std::vector<std::string> items; // -cont_switch, parsed by ParseSwitchSpecs
  PetscReal step = 0.02;
};
} // namespace

static const auto &kSwitchTable = DeclareOptionTable<SwitchOptions>("cont_", "Branch switching", [](OptionTable<SwitchOptions> &t) {
  t.StringList("switch", &SwitchOptions::items, 16,
               "Follow the families born at these located branch points (on both sides of the critical eigenvector) or period "
               "doublings (the doubled-period family): <branch>:<event index> (the event list of -cont_bifurcations) or "
               "<branch>:<kind>@<omega>, the event of that kind nearest omega (kind bp or branch_point, pd or period_doubling)")
      .Default("none")
      .Real("switch_step", &SwitchOptions::step, Open(0, 1),
            "The first orbit of a switched family: this times |z*| along the critical eigenvector from the branch point");
});

PetscErrorCode SwitchOptionsFromOptions(MPI_Comm comm, bool check, const std::function<bool(const std::string &)> &among, std::vector<SwitchSpec> *specs,
                                        PetscReal *step)
{
  SwitchOptions o;
  PetscFunctionBeginUser;
  o.step = *step;
  PetscCall(kSwitchTable.Read(comm, &o));
  *step = o.step;
  PetscCall(ParseSwitchSpecs(comm, o.items, specs));
  if (check) PetscCall(CheckSwitchParents(comm, *specs, among));
  PetscFunctionReturn(0);
}

PetscErrorCode WarnUnusedSwitches(MPI_Comm comm, const std::vector<SwitchSpec> &specs)
{
  PetscFunctionBeginUser;
  for (const SwitchSpec &sw : specs)
    if (!sw.used) // a family of another switch that was not followed (a numerical failure, warned about) or has another name
      PetscCall(PetscPrintf(
          comm,
          "  warning: -cont_switch %s: no branch %s was followed (its switch failed, or its event started a family of another name, e.g. _pd<k> at a period doubling); not switched\n",
          sw.text.c_str(), sw.branch.c_str()));
  PetscFunctionReturn(0);
}

PetscErrorCode SelectSwitchEvent(MPI_Comm comm, const SwitchSpec &s, const std::vector<BifurcationEvent> &ev, const std::string &label, PetscInt *index)
{
  PetscFunctionBeginUser;
  if (s.ByIndex()) {
    PetscCheck(s.index < (PetscInt)ev.size(), comm, PETSC_ERR_USER, "-cont_switch %s: branch %s has %zu located events%s", s.text.c_str(), label.c_str(),
               ev.size(), ev.empty() ? "" : (" (0 .. " + std::to_string(ev.size() - 1) + ")").c_str());
    *index = s.index;
    PetscFunctionReturn(0);
  }
  PetscCall(SelectEventNearest(comm, "-cont_switch", s.text, s.kind, s.omega, ev, label, index));
  PetscFunctionReturn(0);
}

PetscErrorCode SelectEventNearest(MPI_Comm comm, const char *option, const std::string &text, EventKind kind, PetscReal omega,
                                  const std::vector<BifurcationEvent> &ev, const std::string &label, PetscInt *index)
{
  PetscFunctionBeginUser;
  PetscInt best = -1, next = -1; // the nearest event of the kind and the one after it
  const auto dist = [&](PetscInt i) { return std::abs(ev[i].omega - omega); };
  for (PetscInt i = 0; i < (PetscInt)ev.size(); i++) {
    if (ev[i].kind != kind) continue;
    if (best < 0 || dist(i) < dist(best)) next = best, best = i;
    else if (next < 0 || dist(i) < dist(next)) next = i;
  }
  PetscCheck(best >= 0, comm, PETSC_ERR_USER, "%s %s: branch %s has no %s among its %zu located events", option, text.c_str(), label.c_str(), KindPlural(kind),
             ev.size());
  PetscCheck(next < 0 || dist(next) > 2 * dist(best), comm, PETSC_ERR_USER,
             "%s %s: ambiguous: the %s of branch %s at omega %.9g (event %" PetscInt_FMT ") and %.9g (event %" PetscInt_FMT
             ") are about as near (the nearest must be less than half as far as the next); give omega nearer one of them%s",
             option, text.c_str(), KindPlural(kind), label.c_str(), (double)ev[best].omega, best, (double)ev[next].omega, next,
             std::string(option) == "-cont_switch" ? ", or the index" : "");
  *index = best;
  PetscFunctionReturn(0);
}

std::string SwitchPlan::Label(PetscInt sign) const { return parent + "_" + KindTag(kind) + std::to_string(event) + SideSuffix(kind, sign); }

PetscErrorCode PlanSwitches(BifurcationLocator &loc, Shooting &shoot, std::vector<SwitchSpec> &specs, const std::string &name, const std::string &label,
                            const std::vector<BifurcationEvent> &ev, std::vector<SwitchJob> *jobs)
{
  const MPI_Comm comm = shoot.Flow().Lat().Comm();
  PetscFunctionBeginUser;
  jobs->clear();
  for (SwitchSpec &sw : specs) {
    if (!SwitchNames(sw.branch, name)) continue;
    sw.used = true;
    SwitchJob job;
    PetscCall(SelectSwitchEvent(comm, sw, ev, label, &job.plan.event));
    job.e = ev[job.plan.event];
    job.plan.parent = label, job.plan.kind = job.e.kind, job.plan.period_multiple = SwitchedPeriodMultiple(job.e.kind);
    PetscCheck(job.plan.period_multiple > 0, comm, PETSC_ERR_USER,
               "-cont_switch %s: that event is a %s; branch switching follows branch points (kind 2) and period doublings (kind 3)", sw.text.c_str(),
               EventKindName(job.e.kind));
    for (const SwitchJob &o : *jobs)
      PetscCheck(o.plan.event != job.plan.event, comm, PETSC_ERR_USER, "-cont_switch %s: selects event %" PetscInt_FMT " of branch %s, as another item does",
                 sw.text.c_str(), job.plan.event, label.c_str());
    bool found;
    PetscCall(shoot.CreateUnknowns(job.Xs.out()));
    PetscCall(OrbitAtEvent(loc, job.e, job.Xs, &found));
    if (!found) {
      PetscCall(PetscPrintf(comm, "  warning: -cont_switch %s: the orbit at the branch point (omega %g) was not found again; not switched\n",
                            job.plan.ParentAttribute().c_str(), (double)job.e.omega));
      continue;
    }
    jobs->push_back(std::move(job));
  }
  PetscFunctionReturn(0);
}

PetscErrorCode StartFamily(Shooting &shoot, const SwitchJob &job, PetscReal step, PetscInt sign, FloquetHook &floquet, Branch *start, bool *pinned)
{
  const Lattice &lat = shoot.Flow().Lat();
  const MPI_Comm comm = lat.Comm();
  const BifurcationEvent &e = job.e;
  const bool pd = job.plan.OneFamily();
  const std::string parent = job.plan.ParentAttribute(), label = job.plan.Label(sign);
  PetscReal away;
  PetscFunctionBeginUser;
  PetscCall(StartSwitchedBranch(shoot, job.Xs, e, step, sign, start, pinned, &away));
  if (!*pinned) {
    if (pd && sign > 0)
      PetscCall(PetscPrintf(
          comm, "  warning: -cont_switch %s: no orbit found %g |z*| off the period doubling along +phi (Newton failed); trying -phi (the same family)\n",
          parent.c_str(), (double)step));
    else
      PetscCall(PetscPrintf(
          comm,
          "  warning: -cont_switch %s: no orbit found %g |z*| off the %s along %sits critical eigenvector (Newton failed); %s not followed, try another -cont_switch_step\n",
          parent.c_str(), (double)step, job.plan.What(), pd ? "either side of " : "", label.c_str()));
    PetscFunctionReturn(0);
  }
  PetscCall(PetscPrintf(
      comm,
      "  [%s] from the %s %s at omega %.9f (E %.6g): first orbit at %g |z*| along %sthe critical eigenvector (%.0f %% of the step along it), E %.6g, omega %.9f%s\n",
      label.c_str(), job.plan.What(), parent.c_str(), (double)e.omega, (double)e.energy, (double)step, sign > 0 ? "" : "minus ", (double)(100 * away),
      (double)start->energy[1], (double)start->omega[1], pd ? " (period ~2 T*: the FEP plots it at 2 omega, attribute period_multiple 2)" : ""));
  // the Floquet data of the two start points, as of every other
  floquet.Clear();
  OwnedVec z;
  PetscCall(lat.CreateStateVector(z.out()));
  std::vector<PetscReal> rows = start->z0;
  PetscCall(BroadcastFromRoot(comm, MPIU_REAL, &rows));
  for (size_t q = 0; q < 2; q++) {
    PetscCall(StateFromRow(lat, rows.data() + q * 2 * lat.N(), z));
    PetscCall(floquet.Point(z, start->period[q], start->beta[q], z));
  }
  PetscFunctionReturn(0);
}

PetscInt SwitchedPeriodMultiple(EventKind k) { return k == EventKind::BranchPoint ? 1 : k == EventKind::PeriodDoubling ? 2 : 0; }

PetscErrorCode StartSwitchedBranch(Shooting &shoot, Vec Xs, const BifurcationEvent &e, PetscReal step, PetscInt sign, Branch *start, bool *pinned,
                                   PetscReal *away)
{
  const Lattice &lat = shoot.Flow().Lat();
  MPI_Comm comm = lat.Comm();
  OwnedVec X1, t, Xpred, zs, z1, phi, d;
  bool ok;
  PetscInt its;
  PetscFunctionBeginUser;
  *start = Branch();
  *pinned = false;
  const PetscInt m = SwitchedPeriodMultiple(e.kind);
  PetscCheck(m > 0, comm, PETSC_ERR_SUP, "-cont_switch follows branch points (kind 2) and period doublings (kind 3); this event is a %s",
             EventKindName(e.kind));
  PetscCheck(shoot.Flow().PeriodMultiple() % m == 0, comm, PETSC_ERR_PLIB,
             "-cont_switch: the family born at a %s is integrated with period multiple %" PetscInt_FMT ", not a multiple of %" PetscInt_FMT,
             EventKindName(e.kind), shoot.Flow().PeriodMultiple(), m);
  PetscCheck(e.vector.size() == (size_t)(2 * lat.N()), comm, PETSC_ERR_PLIB, "-cont_switch: the event has no critical eigenvector");
  for (OwnedVec *v : {&X1, &t, &Xpred, &d}) PetscCall(VecDuplicate(Xs, v->out()));
  PetscCall(lat.CreateStateVector(zs.out()));
  PetscCall(VecDuplicate(zs, z1.out()));
  PetscCall(VecDuplicate(zs, phi.out()));
  PetscReal Ts, bs, zn;
  PetscCall(shoot.Unpack(Xs, zs, &Ts, &bs));
  PetscCall(VecNorm(zs, NORM_2, &zn));
  // X* as an orbit of the new family: the parent's orbit traversed m times
  OwnedVec Xm;
  PetscCall(VecDuplicate(Xs, Xm.out()));
  PetscCall(shoot.Pack(zs, m * Ts, bs, Xm));
  // X1: pinned at eps along (phi, 0, 0)
  PetscCall(StateFromRow(lat, e.vector.data(), phi));
  PetscCall(shoot.Pack(phi, 0.0, 0.0, t));
  const PetscReal eps = sign * step * zn;
  PetscCall(VecWAXPY(Xpred, eps, t, Xm));
  PetscCall(shoot.SetArclengthConstraint(zs, t, Xpred));
  PetscCall(VecCopy(Xpred, X1));
  PetscCall(shoot.Solve(X1, &ok, &its));
  *pinned = ok;
  if (!ok) PetscFunctionReturn(0);
  // the share of the first step along phi
  PetscReal T1, b1, dz, along;
  PetscCall(shoot.Unpack(X1, z1, &T1, &b1));
  PetscCall(VecWAXPY(d, -1.0, Xm, X1));
  PetscCall(VecAXPY(z1, -1.0, zs));
  PetscCall(VecNorm(z1, NORM_2, &dz));
  PetscCall(VecDot(z1, phi, &along));
  *away = dz > 0 ? std::abs(along) / dz : 0;
  // the two points and the next step (the resume state of orbits/continuation.hpp)
  PetscCall(AppendStartPoint(shoot, Xm, zs, 0, start));
  PetscCall(AppendStartPoint(shoot, X1, z1, its, start));
  PetscReal ds;
  PetscCall(VecNormalize(d, &ds));
  PetscReal dT, db;
  std::vector<PetscReal> row;
  PetscCall(shoot.Unpack(d, z1, &dT, &db));
  PetscCall(AppendStateRow(lat, z1, &row));
  if (!row.empty()) row.push_back(dT), row.push_back(db);
  start->next_tangent = std::move(row);
  start->next_ds = ds;
  PetscFunctionReturn(0);
}

} // namespace nltopo
