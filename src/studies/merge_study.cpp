// -study merge: joins the shard files of one sweep (-sweep_shard i/n, every
// i once) into one map whose /sweep equals the unsharded run's (docs/studies/
// sweep.md "Shards and merge"). Rank 0 first checks every input, one file at
// a time (the same scene, binary and format version, complete, no point
// missing or twice), then fills each per-point dataset of the map from the
// shards one file at a time: at most one map-sized dataset is in memory. The
// shards' provenance is kept under /merge/shards/<i>.
#include "core/errors.hpp"
#include "core/log.hpp"
#include "core/option_table.hpp"
#include "io/input.hpp"
#include "io/output.hpp"
#include "io/run_options.hpp"
#include "io/schema.hpp"
#include "studies/registry.hpp"
#include "studies/study.hpp"
#include "studies/sweep_store.hpp"
#include <cstring>
#include <sys/stat.h>

namespace nltopo {

namespace {

constexpr PetscInt kMaxInputs = 100000; // a job array's size, and more

struct MergeOptions {
  std::vector<std::string> inputs;
};

// Physics: the inputs are what the merge computes from (an overwrite of another merge's output compares them).
const auto &kMergeTable = DeclareOptionTable<MergeOptions>("merge_", "Merge: join the shard files of one sweep into its map", [](OptionTable<MergeOptions> &t) {
  t.StringList("inputs", &MergeOptions::inputs, kMaxInputs,
               "Shard files of one sweep (-sweep_shard i/n, every i once, any order), comma-separated; -output gets the whole map")
      .Default("none (required)");
});

// What rank 0 knows of the first input: every other is compared with it.
struct FirstShard {
  std::string file, version;
  RunRecord record;
  long count = 0;
  std::vector<PetscReal> omega, energy;
};

// "E* = 1, omega = 2" of grid index i.
std::string PointName(const FirstShard &f, size_t i)
{
  char b[96];
  const size_t no = f.omega.size();
  std::snprintf(b, sizeof b, "E* = %g, omega = %g", (double)f.energy[i / no], (double)f.omega[i % no]);
  return b;
}

class MergeStudy : public Study {
protected:
  PetscErrorCode ReadOptions() override
  {
    std::vector<PetscBool> set;
    PetscFunctionBeginUser;
    PetscCall(kMergeTable.Read(comm_, &o_, &set));
    PetscCheck(declaring_ || !o_.inputs.empty(), comm_, PETSC_ERR_USER, "-study merge needs -merge_inputs a.h5,b.h5,... (the shard files of one sweep)");
    PetscFunctionReturn(0);
  }
  // The output path, then every input checked (rank 0), before the output file is opened.
  PetscErrorCode OutputPath(std::string *path) override
  {
    PetscFunctionBeginUser;
    PetscCall(Study::OutputPath(path));
    for (const std::string &in : o_.inputs) // the output is renamed into place: it must not replace an input
      PetscCheck(!SameFile(in, *path), comm_, PETSC_ERR_USER, "-output %s is one of -merge_inputs: merge into another file", path->c_str());
    PetscCall(OnRoot([&]() { return CheckInputs(); }));
    unsigned long dims[3] = {nrows_, ncols_, order_.size()};
    PetscCallMPI(MPI_Bcast(dims, 3, MPI_UNSIGNED_LONG, 0, comm_));
    nrows_ = dims[0], ncols_ = dims[1];
    order_.resize(dims[2]); // (rank 0's values; the others only count)
    PetscFunctionReturn(0);
  }
  PetscErrorCode Build() override { return 0; }
  PetscErrorCode Solve() override { return 0; } // the work is the copy, in Write
  PetscErrorCode Write(PetscViewer v) override
  {
    PetscFunctionBeginUser;
    PetscCall(PetscLogEventBegin(Log().output, 0, 0, 0, 0));
    const Schema *s = FindSchema("/sweep");
    PetscCheck(s, comm_, PETSC_ERR_PLIB, "no /sweep schema");
    for (const Field &f : s->fields) {
      if (f.kind != FieldKind::Dataset) continue;
      if (!std::strcmp(f.shape, "ne x no")) PetscCall(WritePerPoint(v, f));
      else PetscCall(CopyFromFirst(v, f));
    }
    for (const Field &f : s->fields)
      if (f.kind == FieldKind::Attribute) PetscCall(CopyFromFirst(v, f));
    PetscCall(WriteProvenance(v));
    PetscCall(PetscLogEventEnd(Log().output, 0, 0, 0, 0));
    PetscCall(PetscPrintf(comm_, "nltopo merge: %zu shards of %zu omega x %zu E* = %zu points\n", order_.size(), ncols_, nrows_, ncols_ * nrows_));
    PetscFunctionReturn(0);
  }

private:
  PetscErrorCode CheckInputs();
  PetscErrorCode CheckOne(size_t k, std::vector<int> *owner, std::vector<long> *shard_file);
  PetscErrorCode WritePerPoint(PetscViewer v, const Field &f);
  PetscErrorCode CopyFromFirst(PetscViewer v, const Field &f);
  PetscErrorCode WriteProvenance(PetscViewer v);
  // Rank 0's value on every rank.
  PetscErrorCode Bcast(std::string *s) const
  {
    unsigned long n = s->size();
    PetscFunctionBeginUser;
    PetscCallMPI(MPI_Bcast(&n, 1, MPI_UNSIGNED_LONG, 0, comm_));
    s->resize(n);
    PetscCallMPI(MPI_Bcast(s->data(), (PetscMPIInt)n, MPI_CHAR, 0, comm_));
    PetscFunctionReturn(0);
  }
  // Attribute f of group `from` ("" the root) of input `in`, written to the output's `group` when the input has it.
  PetscErrorCode CopyAttribute(PetscViewer v, const std::string &in, const std::string &from, const char *group, const Field &f);
  // Rank 0 runs fn (reading the inputs); then every rank fails alike or goes on.
  template <typename Fn> PetscErrorCode OnRoot(Fn &&fn)
  {
    PetscErrorCode err = 0;
    char msg[2048] = "";
    PetscMPIInt rank;
    PetscFunctionBeginUser;
    PetscCallMPI(MPI_Comm_rank(comm_, &rank));
    if (!rank) PetscCall(CaptureError(fn, &err, msg, sizeof msg));
    PetscCall(FailTogether(comm_, err, msg));
    PetscFunctionReturn(0);
  }

