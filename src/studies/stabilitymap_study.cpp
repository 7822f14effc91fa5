// -study stabilitymap (issue 37; docs/studies/stabilitymap.md): where the NNMs
// of one branch are stable in the plane of E and a second parameter p (a
// lattice option, -cont_codim2_parameter). At each lattice size (-smap_cells)
// the branch is continued at the run's p with dense Floquet and its events
// located (as -study continuation -cont_bifurcations does); the events of the
// asked kinds are followed in (E, p) (stability/codim2.hpp), one curve per
// event that no curve followed already passes through; the curves label the
// raster of (p, E) regions (stability/stability_regions.hpp). At the first
// size, one-parameter branches at the -smap_check values of p are the brute
// force the map is checked against: their events and verdicts, with the map's
// label at each of their orbits. /stabilitymap of outputs.md.
#include "studies/nnm_setup.hpp"
#include "bands/bloch.hpp"
#include "core/bytes.hpp"
#include "core/errors.hpp"
#include "core/log.hpp"
#include "core/option_table.hpp"
#include "core/signals.hpp"
#include "io/output.hpp"
#include "io/schema.hpp"
#include "stability/bifurcation_locator.hpp"
#include "stability/codim2.hpp"
#include "stability/floquet_hooks.hpp"
#include "stability/stability_regions.hpp"
#include "studies/continuation_choices.hpp"
#include "studies/continuation_record.hpp"
#include "studies/event_orbit.hpp"
#include "studies/registry.hpp"
#include "studies/study.hpp"
#include <algorithm>
#include <cmath>
#include <memory>
#include <numeric>

