#include "studies/sweep_refine.hpp"
#include "io/input.hpp"
#include "io/output.hpp"
#include "io/run_options.hpp"
#include "io/schema.hpp"
#include <sys/stat.h>
#include <algorithm>
#include <cmath>
#include <tuple>

namespace nltopo {

std::vector<PetscReal> RefinedAxis(const std::vector<PetscReal> &x, bool log_midpoints, PetscInt depth)
{
  std::vector<PetscReal> a = x;
  for (PetscInt d = 0; d < depth; d++) {
    std::vector<PetscReal> b;
    for (size_t i = 0; i < a.size(); i++) {
      b.push_back(a[i]);
      if (i + 1 < a.size()) b.push_back(log_midpoints ? std::sqrt(a[i] * a[i + 1]) : (a[i] + a[i + 1]) / 2);
    }
    a = b;
  }
  return a;
}

PetscInt RefineLattice::LevelOf(size_t i) const
{
  const size_t e = i / no, w = i % no;
  PetscInt d = depth;
  // the coarsest depth whose lattice (stride 2^(depth - d)) holds both coordinates
  while (d > 0) {
    const size_t s = (size_t)1 << (depth - d + 1);
    if (e % s || w % s) break;
    d--;
  }
  return d;
}

namespace {

// How far a cell's corner scores exceed the thresholds: the largest ratio
// difference / threshold (> 1: refine), and which scores did.
struct CellScore {
  double priority = 0;
  bool mcr = false, kcorr = false, ratio = false, predictable = false;
  bool Over() const { return mcr || kcorr || ratio || predictable; }
};

CellScore ScoreCell(const SweepPoint *c[4], const SweepRefineOptions &o, bool kcorr_on)
{
  CellScore s;
  int unpredictable = 0, predictable = 0;
  for (int k = 0; k < 4; k++) unpredictable += c[k]->predictable == 0, predictable += c[k]->predictable == 1;
  // All four unpredictable: their scores are twin statistics, noise (else the chaotic region would take every point).
  if (unpredictable == 4) return s;
  // range of a score over the corners; NaN if a corner lacks it (failed, no K)
  auto range = [&](auto f) {
    double lo = INFINITY, hi = -INFINITY;
    for (int k = 0; k < 4; k++) {
      const double v = f(*c[k]);
      if (!std::isfinite(v)) return (double)NAN;
      lo = std::min(lo, v), hi = std::max(hi, v);
    }
    return hi - lo;
  };
  double spread = 0; // the noise floor: the twins' spread (0 at predictable points and without -sweep_mcr_tol)
  for (int k = 0; k < 4; k++) spread = std::max(spread, (double)c[k]->mcr_spread);
  const double dm = range([](const SweepPoint &p) { return (double)p.mcr; });
  if (dm > o.mcr && dm > spread) s.mcr = true, s.priority = std::max(s.priority, dm / std::max((double)o.mcr, spread));
  if (kcorr_on) {
    const double dk = range([](const SweepPoint &p) { return (double)p.kcorr; });
    if (dk > o.kcorr) s.kcorr = true, s.priority = std::max(s.priority, dk / o.kcorr);
  }
  const double dr = range([](const SweepPoint &p) { return p.nl_ratio > 0 ? std::log((double)p.nl_ratio) : (double)NAN; });
  if (dr > o.ratio) s.ratio = true, s.priority = std::max(s.priority, dr / o.ratio);
  if (unpredictable && predictable) s.predictable = true, s.priority = std::max(s.priority, 1.0);
  return s;
}

} // namespace

RefineSelection SelectRefinement(const SweepGrid &g, const RefineLattice &lat, const SweepRefineOptions &o, bool kcorr_on)
{
  RefineSelection sel;
  struct Cell {
    double priority;
    PetscInt d;
    size_t e, w; // lower-left corner
    CellScore score;
  };
  std::vector<Cell> cells;
  // leaves of every depth d < lat.depth: squares of side s = 2^(depth - d) with four sampled corners and no centre
  for (PetscInt d = 0; d < lat.depth; d++) {
    const size_t s = (size_t)1 << (lat.depth - d);
    for (size_t e = 0; e + s < lat.ne; e += s)
      for (size_t w = 0; w + s < lat.no; w += s) {
        const size_t corner[4] = {lat.Index(e, w), lat.Index(e, w + s), lat.Index(e + s, w), lat.Index(e + s, w + s)};
        if (!(g.done[corner[0]] && g.done[corner[1]] && g.done[corner[2]] && g.done[corner[3]]) || g.done[lat.Index(e + s / 2, w + s / 2)]) continue;
        sel.leaves++;
        const SweepPoint *c[4] = {&g.pts[corner[0]], &g.pts[corner[1]], &g.pts[corner[2]], &g.pts[corner[3]]};
        const CellScore sc = ScoreCell(c, o, kcorr_on);
        if (sc.Over()) cells.push_back({sc.priority, d, e, w, sc});
      }
  }
  sel.over = cells.size();
  // largest difference first; then the larger cell; then the lattice order (deterministic)
  std::sort(cells.begin(), cells.end(),
            [&](const Cell &a, const Cell &b) { return std::make_tuple(-a.priority, a.d, a.e, a.w) < std::make_tuple(-b.priority, b.d, b.e, b.w); });
  std::vector<char> added(g.done.size(), 0);
  for (const Cell &c : cells) {
    const size_t h = (size_t)1 << (lat.depth - c.d - 1); // half the side
    const size_t cand[5] = {lat.Index(c.e, c.w + h), lat.Index(c.e + 2 * h, c.w + h), lat.Index(c.e + h, c.w), lat.Index(c.e + h, c.w + 2 * h),
                            lat.Index(c.e + h, c.w + h)};
    size_t fresh = 0;
    for (size_t i : cand) fresh += !g.done[i] && !added[i];
    if (o.max_points > 0 && sel.points.size() + fresh > (size_t)o.max_points) break; // the budget: the cells with the largest differences had it
    for (size_t i : cand)
      if (!g.done[i] && !added[i]) added[i] = 1, sel.points.push_back(i);
    sel.refined++;
    sel.by_mcr += c.score.mcr, sel.by_kcorr += c.score.kcorr, sel.by_ratio += c.score.ratio, sel.by_predictable += c.score.predictable;
  }
  std::sort(sel.points.begin(), sel.points.end());
  return sel;
}

std::string RefineSourceProblem(const std::string &path)
{
  const std::string what = "-sweep_refine_from " + path;
  struct stat st;
  if (stat(path.c_str(), &st)) return what + ": no such file";
  std::string study, o, e;
  long v = 0, complete = 0;
  if (!ReadRootAttribute(path, "study", &study) || !ReadRootAttribute(path, "options", &o)) return what + ": not an nltopo output";
  ReadRootAttribute(path, "format_version", &v);
  if (v != kFormatVersion) return what + " has format_version " + std::to_string(v) + " (this nltopo writes " + std::to_string(kFormatVersion) + ")";
  if (study != "sweep" && study != "merge") return what + " was written by -study " + study + " (a sweep, a merged sweep or a refinement level is needed)";
  ReadRootAttribute(path, "complete", &complete);
  if (!complete) return what + " is a partial output (complete = 0): finish it first (-sweep_resume)";
  if (HasDataset(path, "/sweep/shard_points")) return what + " holds one shard: merge the shards first (-study merge)";
  if (study == "merge") { // the scene of its shards (all the same: the merge checked)
    if (!ReadRootAttribute(path, "/merge/shards/0/options", &o)) return what + ": a merged file without /merge/shards/0";
    e.clear();
    ReadRootAttribute(path, "/merge/shards/0/effective_options", &e);
  } else ReadRootAttribute(path, "effective_options", &e);
  const std::string d = FirstOptionDifference({o, e}, ThisRunRecord(), OptionRule::Resume);
  return d.empty() ? "" : what + " was written " + d;
}

namespace {

// The file's /sweep/refined samples: lattice coordinates at its depth, done flags and values, into g (lattice lat, whose depth is the file's + shift).
PetscErrorCode ReadRefinedSamples(const std::string &path, const char *opt, const RefineLattice &lat, PetscInt shift, bool done_only, SweepGrid *g,
                                  std::vector<size_t> *where)
{
  std::vector<PetscInt> wi, ei, done, iv;
  std::vector<PetscReal> v, om, en;
  PetscFunctionBeginUser;
  PetscCall(ReadInts(path, "/sweep/refined/omega_index", &wi));
  PetscCall(ReadInts(path, "/sweep/refined/energy_index", &ei));
  PetscCall(ReadInts(path, "/sweep/refined/done", &done));
  PetscCall(ReadDoubles(path, "/sweep/refined/omega", &om));
  PetscCall(ReadDoubles(path, "/sweep/refined/energy", &en));
  const size_t n = wi.size();
  PetscCheck(ei.size() == n && done.size() == n && om.size() == n && en.size() == n, PETSC_COMM_SELF, PETSC_ERR_USER,
             "%s %s: the /sweep/refined datasets differ in size (a damaged file?)", opt, path.c_str());
  where->assign(n, (size_t)-1);
  for (size_t k = 0; k < n; k++) {
    const size_t w = (size_t)wi[k] << shift, e = (size_t)ei[k] << shift;
    PetscCheck(wi[k] >= 0 && ei[k] >= 0 && w < lat.no && e < lat.ne && g->omega[w] == om[k] && g->energy[e] == en[k], PETSC_COMM_SELF, PETSC_ERR_USER,
               "%s %s: sample %zu (omega %g, E* %g) is not on this sweep's refined lattice (other -sweep_* axes?)", opt, path.c_str(), k, (double)om[k],
               (double)en[k]);
    PetscCheck(done[k] == 1 || (done_only && done[k] == 0), PETSC_COMM_SELF, PETSC_ERR_USER, "%s %s: sample %zu is not computed (done = %" PetscInt_FMT ")",
               opt, path.c_str(), k, done[k]);
    if (done[k] == 1) (*where)[k] = lat.Index(e, w);
  }
  for (const auto &f : SweepRealFields()) {
    PetscCall(ReadDoubles(path, (std::string("/sweep/refined/") + f.name).c_str(), &v));
    PetscCheck(v.size() == n, PETSC_COMM_SELF, PETSC_ERR_USER, "%s %s: /sweep/refined/%s has the wrong size", opt, path.c_str(), f.name);
    for (size_t k = 0; k < n; k++)
      if ((*where)[k] != (size_t)-1) g->pts[(*where)[k]].*f.field = v[k];
  }
  for (const auto &f : SweepIntFields()) {
    PetscCall(ReadInts(path, (std::string("/sweep/refined/") + f.name).c_str(), &iv));
    PetscCheck(iv.size() == n, PETSC_COMM_SELF, PETSC_ERR_USER, "%s %s: /sweep/refined/%s has the wrong size", opt, path.c_str(), f.name);
    for (size_t k = 0; k < n; k++)
      if ((*where)[k] != (size_t)-1) g->pts[(*where)[k]].*f.field = iv[k];
  }
  for (size_t k = 0; k < n; k++) {
    std::string bad;
    PetscCheck((*where)[k] == (size_t)-1 || SweepPointValid(g->pts[(*where)[k]], &bad), PETSC_COMM_SELF, PETSC_ERR_USER,
               "%s %s: sample %zu holds %s, which no sweep writes (a damaged file?)", opt, path.c_str(), k, bad.c_str());
  }
  PetscFunctionReturn(0);
}

// The fine lattice of depth lat->depth over the base axes, every point absent.
PetscErrorCode ResetLattice(const std::vector<PetscReal> &omega, const std::vector<PetscReal> &energy, bool log_energy, RefineLattice *lat, SweepGrid *g)
{
  PetscFunctionBeginUser;
  const std::vector<PetscReal> w = RefinedAxis(omega, false, lat->depth), e = RefinedAxis(energy, log_energy, lat->depth);
  PetscCheck((double)w.size() * (double)e.size() <= 4e6, PETSC_COMM_SELF, PETSC_ERR_USER,
             "-sweep_refine_from: a refinement of depth %" PetscInt_FMT " would need a lattice of %zu x %zu points (at most 4e6): refine a smaller window",
             lat->depth, e.size(), w.size());
  lat->no = w.size(), lat->ne = e.size();
  g->Reset(w, e);
  g->scattered = true;
  PetscFunctionReturn(0);
}

} // namespace

PetscErrorCode LoadRefineSource(const std::string &path, const std::vector<PetscReal> &omega, const std::vector<PetscReal> &energy, bool log_energy,
                                SweepGrid *g, RefineLattice *lat)
{
  PetscFunctionBeginUser;
  if (!HasDataset(path, "/sweep/refined/omega_index")) { // a grid (or a merged one): its points are the samples of depth 0
    SweepGrid base;
    base.Reset(omega, energy);
    PetscCall(base.Load(path, "-sweep_refine_from"));
    const PetscInt done = base.Done();
    PetscCheck(done == (PetscInt)base.Size(), PETSC_COMM_SELF, PETSC_ERR_USER, "-sweep_refine_from %s: %" PetscInt_FMT " of %zu points done (not complete)",
               path.c_str(), done, base.Size());
    lat->depth = 1;
    PetscCall(ResetLattice(omega, energy, log_energy, lat, g));
    for (size_t e = 0; e < energy.size(); e++)
      for (size_t w = 0; w < omega.size(); w++) {
        g->pts[lat->Index(2 * e, 2 * w)] = base.pts[e * omega.size() + w];
        g->done[lat->Index(2 * e, 2 * w)] = 1;
      }
  } else {
    long depth = -1;
    std::vector<PetscReal> w, e;
    ReadRootAttribute(path, "/sweep/refined/depth", &depth);
    PetscCheck(depth >= 0 && depth < 30, PETSC_COMM_SELF, PETSC_ERR_USER, "-sweep_refine_from %s: /sweep/refined has no valid depth attribute (%ld)",
               path.c_str(), depth);
    PetscCall(ReadDoubles(path, "/sweep/omega", &w));
    PetscCall(ReadDoubles(path, "/sweep/energy", &e));
    PetscCheck(w == omega && e == energy, PETSC_COMM_SELF, PETSC_ERR_USER,
               "-sweep_refine_from %s: its base grid (%zu x %zu) differs from the -sweep_* axes (%zu x %zu)", path.c_str(), e.size(), w.size(), energy.size(),
               omega.size());
    lat->depth = (PetscInt)depth + 1;
    PetscCall(ResetLattice(omega, energy, log_energy, lat, g));
    std::vector<size_t> where;
    PetscCall(ReadRefinedSamples(path, "-sweep_refine_from", *lat, 1, false, g, &where));
    for (size_t i : where) g->done[i] = 1;
  }
  g->points.clear();
  for (size_t i = 0; i < g->Size(); i++)
    if (g->done[i]) g->points.push_back(i);
  PetscFunctionReturn(0);
}

PetscErrorCode LoadRefinedPartial(const std::string &path, const RefineLattice &lat, SweepGrid *g)
{
  long depth = -1;
  std::vector<size_t> where;
  PetscFunctionBeginUser;
  ReadRootAttribute(path, "/sweep/refined/depth", &depth);
  PetscCheck(depth == lat.depth, PETSC_COMM_SELF, PETSC_ERR_USER,
             "-sweep_resume: %s holds a refinement of depth %ld, this level is depth %" PetscInt_FMT " (another -sweep_refine_from?)", path.c_str(), depth,
             lat.depth);
  SweepGrid read = *g;
  PetscCall(ReadRefinedSamples(path, "-sweep_resume", lat, 0, true, &read, &where));
  for (size_t i : where)
    if (i != (size_t)-1 && std::binary_search(g->points.begin(), g->points.end(), i)) g->pts[i] = read.pts[i], g->done[i] = 1;
  PetscFunctionReturn(0);
}

PetscErrorCode WriteRefinedSamples(PetscViewer w, const SweepGrid &g, const RefineLattice &lat)
{
  const char *grp = "/sweep/refined";
  const size_t n = g.points.size();
  std::vector<PetscReal> v(n);
  std::vector<PetscInt> iv(n);
  PetscFunctionBeginUser;
  for (size_t k = 0; k < n; k++) v[k] = g.omega[g.points[k] % lat.no];
  PetscCall(WriteArray(w, grp, "omega", v));
  for (size_t k = 0; k < n; k++) v[k] = g.energy[g.points[k] / lat.no];
  PetscCall(WriteArray(w, grp, "energy", v));
  for (size_t k = 0; k < n; k++) iv[k] = lat.LevelOf(g.points[k]);
  PetscCall(WriteIntArray(w, grp, "level", iv));
  for (size_t k = 0; k < n; k++) iv[k] = (PetscInt)(g.points[k] % lat.no);
  PetscCall(WriteIntArray(w, grp, "omega_index", iv));
  for (size_t k = 0; k < n; k++) iv[k] = (PetscInt)(g.points[k] / lat.no);
  PetscCall(WriteIntArray(w, grp, "energy_index", iv));
  for (size_t k = 0; k < n; k++) iv[k] = g.done[g.points[k]];
  PetscCall(WriteIntArray(w, grp, "done", iv));
  for (const auto &f : SweepRealFields()) {
    for (size_t k = 0; k < n; k++) v[k] = g.pts[g.points[k]].*f.field;
    PetscCall(WriteArray(w, grp, f.name, v));
  }
  for (const auto &f : SweepIntFields()) {
    for (size_t k = 0; k < n; k++) iv[k] = g.pts[g.points[k]].*f.field;
    PetscCall(WriteIntArray(w, grp, f.name, iv));
  }
  PetscCall(WriteAttr(w, grp, "depth", lat.depth));
  PetscFunctionReturn(0);
}

} // namespace nltopo
