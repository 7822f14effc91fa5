#include "io/output.hpp"
#include "io/cost_card.hpp"
#include "io/output_claim.hpp"
#include "core/effective_options.hpp"
#include "core/errors.hpp"
#include "core/log.hpp"
#include "core/option_table.hpp"
#include "io/run_options.hpp"
#include "io/schema.hpp"
#include "io/self_describe.hpp"
#include <petscviewerhdf5.h>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <sys/stat.h>
#include <sys/statvfs.h>
#include <unistd.h>

namespace nltopo {

namespace {
struct OutputOptions {
  std::string path; // the study's name + ".h5" when not given
  PetscBool overwrite = PETSC_FALSE;
};
} // namespace

// Where the output goes is never compared (io/run_options.hpp).
static const auto &kOutputTable = DeclareOptionTable<OutputOptions>(NULL, "Output (docs/outputs.md)", [](OptionTable<OutputOptions> &t) {
  t.String("output", &OutputOptions::path, "HDF5 file to write (default <study>.h5)", OptionClass::Bookkeeping)
      .Default("<study>.h5")
      .Bool("output_overwrite", &OutputOptions::overwrite,
            "Replace -output even if it holds the output of another study or of other physics/numerics options (docs/errors.md, overwrite rule)",
            OptionClass::Bookkeeping);
});

static PetscErrorCode ReadOutputOptions(MPI_Comm comm, const char *study, std::string *path, PetscBool *overwrite)
{
  OutputOptions o;
  PetscFunctionBeginUser;
  o.path = std::string(study) + ".h5";
  PetscCall(kOutputTable.Read(comm, &o));
  PetscCheck(!o.path.empty(), comm, PETSC_ERR_USER, "-output must name a file");
  *path = o.path;
  *overwrite = o.overwrite;
  PetscFunctionReturn(0);
}

PetscErrorCode DeclareOutputOptions(MPI_Comm comm, const char *study)
{
  std::string path;
  PetscBool overwrite;
  return ReadOutputOptions(comm, study, &path, &overwrite);
}

PetscErrorCode OutputPathOption(MPI_Comm comm, const char *study, std::string *path)
{
  PetscBool overwrite;
  return ReadOutputOptions(comm, study, path, &overwrite);
}

// A fresh run next to an earlier run's partial output: refused (it would
// replace it), or with -output_overwrite the partial output and its journals
// are discarded. Rank 0 looks; every rank fails alike.
static PetscErrorCode CheckPartial(MPI_Comm comm, const std::string &path, PetscBool overwrite, const char *resume_how)
{
  PetscMPIInt rank;
  char msg[1024] = "";
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  const std::string partial = PartialPath(path);
  if (!rank && !access(partial.c_str(), F_OK)) {
    if (overwrite) {
      std::remove(partial.c_str());
      for (const std::string &f : FilesNamed(path + ".journal.")) std::remove(f.c_str());
    } else {
      std::string how = resume_how ? resume_how : "";
      if (how.find("{}") != std::string::npos) how.replace(how.find("{}"), 2, partial);
      const std::string m = "-output " + path + ": " + partial + " holds the partial output (complete = 0) of an earlier run; " +
                            (how.empty() ? "" : "continue it with " + how + ", or ") + "remove it or give -output_overwrite to start afresh";
      PetscCall(PetscStrncpy(msg, m.c_str(), sizeof(msg)));
    }
  }
  PetscCallMPI(MPI_Bcast(msg, sizeof(msg), MPI_CHAR, 0, comm));
  PetscCheck(!msg[0], comm, PETSC_ERR_FILE_WRITE, "%s", msg);
  PetscFunctionReturn(0);
}

PetscErrorCode OutputPathFromOptions(MPI_Comm comm, const char *study, std::string *path, const std::function<bool(const std::string &)> &resumes,
                                     const char *resume_how)
{
  PetscBool overwrite;
  PetscFunctionBeginUser;
  PetscCall(ReadOutputOptions(comm, study, path, &overwrite));
  if (!(resumes && resumes(*path))) PetscCall(CheckOverwrite(comm, *path, study, overwrite));
  if (!(resumes && resumes(PartialPath(*path)))) PetscCall(CheckPartial(comm, *path, overwrite, resume_how));
  PetscFunctionReturn(0);
}

static PetscErrorCode (*g_commit_guard)(MPI_Comm) = nullptr;
static const double kMinFreeBytes = 1e6; // HDF5 metadata and the root attributes

// A collective write step fails on every rank if it failed on any: a failure
// on some ranks only (disk full under MPI-IO) would leave the others waiting
// in the next collective call.
#define AGREE(comm, expr, what)                                                                                                                                \
  do {                                                                                                                                                         \
    PetscCall(PetscPushErrorHandler(PetscReturnErrorHandler, NULL));                                                                                           \
    const int bad_ = (expr) ? 1 : 0;                                                                                                                           \
    PetscCall(PetscPopErrorHandler());                                                                                                                         \
    int any_;                                                                                                                                                  \
    PetscCallMPI(MPI_Allreduce(&bad_, &any_, 1, MPI_INT, MPI_MAX, comm));                                                                                      \
    PetscCheck(!any_, comm, PETSC_ERR_LIB, "HDF5 %s failed", what);                                                                                            \
  } while (0)

PetscErrorCode SetCommitGuard(PetscErrorCode (*guard)(MPI_Comm))
{
  g_commit_guard = guard;
  return 0;
}

OutputFile::~OutputFile()
{
  if (tmp_.empty() || committed_) return;
  PetscPushErrorHandler(PetscIgnoreErrorHandler, NULL); // closing after a failed write fails too: the first error was reported
  viewer_.reset();
  PetscPopErrorHandler();
  PetscMPIInt rank = 0;
  MPI_Comm_rank(comm_, &rank);
  if (!rank) std::remove(tmp_.c_str()); // never leave a partial file behind
}

PetscErrorCode OutputFile::Open(MPI_Comm comm, const std::string &path, const std::string &tag, double expected_bytes)
{
  PetscMPIInt rank;
  int pid = (int)getpid(), err = 0;
  char msg[256] = "";
  PetscFunctionBeginUser;
  comm_ = comm;
  path_ = path;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCallMPI(MPI_Bcast(&pid, 1, MPI_INT, 0, comm));
  tmp_ = path + ".tmp." + tag + std::to_string(pid);
  struct stat st;
  if (!rank && !stat(path.c_str(), &st) && S_ISDIR(st.st_mode)) {
    err = EISDIR;
    PetscCall(PetscStrncpy(msg, "is a directory", sizeof(msg)));
  } else if (!rank) { // probe: can we create a file next to the target?
    FILE *f = std::fopen(tmp_.c_str(), "w");
    if (!f) {
      err = errno;
      PetscCall(PetscStrncpy(msg, std::strerror(err), sizeof(msg)));
    } else {
      std::fclose(f);
      std::remove(tmp_.c_str());
      // Disk full is refused here, up front: parallel HDF5 (1.10) does not
      // fail collectively when MPI-IO runs out of space mid-write.
      struct statvfs fs;
      const std::string dir = path.find('/') == std::string::npos ? "." : path.substr(0, path.rfind('/') + 1);
      const double need = expected_bytes + kMinFreeBytes;
      if (!statvfs(dir.c_str(), &fs) && (double)fs.f_bavail * (double)fs.f_frsize < need) {
        err = ENOSPC;
        PetscCall(PetscSNPrintf(msg, sizeof(msg), "needs about %.3g MB, the filesystem has %.3g MB free", need / 1e6, (double)fs.f_bavail * fs.f_frsize / 1e6));
      }
    }
  }
  PetscCallMPI(MPI_Bcast(&err, 1, MPI_INT, 0, comm));
  PetscCallMPI(MPI_Bcast(msg, sizeof(msg), MPI_CHAR, 0, comm));
  if (err) tmp_.clear(); // nothing of ours to remove
  PetscCheck(!err, comm, PETSC_ERR_FILE_OPEN, "cannot write -output %s: %s", path.c_str(), msg);
  SetOutputContext(path.c_str());
  PetscCall(PetscViewerHDF5Open(comm, tmp_.c_str(), FILE_MODE_WRITE, viewer_.out()));
  PetscFunctionReturn(0);
}

PetscErrorCode OutputFile::Commit(const char *study, PetscReal wall_seconds, bool complete)
{
  char *opts;
  PetscMPIInt rank;
  int err = 0;
  PetscFunctionBeginUser;
  if (complete && g_commit_guard) {
    PetscMPIInt size, world;
    PetscCallMPI(MPI_Comm_size(comm_, &size));
    PetscCallMPI(MPI_Comm_size(PETSC_COMM_WORLD, &world));
    if (size == world) PetscCall(g_commit_guard(comm_)); // a rank-local commit (sweep) audits collectively itself
  }
  PetscCall(WriteCostCard(viewer_, wall_seconds)); // /cost: integrators, work, accuracy
  PetscCall(PetscOptionsGetAll(NULL, &opts));
  PetscCall(WriteAttr(viewer_, "/", "study", study));
  PetscCall(WriteAttr(viewer_, "/", "version", NLTOPO_VERSION));
  PetscCall(WriteAttr(viewer_, "/", "options", opts));
  PetscCall(WriteAttr(viewer_, "/", "effective_options", EffectiveOptionsText().c_str()));
  PetscCall(WriteAttr(viewer_, "/", "wall_seconds", wall_seconds));
  PetscCall(WriteAttr(viewer_, "/", "complete", (PetscInt)complete));
  PetscCall(WriteAttr(viewer_, "/", "format_version", kFormatVersion));
  PetscCall(PetscFree(opts));
  PetscCall(WriteGivenOptions(viewer_));
  PetscCall(DescribeFile(viewer_)); // description, units and codes of every field (io/self_describe.hpp)
  PetscViewer raw = viewer_.release();
  AGREE(comm_, PetscViewerDestroy(&raw), "flush and close"); // the close may fail (disk full)
  PetscCallMPI(MPI_Comm_rank(comm_, &rank));
  if (!rank && std::rename(tmp_.c_str(), path_.c_str())) err = errno;
  PetscCallMPI(MPI_Bcast(&err, 1, MPI_INT, 0, comm_));
  PetscCheck(!err, comm_, PETSC_ERR_FILE_WRITE, "cannot write -output %s: %s", path_.c_str(), std::strerror(err));
  committed_ = true;
  PetscFunctionReturn(0);
}

static PetscErrorCode WriteRank0(PetscViewer v, const char *group, const char *name, const PetscReal *data, PetscInt n, PetscInt bs)
{
  MPI_Comm comm = PetscObjectComm((PetscObject)v);
  PetscMPIInt rank;
  OwnedVec x;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCallMPI(MPI_Bcast(&n, 1, MPIU_INT, 0, comm));
  PetscCall(VecCreate(comm, x.out()));
  PetscCall(VecSetSizes(x, rank ? 0 : n, n));
  PetscCall(VecSetBlockSize(x, bs));
  PetscCall(VecSetType(x, VECSTANDARD));
  if (!rank && n) {
    PetscScalar *a;
    PetscCall(VecGetArray(x, &a));
    for (PetscInt i = 0; i < n; i++) a[i] = data[i];
    PetscCall(VecRestoreArray(x, &a));
  }
  PetscCall(WriteVec(v, group, name, x));
  PetscFunctionReturn(0);
}

PetscErrorCode WriteArray(PetscViewer v, const char *group, const char *name, const std::vector<PetscReal> &data, PetscInt bs)
{
  PetscFunctionBeginUser;
  PetscCall(SchemaCheckWrite(PetscObjectComm((PetscObject)v), group, name, FieldKind::Dataset, FieldType::Real));
  PetscCall(WriteRank0(v, group, name, data.data(), (PetscInt)data.size(), bs));
  PetscFunctionReturn(0);
}

// Raw HDF5 calls return a negative value on failure.
#define H5CHK(call)                                                                                                                                            \
  do {                                                                                                                                                         \
    if ((call) < 0)                                                                                                                                            \
      SETERRQ(PetscObjectComm((PetscObject)v), PETSC_ERR_LIB, "HDF5 call %.*s failed", (int)std::strcspn(#call, "("),                                          \
              #call); /* collective writes fail on every rank */                                                                                               \
  } while (0)

PetscErrorCode WriteColumnBlock(PetscViewer v, const char *group, const char *name, PetscInt rows, PetscInt ncols, PetscInt col0, PetscInt nloc,
                                const std::vector<PetscReal> &local)
{
  hid_t file, grp, space, mem, dset, xfer;
  PetscMPIInt size;
  PetscFunctionBeginUser;
  PetscCall(SchemaCheckWrite(PetscObjectComm((PetscObject)v), group, name, FieldKind::Dataset, FieldType::Real));
  PetscCall(PetscLogEventBegin(Log().output, 0, 0, 0, 0));
  PetscCallMPI(MPI_Comm_size(PetscObjectComm((PetscObject)v), &size));
  PetscCheck(rows >= 0 && ncols > 0, PetscObjectComm((PetscObject)v), PETSC_ERR_ARG_OUTOFRANGE, "empty dataset %s/%s", group, name);
  const int rank_nd = rows > 0 ? 2 : 1; // rows = 0: a 1-D dataset of ncols values
  const PetscInt r = rows > 0 ? rows : 1;
  PetscCall(PetscViewerHDF5WriteGroup(v, group));
  PetscCall(PetscViewerHDF5GetFileId(v, &file));
  const hsize_t dims2[2] = {(hsize_t)r, (hsize_t)ncols}, start2[2] = {0, (hsize_t)col0}, count2[2] = {(hsize_t)r, (hsize_t)nloc};
  const hsize_t *dims = rank_nd == 2 ? dims2 : dims2 + 1, *start = rank_nd == 2 ? start2 : start2 + 1, *count = rank_nd == 2 ? count2 : count2 + 1;
  H5CHK(grp = H5Gopen2(file, group, H5P_DEFAULT));
  H5CHK(space = H5Screate_simple(rank_nd, dims, NULL));
  H5CHK(dset = H5Dcreate2(grp, name, H5T_NATIVE_DOUBLE, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT));
  H5CHK(mem = H5Screate_simple(rank_nd, count, NULL));
  if (r * nloc > 0) H5CHK(H5Sselect_hyperslab(space, H5S_SELECT_SET, start, NULL, count, NULL));
  else {
    H5CHK(H5Sselect_none(space));
    H5CHK(H5Sselect_none(mem));
  }
  H5CHK(xfer = H5Pcreate(H5P_DATASET_XFER));
#if defined(H5_HAVE_PARALLEL)
  if (size > 1) H5CHK(H5Pset_dxpl_mpio(xfer, H5FD_MPIO_COLLECTIVE));
#endif
  AGREE(PetscObjectComm((PetscObject)v), H5Dwrite(dset, H5T_NATIVE_DOUBLE, mem, space, xfer, local.data()) < 0, "H5Dwrite");
  H5CHK(H5Pclose(xfer));
  H5CHK(H5Sclose(mem));
  H5CHK(H5Dclose(dset));
  H5CHK(H5Sclose(space));
  H5CHK(H5Gclose(grp));
  PetscCall(PetscLogEventEnd(Log().output, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

// A dataset of the given HDF5 type and shape whose values rank 0 gives
// (buf); the other ranks select nothing. Collective.
static PetscErrorCode WriteRootDataset(PetscViewer v, const char *group, const char *name, hid_t type, const std::vector<hsize_t> &dims, const void *buf)
{
  hid_t file, grp, space, dset, xfer;
  PetscMPIInt rank, size;
  MPI_Comm comm = PetscObjectComm((PetscObject)v);
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCallMPI(MPI_Comm_size(comm, &size));
  PetscCall(PetscViewerHDF5WriteGroup(v, group));
  PetscCall(PetscViewerHDF5GetFileId(v, &file));
  H5CHK(grp = H5Gopen2(file, group, H5P_DEFAULT));
  H5CHK(space = H5Screate_simple((int)dims.size(), dims.data(), NULL));
  H5CHK(dset = H5Dcreate2(grp, name, type, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT));
  hsize_t count = 1;
  for (hsize_t d : dims) count *= d;
  if (count) { // (every rank has the same dims; a dataset with no rows is created, not written)
    if (rank) H5CHK(H5Sselect_none(space));
    H5CHK(xfer = H5Pcreate(H5P_DATASET_XFER));
#if defined(H5_HAVE_PARALLEL)
    if (size > 1) H5CHK(H5Pset_dxpl_mpio(xfer, H5FD_MPIO_COLLECTIVE));
#endif
    AGREE(comm, H5Dwrite(dset, type, rank ? space : H5S_ALL, space, xfer, buf) < 0, "H5Dwrite");
    H5CHK(H5Pclose(xfer));
  }
  H5CHK(H5Dclose(dset));
  H5CHK(H5Sclose(space));
  H5CHK(H5Gclose(grp));
  PetscFunctionReturn(0);
}

PetscErrorCode WriteArrayND(PetscViewer v, const char *group, const char *name, const std::vector<PetscReal> &data, const std::vector<PetscInt> &dims)
{
  PetscMPIInt rank;
  MPI_Comm comm = PetscObjectComm((PetscObject)v);
  PetscFunctionBeginUser;
  PetscCall(SchemaCheckWrite(comm, group, name, FieldKind::Dataset, FieldType::Real));
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  size_t n = 1;
  for (PetscInt d : dims) n *= (size_t)d;
  PetscCheck(!dims.empty() && (rank || n == data.size()), comm, PETSC_ERR_ARG_SIZ, "dataset %s/%s: %zu values for its shape", group, name, data.size());
  PetscCall(WriteRootDataset(v, group, name, H5T_NATIVE_DOUBLE, std::vector<hsize_t>(dims.begin(), dims.end()), data.data()));
  PetscFunctionReturn(0);
}

PetscErrorCode WriteIntArray(PetscViewer v, const char *group, const char *name, const std::vector<PetscInt> &data, PetscInt bs, bool two_d)
{
  MPI_Comm comm = PetscObjectComm((PetscObject)v);
  PetscInt n = (PetscInt)data.size();
  PetscFunctionBeginUser;
  PetscCall(SchemaCheckWrite(comm, group, name, FieldKind::Dataset, FieldType::Int));
  PetscCallMPI(MPI_Bcast(&n, 1, MPIU_INT, 0, comm));
  PetscCheck(n >= 0 && bs > 0 && n % bs == 0, comm, PETSC_ERR_ARG_SIZ, "integer dataset %s/%s: %" PetscInt_FMT " values, block %" PetscInt_FMT, group, name, n,
             bs);
  std::vector<hsize_t> dims = {(hsize_t)(n / bs)};
  if (bs != 1 || two_d) dims.push_back((hsize_t)bs);
  const std::vector<int> buf(data.begin(), data.end());
  PetscCall(WriteRootDataset(v, group, name, H5T_NATIVE_INT, dims, buf.data()));
  PetscFunctionReturn(0);
}

PetscErrorCode WriteStringArray(PetscViewer v, const char *group, const char *name, const std::vector<std::string> &data)
{
  hid_t type;
  PetscMPIInt rank;
  MPI_Comm comm = PetscObjectComm((PetscObject)v);
  PetscInt n = (PetscInt)data.size(), width = 1;
  PetscFunctionBeginUser;
  PetscCall(SchemaCheckWrite(comm, group, name, FieldKind::Dataset, FieldType::String));
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  for (const auto &s : data) width = std::max(width, (PetscInt)s.size() + 1);
  PetscCallMPI(MPI_Bcast(&n, 1, MPIU_INT, 0, comm));
  PetscCallMPI(MPI_Bcast(&width, 1, MPIU_INT, 0, comm));
  std::vector<char> buf(rank || !n ? 1 : (size_t)(n * width), '\0'); // (no values: a dataset with no rows)
  if (!rank)
    for (PetscInt i = 0; i < n; i++) std::copy(data[i].begin(), data[i].end(), buf.begin() + i * width);
  H5CHK(type = H5Tcopy(H5T_C_S1));
  H5CHK(H5Tset_size(type, (size_t)width));
  H5CHK(H5Tset_strpad(type, H5T_STR_NULLTERM));
  PetscCall(WriteRootDataset(v, group, name, type, {(hsize_t)n}, buf.data()));
  H5CHK(H5Tclose(type));
  PetscFunctionReturn(0);
}

PetscErrorCode WriteDistributed(PetscViewer v, const char *group, const char *name, Vec x)
{
  PetscInt N, lo, hi;
  const PetscScalar *a;
  PetscFunctionBeginUser;
  PetscCall(VecGetSize(x, &N));
  PetscCall(VecGetOwnershipRange(x, &lo, &hi));
  PetscCall(VecGetArrayRead(x, &a));
  std::vector<PetscReal> local(a, a + (hi - lo));
  PetscCall(VecRestoreArrayRead(x, &a));
  PetscCall(WriteColumnBlock(v, group, name, 0, N, lo, hi - lo, local));
  PetscFunctionReturn(0);
}

PetscErrorCode WriteVec(PetscViewer v, const char *group, const char *name, Vec x)
{
  PetscFunctionBeginUser;
  PetscCall(SchemaCheckWrite(PetscObjectComm((PetscObject)v), group, name, FieldKind::Dataset, FieldType::Real));
  PetscCall(PetscLogEventBegin(Log().output, 0, 0, 0, 0));
  PetscCall(PetscObjectSetName((PetscObject)x, name));
  PetscCall(PetscViewerHDF5PushGroup(v, group));
  AGREE(PetscObjectComm((PetscObject)v), VecView(x, v), "write");
  PetscCall(PetscViewerHDF5PopGroup(v));
  PetscCall(PetscLogEventEnd(Log().output, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

PetscErrorCode WriteAttr(PetscViewer v, const char *path, const char *name, PetscReal value)
{
  PetscFunctionBeginUser;
  PetscCall(SchemaCheckWrite(PetscObjectComm((PetscObject)v), path, name, FieldKind::Attribute, FieldType::Real));
  PetscCall(PetscViewerHDF5WriteGroup(v, path));
  PetscCall(PetscViewerHDF5WriteAttribute(v, path, name, PETSC_REAL, &value));
  PetscFunctionReturn(0);
}

PetscErrorCode WriteAttr(PetscViewer v, const char *path, const char *name, PetscInt value)
{
  PetscFunctionBeginUser;
  PetscCall(SchemaCheckWrite(PetscObjectComm((PetscObject)v), path, name, FieldKind::Attribute, FieldType::Int));
  PetscCall(PetscViewerHDF5WriteGroup(v, path));
  PetscCall(PetscViewerHDF5WriteAttribute(v, path, name, PETSC_INT, &value));
  PetscFunctionReturn(0);
}

PetscErrorCode WriteAttr(PetscViewer v, const char *path, const char *name, const char *value)
{
  PetscFunctionBeginUser;
  PetscCall(SchemaCheckWrite(PetscObjectComm((PetscObject)v), path, name, FieldKind::Attribute, FieldType::String));
  PetscCall(PetscViewerHDF5WriteGroup(v, path));
  PetscCall(PetscViewerHDF5WriteAttribute(v, path, name, PETSC_STRING, value));
  PetscFunctionReturn(0);
}

} // namespace nltopo