namespace nltopo {

namespace {

constexpr const char *kRegionCodes = "0 stable; 1 B-B unstable; 2 B-E unstable; 3 E-E unstable";
constexpr const char *kCurveSideCodes = "1 left of its direction of travel; -1 right; 0 unknown (no direction, or vertical at its event)";
constexpr const char *kAgreeCodes = "1 the map's label equals the orbit's class; 0 it does not; -1 not compared (within -smap_same_curve_rtol of a curve, or "
                                    "outside [-smap_energy_min, -cont_energy_max])";

struct MapOptions {
  std::vector<PetscReal> cells{5};
  std::string branch = "insulated";
  std::vector<PetscReal> kinds{5, 2, 3};
  std::vector<PetscReal> classes{2, 3};
  std::vector<PetscReal> check;
  PetscInt raster_p = 121, raster_energy = 121;
  PetscReal energy_min = 0.1;
  PetscInt max_curves = 40;
  PetscReal same_curve_rtol = 1e-3;
  PetscBool seed_checks = PETSC_TRUE;
  PetscInt group_size = 1;
};

const auto &kMapTable = DeclareOptionTable<MapOptions>(
    "smap_", "Stability map in (p, E): event curves of one branch, regions, brute-force check", [](OptionTable<MapOptions> &t) {
      using M = MapOptions;
      t.RealList("cells", &M::cells, 4, Closed(1, 1e5),
                 "Cells per side of each lattice size mapped (N = 4 cells + 2 on the interface layout), integers; the first is the main map (the "
                 "-smap_check branches are compared with it), the others are drawn beside it to show where the map depends on N")
          .String("branch", &M::branch, "The branch whose stability is mapped, named as in -cont_branch (insulated, interface, ..., mode<k>)")
          .RealList("kinds", &M::kinds, 4, Closed(1, 5),
                    "The kinds of located events followed as curves, in the codes of /bifurcations kind: 1 energy fold, 2 branch point, 3 period "
                    "doubling, 5 Hamiltonian-Hopf onset (4, a pass of equal signatures, bounds no instability)")
          .RealList("classes", &M::classes, 3, Closed(1, 3),
                    "The instability classes whose events are followed (the critical eigenvector's localisation: 1 B-B, 2 B-E, 3 E-E); 3 alone maps "
                    "the interface's own instabilities, whose curves do not multiply with N")
          .RealList("check", &M::check, 16, Closed(-1e6, 1e6),
                    "Values of p (-cont_codim2_parameter) at which the branch is also continued as a one-parameter run at the first size: its events "
                    "and verdicts are the brute force the map is checked against (none: no check)",
                    OptionClass::Extent)
          .Default("none")
          .Int("raster_p", &M::raster_p, Closed(2, 100000), "Columns of the region raster, evenly over [-cont_codim2_min, -cont_codim2_max]", OptionClass::Extent)
          .Int("raster_energy", &M::raster_energy, Closed(2, 100000), "Rows of the region raster, log-spaced over [-smap_energy_min, -cont_energy_max]",
               OptionClass::Extent)
          .Real("energy_min", &M::energy_min, Open(0, 1e12), "The lowest energy of the region raster (the map's bottom)", OptionClass::Extent)
          .Int("max_curves", &M::max_curves, Closed(1, 10000), "Curves followed at most per lattice size (events past it are listed, not followed)",
               OptionClass::Extent)
          .Real("same_curve_rtol", &M::same_curve_rtol, Open(0, 1),
                "An event lies on a curve already followed (and is not followed again) when the curve crosses the run's p at the event's energy to "
                "this, relative")
          .Bool("seed_checks", &M::seed_checks,
                "An event of a -smap_check branch that no curve passes through starts a curve of its own (a bubble the run's p does not cross); 0: "
                "the checks only check")
          .Int("group_size", &M::group_size, Closed(1, 1000000),
               "Ranks per curve: the ranks in groups of this many consecutive ones (PetscSubcomm), each group following one curve at a time (as many "
               "curves at once as groups; the -smap_check branches likewise, one per group); must divide the number of ranks. The branches at the "
               "run's p use every rank",
               OptionClass::Bookkeeping);
    });

PetscErrorCode MapOptionsFromOptions(MPI_Comm comm, MapOptions *o)
{
  PetscFunctionBeginUser;
  PetscCall(kMapTable.Read(comm, o));
  PetscCheck(!o->cells.empty(), comm, PETSC_ERR_USER, "-smap_cells needs at least one size");
  for (PetscReal c : o->cells)
    PetscCheck(c == std::floor(c), comm, PETSC_ERR_USER, "-smap_cells %g: cells per side are integers", (double)c);
  for (PetscReal k : o->kinds)
    PetscCheck(k == 1 || k == 2 || k == 3 || k == 5, comm, PETSC_ERR_USER,
               "-smap_kinds %s: the kinds followed are 1 (energy fold), 2 (branch point), 3 (period doubling) and 5 (Hamiltonian-Hopf onset)",
               k == std::floor(k) ? std::to_string((long long)k).c_str() : std::to_string(k).c_str());
  PetscFunctionReturn(0);
}

// One followed event: its curve and the side of it where the instability lies.
struct MapCurve {
  Codim2Curve c;
  PetscInt event = 0, cls = 0, direction = 0, side = 0;
  PetscInt seed = -1; // where its event was located: -1 the branch at the run's p, k the check branch k (-smap_seed_checks)
};

// One lattice size: the branch at the run's p, its events and their curves, the raster.
struct SizeMap {
  PetscInt cells = 0, N = 0;
  PetscReal p = 0;
  Branch b;
  FloquetColumns f;
  std::vector<BifurcationEvent> events;
  std::vector<PetscInt> event_curve; // per event: the curve it lies on (-1 not a kind followed, -2 not followed: -smap_max_curves or a failure)
  std::vector<MapCurve> curves;
  std::vector<PetscInt> label;
  PetscInt inconsistent = 0;
  PetscReal seconds = 0;
};

// One brute-force branch at p = -smap_check value.
struct CheckRun {
  PetscReal p = 0;
  Branch b;
  FloquetColumns f;
  std::vector<BifurcationEvent> events;
  std::vector<PetscInt> map_label, agree;
  std::vector<PetscInt> event_curve; // per event: as SizeMap's (the first size's curves)
  std::vector<PetscReal> event_offset; // per event: relative E distance to the nearest crossing of a curve of its kind at p
  PetscReal seconds = 0;
};

// Ranks that work together: comm, split into groups (group: this rank's) of
// group_size consecutive ranks; each group follows one curve at a time.
struct Team {
  MPI_Comm comm, group;
  PetscInt groups, my_group, group_size;
};

void MapCurveFields(MapCurve &m, Bytes &w, bool put)
{
  Codim2CurveFields(m.c, w, put);
  w.Field(m.event, put), w.Field(m.cls, put), w.Field(m.direction, put), w.Field(m.side, put), w.Field(m.seed, put);
}

// A check branch, the curves its events seeded and its failure ("" none), as bytes or from them.
void CheckFields(CheckRun &cr, std::vector<MapCurve> &seeds, std::string &failure, Bytes &w, bool put)
{
  w.Field(failure, put), w.Field(cr.p, put), w.Field(cr.seconds, put), w.Field(cr.b.energy, put), w.Field(cr.b.omega, put);
  w.Field(cr.f.instability, put), w.Field(cr.event_curve, put);
  size_t n = cr.events.size(), ns = seeds.size();
  w.Field(n, put), w.Field(ns, put);
  cr.events.resize(n), seeds.resize(ns);
  for (BifurcationEvent &e : cr.events) { // (not its critical vector: the map draws no eigenvectors)
    w.Field(e.kind, put), w.Field(e.direction, put), w.Field(e.point, put), w.Field(e.energy, put), w.Field(e.omega, put), w.Field(e.s, put);
    w.Field(e.omega_bracket, put), w.Field(e.mu_re, put), w.Field(e.mu_im, put), w.Field(e.krein, put), w.Field(e.instability, put);
    w.Field(e.sigma, put), w.Field(e.resonance, put);
  }
  for (MapCurve &m : seeds) MapCurveFields(m, w, put);
}

// The branch of nnm (built) continued with dense Floquet, its events located.
PetscErrorCode BranchWithEvents(MPI_Comm comm, NnmSetup &nnm, const std::string &branch, const FloquetOptions &flo, const BifurcationOptions &bo,
                                BifurcationLocator *loc, Branch *b, FloquetColumns *f, std::vector<BifurcationEvent> *events)
{
  OwnedVec u;
  PetscReal omega;
  std::string label;
  PetscFunctionBeginUser;
  PetscCall(DMCreateGlobalVector(nnm.lat.SiteDM(), u.out()));
  PetscCall(BranchStart(nnm.lat, nnm.modes, branch.c_str(), u, &omega, &label));
  FloquetHook hook(nnm.flow, flo);
  PetscCall(ContinueBranch(nnm.shoot, u, 2 * PETSC_PI / omega, nnm.co, label.c_str(), b, &hook));
  PetscCall(loc->Setup(nnm.shoot, flo, bo));
  loc->SetProgress(nnm.co.progress);
  PetscCall(loc->Locate(*b, hook.c.re, hook.c.im, hook.c.edge, label.c_str(), events, hook.c.krein));
  *f = std::move(hook.c);
  PetscFunctionReturn(0);
}

// A branch's located events as the event_* columns of group g.
PetscErrorCode WriteEvents(PetscViewer v, const char *g, const std::vector<BifurcationEvent> &events)
{
  std::vector<PetscInt> kind, cls, dir;
  std::vector<PetscReal> E, w;
  PetscFunctionBeginUser;
  for (const BifurcationEvent &e : events)
    kind.push_back((PetscInt)e.kind), cls.push_back(e.instability), dir.push_back(e.direction), E.push_back(e.energy), w.push_back(e.omega);
  PetscCall(WriteArray(v, g, "event_energy", E));
  PetscCall(WriteArray(v, g, "event_omega", w));
  PetscCall(WriteIntArray(v, g, "event_kind", kind));
  PetscCall(WriteIntArray(v, g, "event_class", cls));
  PetscCall(WriteIntArray(v, g, "event_direction", dir));
  PetscFunctionReturn(0);
}

RegionCurve AsRegion(const MapCurve &m)
{
  RegionCurve r;
  r.p = m.c.p, r.energy = m.c.energy, r.cls = m.cls, r.side = m.side;
  return r;
}

// Relative distance in E from (p, E) to the nearest crossing of the column p by a curve of kind k (+inf: none crosses).
PetscReal OffsetToCurves(const std::vector<MapCurve> &curves, EventKind k, PetscReal p, PetscReal energy)
{
  PetscReal best = INFINITY;
  for (const MapCurve &m : curves) {
    if (m.c.kind != k) continue;
    for (const Crossing &x : ColumnCrossings(AsRegion(m), p)) best = std::min(best, std::abs(x.energy - energy) / energy);
  }
  return best;
}

class StabilityMapStudy : public Study {
protected:
  PetscErrorCode ReadOptions() override
  {
    PetscFunctionBeginUser;
    PetscCall(base_.ReadOptions(comm_));
    if (!declaring_) PetscCall(RejectGivenOptions(comm_, {"-lattice_cells", "-cont_codim2"}, "-study stabilitymap (-smap_cells, -smap_kinds)"));
    PetscCall(FloquetOptionsFromOptions(comm_, &flo_));
    PetscCall(BifurcationOptionsFromOptions(comm_, PETSC_TRUE, &bo_));
    PetscCall(Codim2OptionsFromOptions(comm_, &c2o_, &c2spec_));
    PetscCall(MapOptionsFromOptions(comm_, &mo_));
    if (declaring_) PetscFunctionReturn(0);
    PetscCheck(bo_.enabled, comm_, PETSC_ERR_USER, "-study stabilitymap locates the branch's events: -cont_bifurcations 0 cannot be given");
    PetscCheck(base_.so.jacobian == ShootingJacobian::Dense, comm_, PETSC_ERR_USER,
               "-study stabilitymap needs -nnm_jacobian dense (the curves' test functions factor the shooting Jacobian)");
    PetscCheck(c2o_.pmin > -1e6 && c2o_.pmax < 1e6, comm_, PETSC_ERR_USER,
               "-study stabilitymap needs -cont_codim2_min and -cont_codim2_max: the window of %s the map covers", Codim2ParameterOption(c2o_.parameter));
    const PetscReal p = Codim2ParameterValue(base_.lp, c2o_.parameter);
    PetscCheck(p >= c2o_.pmin && p <= c2o_.pmax, comm_, PETSC_ERR_USER, "-study stabilitymap: the run's %s %g lies outside [-cont_codim2_min %g, -cont_codim2_max %g]",
               Codim2ParameterOption(c2o_.parameter), (double)p, (double)c2o_.pmin, (double)c2o_.pmax);
    for (PetscReal q : mo_.check)
      PetscCheck(q >= c2o_.pmin && q <= c2o_.pmax, comm_, PETSC_ERR_USER, "-smap_check %g lies outside [-cont_codim2_min %g, -cont_codim2_max %g]", (double)q,
                 (double)c2o_.pmin, (double)c2o_.pmax);
    PetscCheck(mo_.energy_min < base_.co.energy_max, comm_, PETSC_ERR_USER, "-smap_energy_min %g must lie below -cont_energy_max %g", (double)mo_.energy_min,
               (double)base_.co.energy_max);
    // the curves end where they leave the map's window of E (their first point outside kept)
    c2o_.emin = std::max(c2o_.emin, mo_.energy_min), c2o_.emax = std::min(c2o_.emax, base_.co.energy_max);
    PetscFunctionReturn(0);
  }
  PetscErrorCode DeclareSolvers(MPI_Comm comm) override
  {
    PetscFunctionBeginUser;
    PetscCall(base_.DeclareSolvers(comm));
    PetscCall(DeclareEPS(comm, "floquet_"));
    PetscFunctionReturn(0);
  }
  PetscErrorCode CheckResources() override
  {
    PetscFunctionBeginUser;
    for (PetscReal c : mo_.cells) {
      NnmSetup s;
      Adopt(&s, (PetscInt)c, Codim2ParameterValue(base_.lp, c2o_.parameter));
      PetscCall(s.CheckResources(comm_));
    }
    PetscFunctionReturn(0);
  }
  PetscErrorCode Build() override
  {
    PetscMPIInt size, rank;
    PetscFunctionBeginUser;
    PetscCallMPI(MPI_Comm_size(comm_, &size));
    PetscCallMPI(MPI_Comm_rank(comm_, &rank));
    PetscCheck(size % mo_.group_size == 0, comm_, PETSC_ERR_USER, "-smap_group_size %" PetscInt_FMT " must divide the number of ranks (%d)", mo_.group_size,
               size);
    groups_ = size / mo_.group_size, my_group_ = rank / mo_.group_size;
    PetscCall(PetscSubcommCreate(comm_, &subcomm_));
    PetscCall(PetscSubcommSetNumber(subcomm_, groups_));
    PetscCall(PetscSubcommSetType(subcomm_, PETSC_SUBCOMM_CONTIGUOUS));
    group_ = PetscSubcommChild(subcomm_);
    for (PetscInt i = 0; i < mo_.raster_p; i++) p_.push_back(c2o_.pmin + (c2o_.pmax - c2o_.pmin) * i / (mo_.raster_p - 1));
    const PetscReal l0 = std::log(mo_.energy_min), l1 = std::log(base_.co.energy_max);
    for (PetscInt j = 0; j < mo_.raster_energy; j++) energy_.push_back(std::exp(l0 + (l1 - l0) * j / (mo_.raster_energy - 1)));
    PetscFunctionReturn(0);
  }
  PetscErrorCode Solve() override
  {
    PetscFunctionBeginUser;
    PetscCall(PetscPrintf(comm_, "nltopo stabilitymap: branch %s in (E, %s), %s in [%g, %g], %zu size(s), %zu check branch(es)\n", mo_.branch.c_str(),
                          Codim2ParameterOption(c2o_.parameter), Codim2ParameterOption(c2o_.parameter), (double)c2o_.pmin, (double)c2o_.pmax,
                          mo_.cells.size(), mo_.check.size()));
    for (PetscReal c : mo_.cells) PetscCall(MapSize((PetscInt)c));
    PetscCall(Checks());
    PetscCall(Label());
    PetscFunctionReturn(0);
  }
  // A stop signal: the sizes whose branch is done, with the curves followed so far, and the checks done.
  bool Interrupted(Interruption *it) const override
  {
    it->partial = !sizes_.empty();
    it->where = "after " + std::to_string(sizes_.size()) + " of " + std::to_string(mo_.cells.size()) + " sizes' branches (" +
                std::to_string(sizes_.empty() ? 0 : sizes_.back().curves.size()) + " curves of the last) and " + std::to_string(checks_.size()) + " of " +
                std::to_string(mo_.check.size()) + " checks";
    return true;
  }
  PetscErrorCode Write(PetscViewer v) override;

private:
  void Adopt(NnmSetup *s, PetscInt cells, PetscReal p) const
  {
    s->lp = base_.lp, s->mo = base_.mo, s->fo = base_.fo, s->so = base_.so, s->co = base_.co;
    s->lp.cells = cells;
    SetCodim2Parameter(&s->lp, c2o_.parameter, p);
  }
  bool Followed(const BifurcationEvent &e) const
  {
    bool kind = false, cls = e.instability == 0; // (a fold has no class)
    for (PetscReal q : mo_.kinds) kind = kind || (PetscInt)q == (PetscInt)e.kind;
    for (PetscReal q : mo_.classes) cls = cls || (PetscInt)q == e.instability;
    return kind && cls;
  }
  // The curve of sm.curves that event e (located at p) lies on, -1 none: one that crosses
  // p again (away from its own event: the segments next to its event row
  // are left out) at e's energy.
  PetscInt CurveThrough(const SizeMap &sm, const BifurcationEvent &e, PetscReal p) const
  {
    for (size_t k = 0; k < sm.curves.size(); k++) {
      const MapCurve &m = sm.curves[k];
      if (m.c.kind != e.kind) continue;
      const size_t ev = (size_t)m.c.event_point;
      for (int part = 0; part < 2; part++) { // rows before and after the event row
        MapCurve piece;
        piece.c.kind = m.c.kind;
        const size_t lo = part == 0 ? 0 : ev + 1, hi = part == 0 ? ev : m.c.p.size(); // [lo, hi)
        for (size_t r = lo; r < hi; r++) piece.c.p.push_back(m.c.p[r]), piece.c.energy.push_back(m.c.energy[r]);
        if (OffsetToCurves({piece}, e.kind, p, e.energy) <= mo_.same_curve_rtol) return (PetscInt)k;
      }
    }
    return -1;
  }
  PetscErrorCode MapSize(PetscInt cells);
  PetscErrorCode FollowEvents(const Team &t, NnmSetup &nnm, BifurcationLocator &loc, const std::vector<BifurcationEvent> &events, PetscReal p, PetscInt seed,
                              SizeMap *sm, std::vector<PetscInt> *event_curve);
  PetscErrorCode PickRound(const Team &t, NnmSetup &nnm, BifurcationLocator &loc, const std::vector<BifurcationEvent> &events, PetscReal p, PetscInt seed,
                           SizeMap *sm, std::vector<PetscInt> *event_curve, std::vector<size_t> *pending, std::vector<size_t> *round,
                           std::vector<Codim2Start> *starts);
  PetscErrorCode FollowRound(const Team &t, NnmSetup &nnm, const std::vector<BifurcationEvent> &events, const std::vector<size_t> &round,
                             const std::vector<Codim2Start> &starts, const std::string &label, std::vector<Codim2Curve> *got, std::vector<std::string> *failed);
  PetscErrorCode Checks();
  PetscErrorCode RunCheck(const Team &t, PetscReal p, PetscInt seed, CheckRun *cr, std::vector<MapCurve> *seeds, std::string *failure);
  void MergeCheck(CheckRun cr, std::vector<MapCurve> seeds, size_t first_seed_row);
  Team All() const { return {comm_, group_, groups_, my_group_, mo_.group_size}; }
  PetscErrorCode Label();
  PetscErrorCode WriteSize(PetscViewer v, const SizeMap &sm) const;
  PetscErrorCode WriteCheck(PetscViewer v, size_t k, const CheckRun &cr) const;
  PetscErrorCode WriteAxes(PetscViewer v) const;