  MergeOptions o_;
  FirstShard first_;             // rank 0
  size_t nrows_ = 0, ncols_ = 0; // the map: energy rows x omega columns (every rank)
  std::vector<size_t> order_;    // rank 0: input index of shard 0, 1, ...
  PetscInt computed_ = 0;        // rank 0: the shards' points_computed, summed
};

// One input: a complete sweep shard of the first input's scene, binary,
// format, shard count and axes, whose points no earlier input holds.
// owner[i]: the input holding grid point i (-1: none yet); shard_file[j]: the input that is shard j.
PetscErrorCode MergeStudy::CheckOne(size_t k, std::vector<int> *owner, std::vector<long> *shard_file)
{
  const std::string &in = o_.inputs[k];
  const char *file = in.c_str();
  std::string study, opts, eff, version;
  long fv = 0, complete = 0, index = -1, count = 0;
  struct stat st;
  PetscFunctionBeginUser;
  PetscCheck(!stat(file, &st), PETSC_COMM_SELF, PETSC_ERR_FILE_OPEN, "-merge_inputs %s: no such file", file);
  PetscCheck(ReadRootAttribute(in, "study", &study) && ReadRootAttribute(in, "options", &opts), PETSC_COMM_SELF, PETSC_ERR_USER,
             "-merge_inputs %s: not an nltopo output (no root attributes study and options)", file);
  PetscCheck(study == "sweep", PETSC_COMM_SELF, PETSC_ERR_USER, "-merge_inputs %s was written by -study %s, not by a -study sweep shard", file, study.c_str());
  ReadRootAttribute(in, "format_version", &fv);
  PetscCheck(fv == kFormatVersion, PETSC_COMM_SELF, PETSC_ERR_USER,
             "-merge_inputs %s has format_version %ld (this nltopo writes %d): merge it with the nltopo that wrote it", file, fv, (int)kFormatVersion);
  ReadRootAttribute(in, "complete", &complete);
  PetscCheck(complete == 1, PETSC_COMM_SELF, PETSC_ERR_USER, "-merge_inputs %s is a partial output (complete = 0): finish its shard first (-sweep_resume)",
             file);
  PetscCheck(ReadRootAttribute(in, "/sweep/shard_count", &count) && ReadRootAttribute(in, "/sweep/shard_index", &index), PETSC_COMM_SELF, PETSC_ERR_USER,
             "-merge_inputs %s holds a whole sweep, not a shard (-sweep_shard i/n)", file);
  ReadRootAttribute(in, "version", &version);
  ReadRootAttribute(in, "effective_options", &eff);
  std::vector<PetscReal> w, e;
  PetscCall(ReadDoubles(in, "/sweep/omega", &w));
  PetscCall(ReadDoubles(in, "/sweep/energy", &e));
  if (!k) {
    first_ = {in, version, {opts, eff}, count, w, e};
    owner->assign(w.size() * e.size(), -1);
    shard_file->assign(count > 0 ? count : 0, -1);
  } else {
    const char *f0 = first_.file.c_str();
    PetscCheck(version == first_.version, PETSC_COMM_SELF, PETSC_ERR_USER,
               "-merge_inputs %s was written by nltopo %s, %s by nltopo %s: the shards of one map come from one binary", file, version.c_str(), f0,
               first_.version.c_str());
    std::string d = FirstOptionDifference({opts, eff}, first_.record, OptionRule::Overwrite);
    for (size_t p = d.find("(now "); p != std::string::npos; p = d.find("(now ", p)) d.replace(p, 5, "(in " + first_.file + ": ");
    PetscCheck(d.empty(), PETSC_COMM_SELF, PETSC_ERR_USER, "-merge_inputs %s is another scene than %s: it was written %s", file, f0, d.c_str());
    PetscCheck(count == first_.count, PETSC_COMM_SELF, PETSC_ERR_USER, "-merge_inputs %s is shard %ld/%ld, %s one of %ld shards", file, index, count, f0,
               first_.count);
    PetscCheck(w == first_.omega && e == first_.energy, PETSC_COMM_SELF, PETSC_ERR_USER, "-merge_inputs %s has other -sweep_* axes than %s", file, f0);
  }
  PetscCheck(index >= 0 && index < count && (size_t)count <= owner->size(), PETSC_COMM_SELF, PETSC_ERR_USER,
             "-merge_inputs %s: shard %ld/%ld is not a shard of its %zu-point grid (a damaged file?)", file, index, count, owner->size());
  PetscCheck((*shard_file)[index] < 0, PETSC_COMM_SELF, PETSC_ERR_USER, "-merge_inputs %s is shard %ld/%ld, as is %s (duplicate points)", file, index, count,
             o_.inputs[(*shard_file)[index]].c_str());
  (*shard_file)[index] = (long)k;
  std::vector<PetscInt> pts, done;
  PetscCall(ReadInts(in, "/sweep/shard_points", &pts));
  PetscCall(ReadInts(in, "/sweep/done", &done));
  PetscCheck(done.size() == pts.size(), PETSC_COMM_SELF, PETSC_ERR_USER,
             "-merge_inputs %s: /sweep/done and /sweep/shard_points differ in size (a damaged file?)", file);
  size_t ndone = 0;
  for (size_t j = 0; j < pts.size(); j++) {
    PetscCheck(pts[j] >= 0 && (size_t)pts[j] < owner->size(), PETSC_COMM_SELF, PETSC_ERR_USER,
               "-merge_inputs %s: /sweep/shard_points holds %" PetscInt_FMT ", outside its %zu-point grid (a damaged file?)", file, pts[j], owner->size());
    const int o = (*owner)[pts[j]];
    PetscCheck(o < 0, PETSC_COMM_SELF, PETSC_ERR_USER, "-merge_inputs %s holds the point %s that %s holds too (duplicate points)", file,
               PointName(first_, pts[j]).c_str(), o_.inputs[o].c_str());
    (*owner)[pts[j]] = (int)k;
    ndone += done[j] == 1;
  }
  PetscCheck(ndone == pts.size(), PETSC_COMM_SELF, PETSC_ERR_USER, "-merge_inputs %s is incomplete: %zu of its %zu points done (-sweep_resume finishes it)",
             file, ndone, pts.size());
  long computed = 0;
  ReadRootAttribute(in, "/sweep/points_computed", &computed);
  computed_ += (PetscInt)computed;
  PetscFunctionReturn(0);
}

PetscErrorCode MergeStudy::CheckInputs()
{
  std::vector<int> owner;       // one int per point: the map's size, not the shards'
  std::vector<long> shard_file; // one per shard
  PetscFunctionBeginUser;
  computed_ = 0;
  for (size_t k = 0; k < o_.inputs.size(); k++) PetscCall(CheckOne(k, &owner, &shard_file));
  for (size_t j = 0; j < shard_file.size(); j++) {
    if (shard_file[j] >= 0) continue;
    size_t missing = 0, example = 0;
    for (size_t i = owner.size(); i-- > 0;)
      if (owner[i] < 0) missing++, example = i;
    SETERRQ(PETSC_COMM_SELF, PETSC_ERR_USER, "-merge_inputs: shard %zu/%zu is missing (%zu of the %zu points are in none of the %zu inputs, e.g. %s)", j,
            shard_file.size(), missing, owner.size(), o_.inputs.size(), PointName(first_, example).c_str());
  }
  for (size_t i = 0; i < owner.size(); i++) // every shard given, yet a point in none: shards of different splits
    PetscCheck(owner[i] >= 0, PETSC_COMM_SELF, PETSC_ERR_USER, "-merge_inputs: the point %s is in none of the %zu shards (shards of different splits?)",
               PointName(first_, i).c_str(), shard_file.size());
  order_.assign(shard_file.begin(), shard_file.end());
  nrows_ = first_.energy.size(), ncols_ = first_.omega.size();
  PetscFunctionReturn(0);
}

// Each per-point map, filled from the shards one file at a time.
PetscErrorCode MergeStudy::WritePerPoint(PetscViewer v, const Field &f)
{
  std::vector<PetscReal> real;
  std::vector<PetscInt> ints;
  const bool is_real = f.type == FieldType::Real;
  PetscFunctionBeginUser;
  PetscCheck(f.type != FieldType::String, comm_, PETSC_ERR_PLIB, "-study merge cannot join the string map /sweep/%s", f.name);
  PetscCall(OnRoot([&]() -> PetscErrorCode {
    std::vector<PetscInt> pts, iv;
    std::vector<PetscReal> rv;
    const std::string name = std::string("/sweep/") + f.name;
    PetscFunctionBeginUser;
    if (is_real) real.assign(nrows_ * ncols_, 0);
    else ints.assign(nrows_ * ncols_, 0);
    for (size_t k : order_) {
      const std::string &in = o_.inputs[k];
      PetscCall(ReadInts(in, "/sweep/shard_points", &pts));
      if (is_real) PetscCall(ReadDoubles(in, name.c_str(), &rv));
      else PetscCall(ReadInts(in, name.c_str(), &iv));
      PetscCheck((is_real ? rv.size() : iv.size()) == pts.size(), PETSC_COMM_SELF, PETSC_ERR_USER,
                 "-merge_inputs %s: %s holds %zu values for its %zu points (a damaged file?)", in.c_str(), name.c_str(), is_real ? rv.size() : iv.size(),
                 pts.size());
      for (size_t j = 0; j < pts.size(); j++) // (indices checked by CheckOne)
        if (is_real) real[pts[j]] = rv[j];
        else ints[pts[j]] = iv[j];
    }
    PetscFunctionReturn(0);
  }));
  // as the sweep writes it: ne x no (1-D when no = 1)
  if (is_real) PetscCall(WriteArray(v, "/sweep", f.name, real, (PetscInt)ncols_));
  else PetscCall(WriteIntArray(v, "/sweep", f.name, ints, (PetscInt)ncols_));
  PetscFunctionReturn(0);
}

PetscErrorCode MergeStudy::CopyAttribute(PetscViewer v, const std::string &in, const std::string &from, const char *group, const Field &f)
{
  int has = 0;
  double x = 0;
  long i = 0;
  std::string s;
  PetscMPIInt rank;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm_, &rank));
  if (!rank) {
    const std::string path = from + "/" + f.name;
    has = f.type == FieldType::Real  ? ReadRootAttribute(in, path.c_str(), &x)
          : f.type == FieldType::Int ? ReadRootAttribute(in, path.c_str(), &i)
                                     : ReadRootAttribute(in, path.c_str(), &s);
  }
  PetscCallMPI(MPI_Bcast(&has, 1, MPI_INT, 0, comm_));
  if (!has) PetscFunctionReturn(0);
  PetscCallMPI(MPI_Bcast(&x, 1, MPI_DOUBLE, 0, comm_));
  PetscCallMPI(MPI_Bcast(&i, 1, MPI_LONG, 0, comm_));
  PetscCall(Bcast(&s));
  if (f.type == FieldType::Real) PetscCall(WriteAttr(v, group, f.name, (PetscReal)x));
  else if (f.type == FieldType::Int) PetscCall(WriteAttr(v, group, f.name, (PetscInt)i));
  else PetscCall(WriteAttr(v, group, f.name, s.c_str()));
  PetscFunctionReturn(0);
}

