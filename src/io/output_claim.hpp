#pragma once
// One run per -output (docs/errors.md "One run per output"). Before a run
// reads or writes anything next to its -output, rank 0 creates the lock file
// <output>.lock with O_CREAT | O_EXCL: atomic on local filesystems and on NFS
// v3 and later, where flock is not honoured. The lock holds one line naming
// its owner (process id, host, boot id, the process's start time), and the
// run removes it when it ends, however it ends. Only the holder of the lock
// writes <output>, its temporaries (<file>.tmp.*), its partial output and
// the sweep's journals.
//
// A second run into the same -output is refused in one line that names the
// owner. It never waits. A lock whose owner is provably gone is taken over:
// same host and boot, and its process no longer running (or a zombie, or its
// id reused by a later process). This covers SIGKILL and the OOM killer. The
// taker removes the dead run's temporaries, keeps its partial output and
// journals for a resume, and says so in one warning line. A lock of another
// host, or one that names no owner, is never taken over: the refusal says to
// remove it once that run is known to be over.
//
// What else a run leaves next to -output (docs/errors.md "Partial and failed
// runs") is settled here too, at Release: a complete run removes the partial
// output it supersedes, an interrupted one keeps its partial output, a failed
// one removes what it created and keeps what it found.
#include <petscsys.h>
#include <string>
#include <vector>

namespace nltopo {

// <output>.lock
std::string LockPath(const std::string &output);
// <output>.partial.h5: where a run that stops early (a signal) leaves what it
// has, and where the sweep's and the continuation's checkpoints go (root
// attribute complete = 0). -output itself only ever receives a complete result.
std::string PartialPath(const std::string &output);
// The files whose path starts with prefix (in prefix's directory), e.g. FilesNamed("o.h5.tmp.").
std::vector<std::string> FilesNamed(const std::string &prefix);

// How a run ended, for what it leaves next to -output (Release).
enum class RunEnd {
  Complete,    // -output committed: the partial output and journals it supersedes go
  Interrupted, // a stop signal: the partial output (and any journal) stays for a resume
  Failed       // an error: the files the run created go, the ones it found stay
};

class OutputClaim {
public:
  OutputClaim() = default;
  OutputClaim(const OutputClaim &) = delete;
  OutputClaim &operator=(const OutputClaim &) = delete;
  ~OutputClaim() { Release(RunEnd::Failed); }
  // Collective on comm. Rank 0 claims path (removes stale temporaries and
  // records what is there, RecordFound); if it cannot, every rank fails with the same one line.
  PetscErrorCode Acquire(MPI_Comm comm, const std::string &path);
  // Rank 0 notes what is next to -output before the run writes there (its
  // partial output, sweep journals): a failed run leaves these as they are.
  void RecordFound();
  // Rank 0 tidies up as `end` says (temporaries always go) and removes the
  // lock. Not collective: also on error paths.
  void Release(RunEnd end);
  bool Held() const { return !lock_.empty(); }

private:
  std::string path_, lock_, owner_; // -output, the lock file and the line it holds (rank 0, while held)
  bool partial_found_ = false;
  std::vector<std::pair<std::string, unsigned long>> journals_found_; // (name, inode)
};

} // namespace nltopo