  NnmSetup base_; // the options; each size and check builds its own NnmSetup from them
  FloquetOptions flo_;
  BifurcationOptions bo_;
  Codim2Options c2o_;
  Codim2Spec c2spec_;
  MapOptions mo_;
  std::vector<PetscReal> p_, energy_; // the raster's axes
  std::vector<SizeMap> sizes_;
  std::vector<CheckRun> checks_;
  bool labelled_ = false;
  PetscSubcomm subcomm_ = nullptr;   // -smap_group_size: the groups of ranks that follow curves
  MPI_Comm group_ = MPI_COMM_NULL;   // this rank's group
  PetscInt groups_ = 1, my_group_ = 0;

public:
  ~StabilityMapStudy() override { PetscSubcommDestroy(&subcomm_); }
};

PetscErrorCode StabilityMapStudy::MapSize(PetscInt cells)
{
  PetscLogDouble t0, t1;
  BifurcationLocator loc;
  PetscFunctionBeginUser;
  PetscCall(PetscTime(&t0));
  SizeMap sm;
  sm.cells = cells, sm.p = Codim2ParameterValue(base_.lp, c2o_.parameter);
  auto nnm = std::make_unique<NnmSetup>();
  Adopt(nnm.get(), cells, sm.p);
  PetscCall(nnm->Build(comm_, "-study stabilitymap"));
  sm.N = nnm->lat.N();
  PetscCall(PetscPrintf(comm_, "  [%s, N = %" PetscInt_FMT "] the branch at %s %g\n", mo_.branch.c_str(), sm.N, Codim2ParameterOption(c2o_.parameter), (double)sm.p));
  PetscCall(BranchWithEvents(comm_, *nnm, mo_.branch, flo_, bo_, &loc, &sm.b, &sm.f, &sm.events));
  sm.b.z0.clear(); // the orbits are -study continuation's to keep; the map keeps its columns
  sizes_.push_back(std::move(sm)); // from here a stop signal writes the curves done (Interrupted)
  SizeMap &done = sizes_.back();
  PetscCall(FollowEvents(All(), *nnm, loc, done.events, done.p, -1, &done, &done.event_curve));
  PetscCall(PetscTime(&t1));
  done.seconds = t1 - t0;
  PetscCall(PetscPrintf(comm_, "  [%s, N = %" PetscInt_FMT "] %zu events, %zu curves, %.1f s\n", mo_.branch.c_str(), done.N, done.events.size(),
                        done.curves.size(), (double)done.seconds));
  PetscFunctionReturn(0);
}

// The events (located at p; seed: -1 the run's branch, k check k) of the kinds
// followed, in order; each one no curve of sm passes through starts a curve
// (its instability's side from the event's direction). event_curve: per event,
// the curve it lies on or starts (-1 not a kind followed, -2 not followed).
// The curves are followed in rounds, one event per group of ranks
// (-smap_group_size); an event whose curve an earlier one of its round passes
// through was followed twice, and is then counted as lying on that curve.
PetscErrorCode StabilityMapStudy::FollowEvents(const Team &t, NnmSetup &nnm, BifurcationLocator &loc, const std::vector<BifurcationEvent> &events, PetscReal p,
                                               PetscInt seed, SizeMap *sm, std::vector<PetscInt> *event_curve)
{
  PetscFunctionBeginUser;
  event_curve->assign(events.size(), -1);
  for (size_t k = 0; k < events.size(); k++)
    if (Followed(events[k])) (*event_curve)[k] = -2; // (until followed: what a stop signal leaves)
  const std::string label = mo_.branch + " N=" + std::to_string(sm->N);
  const size_t n0 = sm->curves.size();
  std::vector<size_t> pending; // the events of the kinds followed, neither on a curve nor followed yet
  for (size_t k = 0; k < events.size(); k++)
    if (Followed(events[k])) pending.push_back(k);
  while (!pending.empty()) {
    std::vector<size_t> round; // the round: at most one event per group
    std::vector<Codim2Start> starts;
    PetscCall(PickRound(t, nnm, loc, events, p, seed, sm, event_curve, &pending, &round, &starts));
    std::vector<Codim2Curve> got;
    std::vector<std::string> failed;
    PetscCall(FollowRound(t, nnm, events, round, starts, label, &got, &failed));
    for (size_t j = 0; j < round.size(); j++) {
      const size_t k = round[j];
      const BifurcationEvent &e = events[k];
      if (!failed[j].empty()) { // a numerical failure of one curve (its start not found again): listed, not followed; the map goes on
        PetscCall(PetscPrintf(t.comm, "  [N = %" PetscInt_FMT "] warning: event %zu (omega %g) not followed: %s\n", sm->N, k, (double)e.omega, failed[j].c_str()));
        continue;
      }
      const PetscInt on = j > 0 ? CurveThrough(*sm, e, p) : -1;
      if (on >= 0) {
        (*event_curve)[k] = on;
        PetscCall(PetscPrintf(t.comm, "  [N = %" PetscInt_FMT "] event %zu (%s, omega %.7f) lies on curve %s (followed in the same round)\n", sm->N, k,
                              EventKindName(e.kind), (double)e.omega, sm->curves[on].c.name.c_str()));
        continue;
      }
      MapCurve m;
      m.event = (PetscInt)k, m.cls = e.instability, m.direction = e.direction, m.seed = seed;
      m.c = std::move(got[j]);
      if (seed >= 0) m.c.name = "check" + std::to_string(seed) + "_" + m.c.name; // (its event's row is the check branch's)
      m.side = UnstableSide(AsRegion(m), m.c.event_point, m.direction);
      (*event_curve)[k] = (PetscInt)sm->curves.size();
      sm->curves.push_back(std::move(m));
    }
  }
  // the new curves in the order of their events, whatever the rounds were (the same rows at any number of groups)
  std::vector<size_t> order(sm->curves.size() - n0), row(order.size());
  std::iota(order.begin(), order.end(), n0);
  std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) { return sm->curves[a].event < sm->curves[b].event; });
  std::vector<MapCurve> sorted;
  for (size_t i = 0; i < order.size(); i++) row[order[i] - n0] = n0 + i, sorted.push_back(std::move(sm->curves[order[i]]));
  std::move(sorted.begin(), sorted.end(), sm->curves.begin() + (std::ptrdiff_t)n0);
  for (PetscInt &ec : *event_curve)
    if (ec >= (PetscInt)n0) ec = (PetscInt)row[ec - n0];
  PetscFunctionReturn(0);
}

