#pragma once
// Where a sweep keeps its results so that a kill at any moment loses nothing:
//  - every rank appends each finished point to its own journal file
//    <output>.journal.<rank> (one line, doubles in hex: exact), flushed at once;
//  - rank 0 merges all journals into the grid and rewrites <output> (temporary
//    file + rename, so the HDF5 file is always complete) every few seconds and
//    at the end, when the journals are removed;
//  - -sweep_resume reads <output> and any journals left by a killed run.
#include "studies/sweep_shard.hpp"
#include <petscsys.h>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

namespace nltopo {

// What a sweep stores per grid point (outputs.md /sweep, plus additions).
struct SweepPoint {
  PetscReal mcr = 0, t_off = -1, kcorr = 0, nl_ratio = 0, amplitude = 0, energy_final = 0, seconds = 0;
  // -sweep_mcr_tol (docs/studies/sweep.md): the MCR's estimated relative
  // error (NaN without the mode or where unpredictable), the spread (max - min) of
  // the twins' MCRs where the point is unpredictable (0 where it is predictable),
  // whether it is (1, 0; -1 without the mode), and the integrations spent on it.
  PetscReal mcr_error = std::numeric_limits<PetscReal>::quiet_NaN(), mcr_spread = 0;
  PetscInt reached = 0, rescalings = 0, rhs = 0, steps = 0;
  PetscInt failed = 0; // the run stopped with an error (e.g. diverged); its numbers are NaN
  PetscInt predictable = -1, runs = 1;
  PetscReal mcr_dt = std::numeric_limits<PetscReal>::quiet_NaN(); // the step of the run(s) behind mcr (NaN without -sweep_mcr_tol)
  // -sweep_lyapunov: the maximal finite-time Lyapunov exponent over the MCR window and over its first half (NaN without),
  // and the regime it and the twins give (codes::kRegime)
  PetscReal lyapunov = std::numeric_limits<PetscReal>::quiet_NaN(), lyapunov_half = std::numeric_limits<PetscReal>::quiet_NaN();
  PetscInt regime = -1;
};

// The per-point (ne x no) datasets of the /sweep schema (sweep_study.cpp) but
// done, in its order, and the SweepPoint fields behind them: what the sweep
// study writes, SweepGrid::Load reads back and a journal line holds.
// Where a finished point may hold NaN (a sweep never writes inf): never, only
// as a failed point's value (failed = 1), or always (no 0-1 test, no estimate).
enum class NanAllowed { Never, IfFailed, Always };
struct SweepRealField {
  const char *name;
  PetscReal SweepPoint::*field;
  NanAllowed nan = NanAllowed::Never;
};
struct SweepIntField {
  const char *name;
  PetscInt SweepPoint::*field;
};
const std::vector<SweepRealField> &SweepRealFields();
const std::vector<SweepIntField> &SweepIntFields();
// Schema fields without a SweepPoint member, and members the schema lacks (tests: none).
std::vector<std::string> SweepFieldsUnbound();

// Rank 0's picture of the grid: energy rows x omega columns, row-major.
// A shard (-sweep_shard) holds the whole grid in memory too, but computes,
// counts and writes only its points.
struct SweepGrid {
  std::vector<PetscReal> omega, energy;
  std::vector<SweepPoint> pts;
  std::vector<PetscInt> done;
  SweepShard shard;           // !shard.On(): the whole grid
  std::vector<size_t> points; // a shard's grid indices, ascending (studies/sweep_shard.hpp), or a refinement's (scattered)
  bool scattered = false;     // -sweep_refine_from: the grid is a refinement's fine lattice, its points the samples (studies/sweep_refine.hpp)
  size_t Size() const { return omega.size() * energy.size(); }
  // This run's points: the shard's, the refinement's, or the whole grid's; At(k) the grid index of the k-th.
  bool Subset() const { return shard.On() || scattered; }
  size_t Count() const { return Subset() ? points.size() : Size(); }
  size_t At(size_t k) const { return Subset() ? points[k] : k; }
  PetscInt Done() const; // of this run's points
  void Reset(const std::vector<PetscReal> &w, const std::vector<PetscReal> &e);
  // Loads a sweep file written by Write (resume); the axes must equal this
  // grid's, and so must the shard and its points (a shard file holds its
  // points' values as 1-D datasets over /sweep/shard_points).
  // opt names the option in messages (-sweep_refine_from loads a base grid).
  PetscErrorCode Load(const std::string &path, const char *opt = "-sweep_resume");
  // Merges every <path>.journal.* into the grid; *lines = points read.
  PetscErrorCode MergeJournals(const std::string &path, PetscInt *lines);
};

// Whether p, a finished point, holds only values a sweep writes (NaN where
// SweepRealField allows it; 0 or 1 in failed); else false and *what names the
// first other value ("mcr = nan"). A resume refuses the file or journal.
bool SweepPointValid(const SweepPoint &p, std::string *what);

// Names of the journal files of an output path.
std::vector<std::string> JournalFiles(const std::string &path);

class Journal {
public:
  ~Journal() { Close(); }
  PetscErrorCode Open(const std::string &path, PetscMPIInt rank);
  PetscErrorCode Append(size_t index, const SweepPoint &p);
  void Close();

private:
  FILE *f_ = nullptr;
};

} // namespace nltopo
