#include "studies/sweep_store.hpp"
#include "io/input.hpp"
#include "io/schema.hpp"
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <dirent.h>
#include <numeric>

namespace nltopo {

namespace {

// (NaN: a failed point's numbers are NaN, sweep_study.cpp; kcorr without
// -sweep_kcorr or too short a record; mcr_error without the mode or where unpredictable)
const SweepRealField kRealMembers[] = {{"mcr", &SweepPoint::mcr, NanAllowed::IfFailed},
                                       {"t_off", &SweepPoint::t_off, NanAllowed::IfFailed},
                                       {"kcorr", &SweepPoint::kcorr, NanAllowed::Always},
                                       {"nl_ratio", &SweepPoint::nl_ratio, NanAllowed::IfFailed},
                                       {"amplitude", &SweepPoint::amplitude, NanAllowed::IfFailed},
                                       {"energy_final", &SweepPoint::energy_final, NanAllowed::IfFailed},
                                       {"seconds", &SweepPoint::seconds, NanAllowed::Never},
                                       {"mcr_error", &SweepPoint::mcr_error, NanAllowed::Always},
                                       {"mcr_spread", &SweepPoint::mcr_spread, NanAllowed::Never},
                                       {"mcr_dt", &SweepPoint::mcr_dt, NanAllowed::Always},
                                       {"lyapunov", &SweepPoint::lyapunov, NanAllowed::Always},
                                       {"lyapunov_half", &SweepPoint::lyapunov_half, NanAllowed::Always}};
const SweepIntField kIntMembers[] = {{"reached", &SweepPoint::reached}, {"rescalings", &SweepPoint::rescalings}, {"rhs_evals", &SweepPoint::rhs},
                                     {"steps", &SweepPoint::steps},     {"failed", &SweepPoint::failed},         {"predictable", &SweepPoint::predictable},
                                     {"mcr_runs", &SweepPoint::runs},   {"regime", &SweepPoint::regime}};

bool PerPoint(const Field &f) { return f.kind == FieldKind::Dataset && !std::strcmp(f.shape, "ne x no") && std::strcmp(f.name, "done"); }

// The members in the schema's order (a member it lacks is left out: SweepFieldsUnbound names it).
template <typename F, size_t n> std::vector<F> InSchemaOrder(const F (&members)[n], FieldType type)
{
  std::vector<F> out;
  if (const Schema *s = FindSchema("/sweep"))
    for (const Field &f : s->fields)
      for (const F &m : members)
        if (PerPoint(f) && f.type == type && !std::strcmp(f.name, m.name)) out.push_back(m);
  return out;
}

} // namespace

const std::vector<SweepRealField> &SweepRealFields()
{
  static const std::vector<SweepRealField> v = InSchemaOrder(kRealMembers, FieldType::Real);
  return v;
}

const std::vector<SweepIntField> &SweepIntFields()
{
  static const std::vector<SweepIntField> v = InSchemaOrder(kIntMembers, FieldType::Int);
  return v;
}

std::vector<std::string> SweepFieldsUnbound()
{
  std::vector<std::string> bad;
  size_t n = 0;
  if (const Schema *s = FindSchema("/sweep"))
    for (const Field &f : s->fields) {
      if (!PerPoint(f)) continue;
      n++;
      bool bound = false;
      for (const auto &m : SweepRealFields()) bound |= !std::strcmp(m.name, f.name);
      for (const auto &m : SweepIntFields()) bound |= !std::strcmp(m.name, f.name);
      if (!bound) bad.push_back(std::string("schema field ") + f.name);
    }
  for (const auto &m : kRealMembers)
    if (!FindField("/sweep", m.name, FieldKind::Dataset)) bad.push_back(std::string("member ") + m.name);
  for (const auto &m : kIntMembers)
    if (!FindField("/sweep", m.name, FieldKind::Dataset)) bad.push_back(std::string("member ") + m.name);
  if (n != SweepRealFields().size() + SweepIntFields().size()) bad.push_back("a member bound twice or of the wrong type");
  return bad;
}

bool SweepPointValid(const SweepPoint &p, std::string *what)
{
  char buf[96];
  if (p.failed != 0 && p.failed != 1) {
    std::snprintf(buf, sizeof buf, "failed = %ld", (long)p.failed);
    *what = buf;
    return false;
  }
  for (const SweepRealField &f : SweepRealFields()) {
    const PetscReal x = p.*f.field;
    if (std::isfinite(x) || (std::isnan(x) && (f.nan == NanAllowed::Always || (f.nan == NanAllowed::IfFailed && p.failed)))) continue;
    std::snprintf(buf, sizeof buf, "%s = %g%s", f.name, (double)x, std::isnan(x) && !p.failed ? " at a point not failed" : "");
    *what = buf;
    return false;
  }
  return true;
}

PetscInt SweepGrid::Done() const
{
  PetscInt n = 0;
  for (size_t k = 0; k < Count(); k++) n += done[At(k)];
  return n;
}

void SweepGrid::Reset(const std::vector<PetscReal> &w, const std::vector<PetscReal> &e)
{
  omega = w;
  energy = e;
  pts.assign(Size(), SweepPoint());
  done.assign(Size(), 0);
}

// The shard a sweep file holds (0 of 0: the whole grid), and whether it is this grid's; else *msg says how it differs.
static PetscErrorCode CheckLoadedShard(const std::string &path, const SweepGrid &g, std::vector<size_t> *points, std::string *msg)
{
  long index = 0, count = 0;
  char buf[512];
  PetscFunctionBeginUser;
  points->clear();
  if (HasDataset(path, "/sweep/shard_points")) {
    std::vector<PetscInt> p;
    ReadRootAttribute(path, "/sweep/shard_index", &index);
    ReadRootAttribute(path, "/sweep/shard_count", &count);
    PetscCall(ReadInts(path, "/sweep/shard_points", &p));
    points->assign(p.begin(), p.end());
  }
  const std::string now = g.shard.On() ? "-sweep_shard " + std::to_string(g.shard.index) + "/" + std::to_string(g.shard.count) : "the whole grid";
  if (count == 0 && g.shard.On()) std::snprintf(buf, sizeof buf, "holds the whole grid (now %s)", now.c_str());
  else if (count && (index != g.shard.index || count != g.shard.count))
    std::snprintf(buf, sizeof buf, "holds shard %ld/%ld (now %s)", index, count, now.c_str());
  else if (count && *points != g.points) std::snprintf(buf, sizeof buf, "holds other points than this nltopo's shard %ld/%ld (another split)", index, count);
  else buf[0] = 0;
  *msg = buf;
  PetscFunctionReturn(0);
}

PetscErrorCode SweepGrid::Load(const std::string &path, const char *opt)
{
  std::vector<PetscReal> w, e, v;
  std::vector<PetscInt> iv;
  std::vector<size_t> stored; // the grid index of each stored value: a shard's points, or every point
  std::string msg;
  PetscFunctionBeginUser;
  PetscCall(ReadDoubles(path, "/sweep/omega", &w));
  PetscCall(ReadDoubles(path, "/sweep/energy", &e));
  for (const auto &[axis, x] : {std::make_pair("omega", &w), std::make_pair("energy", &e)})
    PetscCheck(std::all_of(x->begin(), x->end(), [](PetscReal a) { return std::isfinite(a); }), PETSC_COMM_SELF, PETSC_ERR_USER,
               "%s: /sweep/%s in %s holds a value that is not finite, which no sweep writes (a damaged file?)", opt, axis, path.c_str());
  PetscCheck(w == omega && e == energy, PETSC_COMM_SELF, PETSC_ERR_USER,
             "%s: the grid stored in %s (%zu x %zu) differs from the -sweep_* axes (%zu x %zu)", opt, path.c_str(), e.size(), w.size(), energy.size(),
             omega.size());
  PetscCall(CheckLoadedShard(path, *this, &stored, &msg));
  PetscCheck(msg.empty(), PETSC_COMM_SELF, PETSC_ERR_USER, "%s: %s %s", opt, path.c_str(), msg.c_str());
  if (!shard.On()) {
    stored.resize(Size());
    std::iota(stored.begin(), stored.end(), 0);
  }
  auto doubles = [&](const char *name, PetscReal SweepPoint::*field) -> PetscErrorCode {
    PetscFunctionBeginUser;
    PetscCall(ReadDoubles(path, (std::string("/sweep/") + name).c_str(), &v));
    PetscCheck(v.size() == stored.size(), PETSC_COMM_SELF, PETSC_ERR_FILE_UNEXPECTED, "%s: /sweep/%s in %s has the wrong size", opt, name, path.c_str());
    for (size_t i = 0; i < v.size(); i++) pts[stored[i]].*field = v[i];
    PetscFunctionReturn(0);
  };
  auto ints = [&](const char *name, PetscInt SweepPoint::*field) -> PetscErrorCode {
    PetscFunctionBeginUser;
    PetscCall(ReadInts(path, (std::string("/sweep/") + name).c_str(), &iv));
    PetscCheck(iv.size() == stored.size(), PETSC_COMM_SELF, PETSC_ERR_FILE_UNEXPECTED, "%s: /sweep/%s in %s has the wrong size", opt, name, path.c_str());
    for (size_t i = 0; i < iv.size(); i++) pts[stored[i]].*field = iv[i];
    PetscFunctionReturn(0);
  };
  for (const auto &f : SweepRealFields()) PetscCall(doubles(f.name, f.field));
  for (const auto &f : SweepIntFields()) PetscCall(ints(f.name, f.field));
  PetscCall(ReadInts(path, "/sweep/done", &iv));
  PetscCheck(iv.size() == stored.size(), PETSC_COMM_SELF, PETSC_ERR_FILE_UNEXPECTED, "%s: /sweep/done in %s has the wrong size", opt, path.c_str());
  for (size_t i = 0; i < iv.size(); i++) done[stored[i]] = iv[i];
  // A point done holds what a sweep writes; one not done is computed again.
  const size_t no = omega.size();
  for (size_t i : stored) {
    std::string what;
    char at[96]; // (PETSc's %g would print 1 as "1.")
    std::snprintf(at, sizeof at, "E* = %g, omega = %g", (double)energy[i / no], (double)omega[i % no]);
    PetscCheck(done[i] == 0 || done[i] == 1, PETSC_COMM_SELF, PETSC_ERR_USER,
               "%s: /sweep/done in %s holds %" PetscInt_FMT " at %s, not 0 or 1 (a damaged file?)", opt, path.c_str(), done[i], at);
    PetscCheck(!done[i] || SweepPointValid(pts[i], &what), PETSC_COMM_SELF, PETSC_ERR_USER,
               "%s: %s holds %s at %s, which no sweep writes (a damaged file?)", opt, path.c_str(), what.c_str(), at);
  }
  PetscFunctionReturn(0);
}

std::vector<std::string> JournalFiles(const std::string &path)
{
  const size_t slash = path.find_last_of('/');
  const std::string dir = slash == std::string::npos ? "." : path.substr(0, slash + 1);
  const std::string prefix = (slash == std::string::npos ? path : path.substr(slash + 1)) + ".journal.";
  std::vector<std::string> files;
  if (DIR *d = opendir(dir.c_str())) {
    while (dirent *e = readdir(d))
      if (!std::strncmp(e->d_name, prefix.c_str(), prefix.size())) files.push_back((slash == std::string::npos ? "" : dir) + e->d_name);
    closedir(d);
  }
  return files;
}

// Line format: the index, then every field of SweepRealFields() (hex floats:
// exact) and of SweepIntFields(), in that order.
PetscErrorCode SweepGrid::MergeJournals(const std::string &path, PetscInt *lines)
{
  PetscFunctionBeginUser;
  *lines = 0;
  for (const std::string &name : JournalFiles(path)) {
    FILE *f = std::fopen(name.c_str(), "r");
    if (!f) continue;
    char buf[2048];
    for (long line = 1; std::fgets(buf, sizeof(buf), f); line++) {
      if (!std::strchr(buf, '\n')) break; // a line cut by a kill: ignored, the point is recomputed
      char *p = buf, *end;
      const long idx = std::strtol(p, &end, 10);
      bool ok = end != p && idx >= 0 && (size_t)idx < Size();
      SweepPoint pt;
      for (const auto &fd : SweepRealFields()) {
        if (!ok) break;
        p = end;
        pt.*fd.field = std::strtod(p, &end);
        ok = end != p;
      }
      for (const auto &fd : SweepIntFields()) {
        if (!ok) break;
        p = end;
        pt.*fd.field = (PetscInt)std::strtol(p, &end, 10);
        ok = end != p;
      }
      if (!ok) continue;
      std::string what;
      if (!SweepPointValid(pt, &what)) {
        std::fclose(f);
        SETERRQ(PETSC_COMM_SELF, PETSC_ERR_USER,
                "sweep journal %s, line %ld: %s, which no sweep writes (a damaged journal?): remove it to compute its points again", name.c_str(), line,
                what.c_str());
      }
      pts[idx] = pt;
      done[idx] = 1;
      (*lines)++;
    }
    std::fclose(f);
  }
  PetscFunctionReturn(0);
}

PetscErrorCode Journal::Open(const std::string &path, PetscMPIInt rank)
{
  PetscFunctionBeginUser;
  const std::string name = path + ".journal." + std::to_string(rank);
  f_ = std::fopen(name.c_str(), "a");
  PetscCheck(f_, PETSC_COMM_SELF, PETSC_ERR_FILE_OPEN, "cannot write the sweep journal %s next to -output", name.c_str());
  PetscFunctionReturn(0);
}

PetscErrorCode Journal::Append(size_t index, const SweepPoint &p)
{
  PetscFunctionBeginUser;
  std::string line = std::to_string(index);
  char v[64];
  for (const auto &fd : SweepRealFields()) std::snprintf(v, sizeof(v), " %a", (double)(p.*fd.field)), line += v;
  for (const auto &fd : SweepIntFields()) line += " " + std::to_string((long)(p.*fd.field));
  std::fprintf(f_, "%s\n", line.c_str());
  PetscCheck(std::fflush(f_) == 0, PETSC_COMM_SELF, PETSC_ERR_FILE_WRITE, "cannot write the sweep journal (disk full?)");
  PetscFunctionReturn(0);
}

void Journal::Close()
{
  if (f_) std::fclose(f_);
  f_ = nullptr;
}

} // namespace nltopo