// The next round from pending (in order; each pick removes from pending the
// events it takes, those a curve passes through, and those not followed):
// at most t.groups events no curve passes through, with their orbits. A
// round holds no two events of a kind and class in opposite directions
// (likely the two ends of one bubble: the later one waits, and the earlier's
// curve may pass through it) unless a group would otherwise be idle.
PetscErrorCode StabilityMapStudy::PickRound(const Team &t, NnmSetup &nnm, BifurcationLocator &loc, const std::vector<BifurcationEvent> &events, PetscReal p,
                                            PetscInt seed, SizeMap *sm, std::vector<PetscInt> *event_curve, std::vector<size_t> *pending,
                                            std::vector<size_t> *round, std::vector<Codim2Start> *starts)
{
  std::vector<size_t> open, chosen;
  PetscFunctionBeginUser;
  for (size_t k : *pending) {
    const BifurcationEvent &e = events[k];
    const PetscInt on = CurveThrough(*sm, e, p);
    if (on >= 0) {
      (*event_curve)[k] = on;
      PetscCall(PetscPrintf(t.comm, "  [N = %" PetscInt_FMT "] event %zu (%s, omega %.7f) lies on curve %s\n", sm->N, k, EventKindName(e.kind), (double)e.omega,
                            sm->curves[on].c.name.c_str()));
    } else if ((PetscInt)sm->curves.size() + (PetscInt)open.size() < mo_.max_curves && !(seed >= 0 && !mo_.seed_checks)) open.push_back(k);
  }
  auto paired = [&](size_t k) {
    for (size_t j : chosen)
      if (events[j].kind == events[k].kind && events[j].instability == events[k].instability && events[j].direction == -events[k].direction) return true;
    return false;
  };
  for (bool strict : {true, false})
    for (size_t k : open)
      if ((PetscInt)chosen.size() < t.groups && std::find(chosen.begin(), chosen.end(), k) == chosen.end() && !(strict && paired(k))) chosen.push_back(k);
  std::sort(chosen.begin(), chosen.end());
  pending->clear();
  for (size_t k : open)
    if (std::find(chosen.begin(), chosen.end(), k) == chosen.end()) pending->push_back(k);
  for (size_t k : chosen) {
    Codim2Start st;
    bool found;
    PetscCall(EventOrbit(t.comm, loc, nnm, events[k], &st, &found));
    if (!found) {
      PetscCall(PetscPrintf(t.comm, "  [N = %" PetscInt_FMT "] warning: the orbit of event %zu (omega %g) was not found again; not followed\n", sm->N, k,
                            (double)events[k].omega));
      continue;
    }
    round->push_back(k), starts->push_back(std::move(st));
  }
  PetscFunctionReturn(0);
}

