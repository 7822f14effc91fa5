#pragma once
// HDF5 output per docs/outputs.md. The file is written under a
// temporary name and renamed at Commit(), so a failed or killed run never
// leaves a partial file at the -output path. What a run has before it ends
// (a checkpoint, an interrupted run's part) is committed whole and readable,
// marked by the root attribute complete = 0, at <output>.partial.h5
// (PartialPath, io/output_claim.hpp), never at -output.
#include "core/handle.hpp"
#include <functional>
#include <string>
#include <vector>

namespace nltopo {

// -output <file.h5>, default "<study>.h5". An existing nltopo output there of
// another study or other options (io/run_options.hpp) is an error unless
// -output_overwrite is given, or resumes(path) says this run continues that
// very file (its resume check applies instead). So is an existing partial
// output <path>.partial.h5 (io/output_claim.hpp), whatever its options,
// unless resumes(<path>.partial.h5): a fresh run would replace it. The
// refusal says how to continue it: resume_how, e.g. "-sweep_resume" or
// "-cont_resume {}" ({} the partial file). -output_overwrite discards it.
PetscErrorCode OutputPathFromOptions(MPI_Comm comm, const char *study, std::string *path, const std::function<bool(const std::string &)> &resumes = nullptr,
                                     const char *resume_how = nullptr);
// The same options read without looking at the file (a study's options function, -help).
PetscErrorCode DeclareOutputOptions(MPI_Comm comm, const char *study);
// -output as given (default "<study>.h5"), without the checks: the path a run
// claims (io/output_claim.hpp) before it looks at what is there.
PetscErrorCode OutputPathOption(MPI_Comm comm, const char *study, std::string *path);

// Called by Commit before a complete output is renamed into place, when the
// file's communicator spans every rank (the registry's unused-options audit).
PetscErrorCode SetCommitGuard(PetscErrorCode (*guard)(MPI_Comm));

class OutputFile {
public:
  ~OutputFile();
  // Checks that the path is writable and its filesystem has room for about
  // expected_bytes plus 1 MB (errors name -output), and opens the temporary
  // file <path>.tmp.<tag><pid> (tag: e.g. "checkpoint.", so that a checkpoint
  // and the final file can be open at once).
  PetscErrorCode Open(MPI_Comm comm, const std::string &path, const std::string &tag = "", double expected_bytes = 0);
  PetscViewer Viewer() const { return viewer_; }
  // Writes the root attributes (study, version, options, wall_seconds,
  // complete: 0 for a checkpoint of a run still going, format_version), the
  // structured options and every field's description (io/self_describe.hpp),
  // closes, renames.
  PetscErrorCode Commit(const char *study, PetscReal wall_seconds, bool complete = true);

private:
  MPI_Comm comm_ = MPI_COMM_NULL;
  std::string path_, tmp_;
  OwnedViewer viewer_;
  bool committed_ = false;
};

// A 1-D (bs = 1) or 2-D (n/bs x bs) float64 dataset whose values are given on
// rank 0 (other ranks pass anything; only rank 0's data is written).
PetscErrorCode WriteArray(PetscViewer v, const char *group, const char *name, const std::vector<PetscReal> &data, PetscInt bs = 1);
// A 2-D (rows x ncols) float64 dataset written by columns: each rank gives its
// columns [col0, col0 + nloc) of every row, row-major (rows x nloc). Used for
// time series of distributed fields (e.g. /simulate/u, nt x N) in one write.
PetscErrorCode WriteColumnBlock(PetscViewer v, const char *group, const char *name, PetscInt rows, PetscInt ncols, PetscInt col0, PetscInt nloc,
                                const std::vector<PetscReal> &local);
// A float64 dataset of any rank (dims, row-major) whose values are given on rank 0.
PetscErrorCode WriteArrayND(PetscViewer v, const char *group, const char *name, const std::vector<PetscReal> &data, const std::vector<PetscInt> &dims);
// An integer dataset (bs = 1: 1-D unless two_d; else n/bs x bs) whose values are given on rank 0.
PetscErrorCode WriteIntArray(PetscViewer v, const char *group, const char *name, const std::vector<PetscInt> &data, PetscInt bs = 1, bool two_d = false);
// A 1-D dataset of fixed-length strings (the longest + 1; h5py reads bytes)
// whose values are given on rank 0.
PetscErrorCode WriteStringArray(PetscViewer v, const char *group, const char *name, const std::vector<std::string> &data);
// A distributed 1-D vector as a contiguous float64 dataset (N), each rank
// writing its block collectively with raw HDF5 (VecView's chunked parallel
// write needed GBs per rank at N = 10^6).
PetscErrorCode WriteDistributed(PetscViewer v, const char *group, const char *name, Vec x);
// A distributed vector (its object name is set to name).
PetscErrorCode WriteVec(PetscViewer v, const char *group, const char *name, Vec x);
PetscErrorCode WriteAttr(PetscViewer v, const char *path, const char *name, PetscReal value);
PetscErrorCode WriteAttr(PetscViewer v, const char *path, const char *name, PetscInt value);
PetscErrorCode WriteAttr(PetscViewer v, const char *path, const char *name, const char *value);

} // namespace nltopo