// What is the same in every shard (the axes, the forcing profile, the
// settings as attributes): the first input's; the counts: the map's.
PetscErrorCode MergeStudy::CopyFromFirst(PetscViewer v, const Field &f)
{
  PetscFunctionBeginUser;
  if (f.kind == FieldKind::Attribute) {
    if (!std::strcmp(f.name, "points_done")) PetscCall(WriteAttr(v, "/sweep", f.name, (PetscInt)(nrows_ * ncols_)));
    else if (!std::strcmp(f.name, "points_computed")) {
      PetscInt c = computed_;
      PetscCallMPI(MPI_Bcast(&c, 1, MPIU_INT, 0, comm_));
      PetscCall(WriteAttr(v, "/sweep", f.name, c));
    } else PetscCall(CopyAttribute(v, first_.file, "/sweep", "/sweep", f));
    PetscFunctionReturn(0);
  }
  int has = 0;
  std::vector<PetscReal> x;
  std::vector<PetscInt> iv;
  const std::string name = std::string("/sweep/") + f.name;
  PetscCheck(f.type != FieldType::String, comm_, PETSC_ERR_PLIB, "-study merge cannot copy the string dataset %s", name.c_str());
  PetscCall(OnRoot([&]() -> PetscErrorCode {
    PetscFunctionBeginUser;
    has = HasDataset(first_.file, name.c_str());
    if (has && f.type == FieldType::Real) PetscCall(ReadDoubles(first_.file, name.c_str(), &x));
    if (has && f.type == FieldType::Int) PetscCall(ReadInts(first_.file, name.c_str(), &iv));
    PetscFunctionReturn(0);
  }));
  PetscCallMPI(MPI_Bcast(&has, 1, MPI_INT, 0, comm_));
  if (has && f.type == FieldType::Real) PetscCall(WriteArray(v, "/sweep", f.name, x));
  if (has && f.type == FieldType::Int) PetscCall(WriteIntArray(v, "/sweep", f.name, iv));
  PetscFunctionReturn(0);
}