// Group j follows the curve of events[round[j]] from starts[j] on its ranks;
// every rank gets every curve (got), or its failure's message (failed, "" for
// none). A stop signal in any group stops every rank (PETSC_ERR_SIG) after the round.
PetscErrorCode StabilityMapStudy::FollowRound(const Team &t, NnmSetup &nnm, const std::vector<BifurcationEvent> &events, const std::vector<size_t> &round,
                                              const std::vector<Codim2Start> &starts, const std::string &label, std::vector<Codim2Curve> *got,
                                              std::vector<std::string> *failed)
{
  Codim2Curve mine;
  PetscErrorCode ierr = 0;
  char msg[512] = "";
  PetscFunctionBeginUser;
  if ((size_t)t.my_group < round.size()) {
    const size_t k = round[t.my_group];
    PetscCall(CaptureError(
        [&]() { return ContinueCodim2(t.group, nnm.lp, nnm.fo, nnm.so, flo_, 1, c2o_, events[k], (PetscInt)k, starts[t.my_group], label.c_str(), &mine); },
        &ierr, msg, sizeof msg));
  }
  PetscInt sig = IsInterrupt(ierr) ? 1 : 0;
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &sig, 1, MPIU_INT, MPI_MAX, t.comm));
  if (sig) SETERRQ(t.comm, PETSC_ERR_SIG, "stopped while following curves");
  got->assign(round.size(), Codim2Curve()), failed->assign(round.size(), "");
  for (size_t j = 0; j < round.size(); j++) { // from the group's first rank to every rank
    Bytes w;
    std::string why = ierr ? (msg[0] ? msg : "failed") : "";
    if ((size_t)t.my_group == j) w.Field(why, true), Codim2CurveFields(mine, w, true);
    PetscCall(w.Bcast(t.comm, (PetscMPIInt)(j * t.group_size)));
    w.Field((*failed)[j], false), Codim2CurveFields((*got)[j], w, false);
  }
  PetscFunctionReturn(0);
}

// The brute force: the branches at the -smap_check values of p, one per group
// of ranks at a time (RunCheck), each with the curves its events seeded;
// every rank gets every check (in order) and its seeded curves (MergeCheck).
PetscErrorCode StabilityMapStudy::Checks()
{
  const Team solo{group_, group_, 1, 0, mo_.group_size};
  PetscFunctionBeginUser;
  for (size_t r0 = 0; r0 < mo_.check.size(); r0 += (size_t)groups_) {
    const size_t n = std::min(mo_.check.size() - r0, (size_t)groups_), first_seed_row = sizes_.front().curves.size();
    CheckRun mine;
    std::vector<MapCurve> seeds;
    std::string failure;
    PetscErrorCode ierr = 0;
    char msg[512] = "";
    if ((size_t)my_group_ < n) {
      const size_t j = r0 + (size_t)my_group_;
      PetscCall(CaptureError([&]() { return RunCheck(solo, mo_.check[j], (PetscInt)j, &mine, &seeds, &failure); }, &ierr, msg, sizeof msg));
      if (ierr && !IsInterrupt(ierr)) failure = msg;
    }
    PetscInt sig = IsInterrupt(ierr) ? 1 : 0;
    PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &sig, 1, MPIU_INT, MPI_MAX, comm_));
    if (sig) SETERRQ(comm_, PETSC_ERR_SIG, "stopped in the check branches");
    for (size_t j = 0; j < n; j++) {
      Bytes w;
      CheckRun cr;
      std::vector<MapCurve> sd;
      std::string why;
      if ((size_t)my_group_ == j) CheckFields(mine, seeds, failure, w, true);
      PetscCall(w.Bcast(comm_, (PetscMPIInt)(j * mo_.group_size)));
      CheckFields(cr, sd, why, w, false);
      if (!why.empty()) { // a numerical failure of one check branch: said, left out; the map and the other checks go on
        PetscCall(PetscPrintf(comm_, "  [check %s %g] warning: the branch failed (%s); this check is left out\n", Codim2ParameterOption(c2o_.parameter),
                              (double)mo_.check[r0 + j], why.c_str()));
        continue;
      }
      MergeCheck(std::move(cr), std::move(sd), first_seed_row);
    }
  }
  PetscFunctionReturn(0);
}

// The brute force at p on team t: the branch as a one-parameter run at the
// first size; the curves its events seed (seed: the check's index among
// -smap_check) into seeds, not into the first size's curves (MergeCheck puts
// them there). A failure of the branch: *failure, and no error.
PetscErrorCode StabilityMapStudy::RunCheck(const Team &t, PetscReal p, PetscInt seed, CheckRun *cr, std::vector<MapCurve> *seeds, std::string *failure)
{
  PetscLogDouble t0, t1;
  BifurcationLocator loc;
  PetscFunctionBeginUser;
  PetscCall(PetscTime(&t0));
  SizeMap &sm = sizes_.front();
  cr->p = p;
  auto nnm = std::make_unique<NnmSetup>();
  Adopt(nnm.get(), sm.cells, p);
  PetscCall(nnm->Build(t.comm, "-study stabilitymap"));
  PetscCall(PetscPrintf(t.comm, "  [check, N = %" PetscInt_FMT "] the branch at %s %g\n", sm.N, Codim2ParameterOption(c2o_.parameter), (double)p));
  PetscErrorCode ierr = 0;
  char msg[512];
  PetscCall(CaptureError([&]() { return BranchWithEvents(t.comm, *nnm, mo_.branch, flo_, bo_, &loc, &cr->b, &cr->f, &cr->events); }, &ierr, msg, sizeof msg));
  if (IsInterrupt(ierr)) SETERRQ(t.comm, PETSC_ERR_SIG, "%s", msg);
  if (ierr) {
    *failure = msg;
    PetscFunctionReturn(0);
  }
  const size_t n0 = sm.curves.size();
  PetscCall(FollowEvents(t, *nnm, loc, cr->events, p, seed, &sm, &cr->event_curve));
  seeds->assign(std::make_move_iterator(sm.curves.begin() + n0), std::make_move_iterator(sm.curves.end()));
  sm.curves.resize(n0); // (every rank's first size keeps the same curves until MergeCheck)
  PetscCall(PetscTime(&t1));
  cr->seconds = t1 - t0;
  cr->b.z0.clear();
  PetscFunctionReturn(0);
}

// Check cr (run with the first size's first_seed_row curves: its event_curve
// rows from there on are its seeds) joins checks_; a seed that a curve merged
// since passes through (another check of its round seeded the same bubble)
// is dropped for that curve, the others join the first size's curves.
void StabilityMapStudy::MergeCheck(CheckRun cr, std::vector<MapCurve> seeds, size_t first_seed_row)
{
  SizeMap &sm = sizes_.front();
  const PetscInt idx = (PetscInt)checks_.size();
  std::vector<PetscInt> row(seeds.size()); // each seed's row in the first size's curves
  for (size_t i = 0; i < seeds.size(); i++) {
    MapCurve &m = seeds[i];
    const PetscInt on = CurveThrough(sm, cr.events[m.event], cr.p);
    if (on >= 0) {
      row[i] = on;
      continue;
    }
    const size_t cut = m.c.name.find('_');
    m.seed = idx, m.c.name = "check" + std::to_string(idx) + (cut == std::string::npos ? "_" + m.c.name : m.c.name.substr(cut));
    row[i] = (PetscInt)sm.curves.size();
    sm.curves.push_back(std::move(m));
  }
  for (PetscInt &ec : cr.event_curve)
    if (ec >= (PetscInt)first_seed_row) ec = row[ec - first_seed_row];
  checks_.push_back(std::move(cr));
}

// The raster of each size from its curves; each check orbit's class against
// the first size's label there, each check event's distance to its curves.
PetscErrorCode StabilityMapStudy::Label()
{
  PetscFunctionBeginUser;
  labelled_ = true;
  for (SizeMap &sm : sizes_) {
    std::vector<RegionCurve> rc;
    for (const MapCurve &m : sm.curves) rc.push_back(AsRegion(m));
    sm.label = LabelRegions(rc, p_, energy_, &sm.inconsistent);
    PetscCall(PetscPrintf(comm_, "  [N = %" PetscInt_FMT "] %zu curves; %" PetscInt_FMT " of %zu raster columns inconsistent\n", sm.N, sm.curves.size(), sm.inconsistent,
                          p_.size()));
  }
  const SizeMap &sm = sizes_.front();
  std::vector<RegionCurve> rc;
  for (const MapCurve &m : sm.curves) rc.push_back(AsRegion(m));
  for (CheckRun &cr : checks_) {
    PetscInt agree = 0, compared = 0;
    cr.map_label.clear(), cr.agree.clear(), cr.event_offset.clear();
    for (size_t i = 0; i < cr.b.energy.size(); i++) {
      const PetscReal E = cr.b.energy[i];
      // the orbit's class, where the map follows that class (-smap_classes); else stable for the map
      PetscInt got = cr.f.instability[i];
      bool mapped = false;
      for (PetscReal q : mo_.classes) mapped = mapped || (PetscInt)q == got;
      if (!mapped) got = 0;
      const PetscInt lab = LabelAt(rc, cr.p, E);
      // orbits within -smap_same_curve_rtol of a boundary are not compared (either side is right within the map's resolution)
      bool near = false;
      for (const RegionCurve &r : rc)
        for (const Crossing &x : ColumnCrossings(r, cr.p)) near = near || std::abs(x.energy - E) <= mo_.same_curve_rtol * E;
      const PetscInt a = near || E < mo_.energy_min || E > base_.co.energy_max ? -1 : (lab == got ? 1 : 0); // (outside the map's window: not mapped)
      cr.map_label.push_back(lab), cr.agree.push_back(a);
      if (a >= 0) compared++, agree += a;
    }
    for (const BifurcationEvent &e : cr.events) cr.event_offset.push_back(OffsetToCurves(sm.curves, e.kind, cr.p, e.energy));
    PetscCall(PetscPrintf(comm_, "  [check %s %g] %zu events; the map's label agrees with the branch's verdict at %" PetscInt_FMT " of %" PetscInt_FMT " orbits\n",
                          Codim2ParameterOption(c2o_.parameter), (double)cr.p, cr.events.size(), agree, compared));
  }
  PetscFunctionReturn(0);
}