// /merge: how many shards; /merge/shards/<i>: shard i's file and the root attributes of its run.
PetscErrorCode MergeStudy::WriteProvenance(PetscViewer v)
{
  PetscMPIInt rank;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm_, &rank));
  PetscCall(WriteAttr(v, "/merge", "shard_count", (PetscInt)order_.size()));
  PetscInt c = computed_;
  PetscCallMPI(MPI_Bcast(&c, 1, MPIU_INT, 0, comm_));
  PetscCall(WriteAttr(v, "/merge", "points_computed", c));
  const Schema *s = FindSchema("/merge/shards/<i>");
  PetscCheck(s, comm_, PETSC_ERR_PLIB, "no /merge/shards/<i> schema");
  for (size_t j = 0; j < order_.size(); j++) {
    const std::string group = "/merge/shards/" + std::to_string(j);
    std::string in = rank ? "" : o_.inputs[order_[j]];
    std::vector<PetscInt> pts;
    PetscCall(OnRoot([&]() { return ReadInts(in, "/sweep/shard_points", &pts); }));
    PetscInt npts = (PetscInt)pts.size();
    PetscCall(Bcast(&in));
    PetscCallMPI(MPI_Bcast(&npts, 1, MPIU_INT, 0, comm_));
    PetscCall(WriteAttr(v, group.c_str(), "file", in.c_str()));
    PetscCall(WriteAttr(v, group.c_str(), "shard_index", (PetscInt)j));
    PetscCall(WriteAttr(v, group.c_str(), "points", npts));
    for (const Field &f : s->fields) {
      if (!std::strcmp(f.name, "file") || !std::strcmp(f.name, "shard_index") || !std::strcmp(f.name, "points")) continue;
      PetscCall(CopyAttribute(v, in, !std::strcmp(f.name, "points_computed") ? "/sweep" : "", group.c_str(), f));
    }
  }
  PetscFunctionReturn(0);
}

} // namespace