PetscErrorCode StabilityMapStudy::Write(PetscViewer v)
{
  PetscFunctionBeginUser;
  if (!labelled_) PetscCall(Label()); // (a stop signal: the regions of the curves done)
  PetscCall(WriteAttr(v, "/stabilitymap", "branch", mo_.branch.c_str()));
  PetscCall(WriteAttr(v, "/stabilitymap", "parameter", Codim2ParameterOption(c2o_.parameter)));
  PetscCall(WriteAttr(v, "/stabilitymap", "p_base", Codim2ParameterValue(base_.lp, c2o_.parameter)));
  PetscCall(WriteAttr(v, "/stabilitymap", "sizes", (PetscInt)sizes_.size()));
  PetscCall(WriteAttr(v, "/stabilitymap", "checks", (PetscInt)checks_.size()));
  PetscCall(WriteAxes(v));
  for (const SizeMap &sm : sizes_) PetscCall(WriteSize(v, sm));
  for (size_t k = 0; k < checks_.size(); k++) PetscCall(WriteCheck(v, k, checks_[k]));
  PetscFunctionReturn(0);
}

// The raster's axes, and per p the linear band edges and the insulated mode's decay length.
PetscErrorCode StabilityMapStudy::WriteAxes(PetscViewer v) const
{
  std::vector<PetscReal> ab, at, ob, ot, decay;
  PetscFunctionBeginUser;
  for (PetscReal p : p_) {
    LatticeParams lp = base_.lp;
    SetCodim2Parameter(&lp, c2o_.parameter, p);
    const BandEdges be = InfiniteBandEdges(lp);
    ab.push_back(be.acoustic_bottom), at.push_back(be.acoustic_top), ob.push_back(be.optical_bottom), ot.push_back(be.optical_top);
    // the insulated mode's amplitude changes by -k2/k1 per cell (docs/model.md): decay length 1 / ln(k1/k2) cells
    decay.push_back(lp.K1() > lp.K2() && lp.K2() > 0 ? 1 / std::log(lp.K1() / lp.K2()) : INFINITY);
  }
  PetscCall(WriteArray(v, "/stabilitymap", "p", p_));
  PetscCall(WriteArray(v, "/stabilitymap", "energy", energy_));
  PetscCall(WriteArray(v, "/stabilitymap", "acoustic_bottom", ab));
  PetscCall(WriteArray(v, "/stabilitymap", "acoustic_top", at));
  PetscCall(WriteArray(v, "/stabilitymap", "optical_bottom", ob));
  PetscCall(WriteArray(v, "/stabilitymap", "optical_top", ot));
  PetscCall(WriteArray(v, "/stabilitymap", "decay_cells", decay));
  PetscFunctionReturn(0);
}

PetscErrorCode StabilityMapStudy::WriteSize(PetscViewer v, const SizeMap &sm) const
{
  const std::string g = "/stabilitymap/cells" + std::to_string(sm.cells);
  const char *gc = g.c_str();
  std::vector<PetscInt> ck, ccls, cdir, cside, cev, cpts, cseed;
  std::string names;
  PetscFunctionBeginUser;
  for (const MapCurve &m : sm.curves) {
    ck.push_back((PetscInt)m.c.kind), ccls.push_back(m.cls), cdir.push_back(m.direction), cside.push_back(m.side), cev.push_back(m.event),
        cpts.push_back((PetscInt)m.c.p.size()), cseed.push_back(m.seed);
    names += (names.empty() ? "" : ",") + m.c.name;
  }
  PetscCall(WriteAttr(v, gc, "cells", sm.cells));
  PetscCall(WriteAttr(v, gc, "N", sm.N));
  PetscCall(WriteAttr(v, gc, "curves", names.c_str()));
  PetscCall(WriteAttr(v, gc, "inconsistent_columns", sm.inconsistent));
  PetscCall(WriteAttr(v, gc, "seconds", sm.seconds));
  PetscCall(WriteIntArray(v, gc, "region", sm.label, (PetscInt)energy_.size(), true));
  PetscCall(WriteArray(v, gc, "branch_energy", sm.b.energy));
  PetscCall(WriteArray(v, gc, "branch_omega", sm.b.omega));
  PetscCall(WriteIntArray(v, gc, "branch_instability", sm.f.instability));
  PetscCall(WriteEvents(v, gc, sm.events));
  PetscCall(WriteIntArray(v, gc, "event_curve", sm.event_curve));
  PetscCall(WriteIntArray(v, gc, "curve_kind", ck));
  PetscCall(WriteIntArray(v, gc, "curve_class", ccls));
  PetscCall(WriteIntArray(v, gc, "curve_direction", cdir));
  PetscCall(WriteIntArray(v, gc, "curve_side", cside));
  PetscCall(WriteIntArray(v, gc, "curve_event", cev));
  PetscCall(WriteIntArray(v, gc, "curve_points", cpts));
  PetscCall(WriteIntArray(v, gc, "curve_seed", cseed));
  for (const MapCurve &m : sm.curves) PetscCall(WriteCodim2CurveAt(v, g + "/curves/" + m.c.name, "/stabilitymap/cells<c>/curves/<curve>", m.c));
  PetscFunctionReturn(0);
}

PetscErrorCode StabilityMapStudy::WriteCheck(PetscViewer v, size_t k, const CheckRun &cr) const
{
  const std::string g = "/stabilitymap/checks/check" + std::to_string(k);
  const char *gc = g.c_str();
  PetscFunctionBeginUser;
  PetscCall(WriteAttr(v, gc, "p", cr.p));
  PetscCall(WriteAttr(v, gc, "seconds", cr.seconds));
  PetscCall(WriteArray(v, gc, "energy", cr.b.energy));
  PetscCall(WriteArray(v, gc, "omega", cr.b.omega));
  PetscCall(WriteIntArray(v, gc, "instability", cr.f.instability));
  PetscCall(WriteIntArray(v, gc, "map_label", cr.map_label));
  PetscCall(WriteIntArray(v, gc, "agree", cr.agree));
  PetscCall(WriteEvents(v, gc, cr.events));
  PetscCall(WriteArray(v, gc, "event_offset", cr.event_offset));
  PetscCall(WriteIntArray(v, gc, "event_curve", cr.event_curve));
  PetscFunctionReturn(0);
}

} // namespace

// The event_* columns a size's branch and a check branch share (WriteEvents), after fields.
static std::vector<Field> WithEventFields(std::vector<Field> fields)
{
  using namespace schema_names;
  const std::vector<Field> ev = {
      {"event_energy", D, R, "nev", "energy", "the branch's located events (the branch at p_base, or the check's): energy"},
      {"event_omega", D, R, "nev", "rad/time", "the events' frequency"},
      {"event_kind", D, I, "nev", "1", "the events' kind", codes::kEventKind},
      {"event_class", D, I, "nev", "1", "the events' critical eigenvector class", codes::kInstability},
      {"event_direction", D, I, "nev", "1", "whether the event begins or ends an instability along the branch", codes::kDirection}};
  fields.insert(fields.end(), ev.begin(), ev.end());
  return fields;
}

StudyContract StabilityMapStudyContract()
{
  using namespace schema_names;
  return {WithPrefixes({NnmSetup::OptionPrefixes(), {"-floquet", "-smap_"}}),
          {{"/stabilitymap",
            "",
            {{"branch", A, S, "scalar", "1", "-smap_branch: the branch whose stability is mapped"},
             {"parameter", A, S, "scalar", "1", "the second parameter's option (-cont_codim2_parameter): -lattice_gamma, -lattice_k or -lattice_cubic"},
             {"p_base", A, R, "scalar", "1", "the run's own value of the parameter: the branches are continued and their events located there"},
             {"sizes", A, I, "scalar", "1", "lattice sizes mapped (groups cells<c>)"},
             {"checks", A, I, "scalar", "1", "brute-force branches (groups checks/check<k>)"},
             {"p", D, R, "np", "1 (the parameter's unit)", "the region raster's columns: the parameter, evenly over [-cont_codim2_min, -cont_codim2_max]"},
             {"energy", D, R, "ne", "energy", "the region raster's rows: energy, log-spaced over [-smap_energy_min, -cont_energy_max]"},
             {"acoustic_bottom", D, R, "np", "rad/time", "infinite-lattice acoustic band bottom at each p (linear, E -> 0)"},
             {"acoustic_top", D, R, "np", "rad/time", "infinite-lattice acoustic band top at each p"},
             {"optical_bottom", D, R, "np", "rad/time", "infinite-lattice optical band bottom at each p"},
             {"optical_top", D, R, "np", "rad/time", "infinite-lattice optical band top at each p"},
             {"decay_cells", D, R, "np", "cells",
              "decay length of the insulated mode at each p, 1 / ln(k1 / k2) cells (its amplitude changes by -k2/k1 per cell; inf where k1 <= k2): "
              "where it exceeds a quarter of a size's cells per side, that size's map is a finite-size one"}}},
           {"/stabilitymap/cells<c>",
            "",
            WithEventFields({{"cells", A, I, "scalar", "1", "cells per side"},
             {"N", A, I, "scalar", "1", "sites"},
             {"curves", A, S, "scalar", "1", "the names of the curves followed (groups curves/<curve>), comma-separated, in the order of the curve_* rows"},
             {"inconsistent_columns", A, I, "scalar", "1",
              "raster columns where a crossing closed an instability no crossing below had opened (a curve missing or ended inside the map); 0 "
              "when the curves bound every region"},
             {"seconds", A, R, "scalar", "s", "wall time of this size (branch, events, curves)"},
             {"region", D, I, "np x ne", "1",
              "the label of each raster point (p column, energy row) from the curves: 0 stable, 2 B-E, 3 E-E unstable (E-E wins where both are open; 1 "
              "B-B only with -cont_bif_bulk)",
              kRegionCodes},
             {"branch_energy", D, R, "npts", "energy", "the branch at p_base: energy of each orbit"},
             {"branch_omega", D, R, "npts", "rad/time", "the branch at p_base: frequency"},
             {"branch_instability", D, I, "npts", "1", "the branch at p_base: the leading instability's class of each orbit (dense Floquet)", codes::kInstability},
             {"event_curve", D, I, "nev", "1",
              "the row in curve_* of the curve the event lies on; -1 not a kind or class followed (-smap_kinds, -smap_classes); -2 not followed (-smap_max_curves, or its "
              "curve could not be started)"},
             {"curve_kind", D, I, "ncurves", "1", "each curve's kind of event", codes::kEventKind},
             {"curve_class", D, I, "ncurves", "1", "the class of the instability it bounds", codes::kInstability},
             {"curve_direction", D, I, "ncurves", "1", "its event's direction at p_base", codes::kDirection},
             {"curve_side", D, I, "ncurves", "1", "the hand of its direction of travel (rows ascending, in the (p, ln E) plane) the instability lies on",
              kCurveSideCodes},
             {"curve_event", D, I, "ncurves", "1", "the row of its event in event_*"},
             {"curve_points", D, I, "ncurves", "1", "its points"},
             {"curve_seed", D, I, "ncurves", "1",
              "where its event was located: -1 on the branch at p_base (event_* rows); k >= 0 on check branch k (-smap_seed_checks: a bubble the "
              "run's p does not cross), its event's row then in that check's event_* rows"}})},
           Codim2Schema("/stabilitymap/cells<c>/curves/<curve>"),
           {"/stabilitymap/checks/<check>",
            "",
            WithEventFields({{"p", A, R, "scalar", "1 (the parameter's unit)", "the value of the parameter (-smap_check) of this one-parameter branch (first size)"},
             {"seconds", A, R, "scalar", "s", "wall time of this branch and its events"},
             {"energy", D, R, "npts", "energy", "energy of each orbit"},
             {"omega", D, R, "npts", "rad/time", "frequency of each orbit"},
             {"instability", D, I, "npts", "1", "the orbit's leading instability class (dense Floquet): the brute force", codes::kInstability},
             {"map_label", D, I, "npts", "1", "the map's label at (p, E) of the orbit (first size)", kRegionCodes},
             {"agree", D, I, "npts", "1", "whether the map's label equals the orbit's class (a class not in -smap_classes counts as stable)", kAgreeCodes},
             {"event_offset", D, R, "nev", "1",
              "relative distance in E from the event to the nearest crossing of p by a map curve of its kind (first size); inf: none crosses there"},
             {"event_curve", D, I, "nev", "1",
              "the row in the first size's curve_* of the curve the event lies on, or started (-smap_seed_checks; curve_seed says which); -1 not a kind "
              "followed; -2 not followed"}})}}};
}

std::unique_ptr<Study> CreateStabilityMapStudy() { return std::make_unique<StabilityMapStudy>(); }

} // namespace nltopo