StudyContract MergeStudyContract()
{
  using namespace schema_names;
  return {{"-merge_"},
          {{"/merge",
            "",
            {{"shard_count", A, I, "scalar", "1", "n, the number of shards joined (-sweep_shard i/n); the map itself is /sweep, as a whole sweep writes it"},
             {"points_computed", A, I, "scalar", "1", "the shards' points_computed, summed"}}},
           {"/merge/shards/<i>",
            "",
            {{"file", A, S, "scalar", "1", "the shard file as given to -merge_inputs"},
             {"shard_index", A, I, "scalar", "1", "i of its -sweep_shard i/n"},
             {"points", A, I, "scalar", "1", "points of the shard"},
             {"points_computed", A, I, "scalar", "1", "its /sweep points_computed (points computed by its last run)"},
             {"study", A, S, "scalar", "1", "its root attribute study"},
             {"version", A, S, "scalar", "1", "its root attribute version: the nltopo that computed it"},
             {"options", A, S, "scalar", "1", "its root attribute options: the options of its run"},
             {"effective_options", A, S, "scalar", "1", "its root attribute effective_options"},
             {"wall_seconds", A, R, "scalar", "s", "its root attribute wall_seconds"},
             {"format_version", A, I, "scalar", "1", "its root attribute format_version"}}}}};
}

std::unique_ptr<Study> CreateMergeStudy() { return std::make_unique<MergeStudy>(); }

} // namespace nltopo
