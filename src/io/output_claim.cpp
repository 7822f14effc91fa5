#include "io/output_claim.hpp"
#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <dirent.h>
#include <fcntl.h>
#include <fstream>
#include <sys/stat.h>
#include <sstream>
#include <unistd.h>
#include <vector>

namespace nltopo {

std::string LockPath(const std::string &output) { return output + ".lock"; }

std::string PartialPath(const std::string &output) { return output + ".partial.h5"; }

namespace {

std::string FirstLine(const std::string &path)
{
  std::ifstream f(path);
  std::string s;
  std::getline(f, s);
  return s;
}

// Fields 3 (state) and 22 (start time, clock ticks since boot) of /proc/<pid>/stat; false if unreadable.
bool ProcStat(long pid, char *state, unsigned long long *start)
{
  const std::string s = FirstLine("/proc/" + std::to_string(pid) + "/stat");
  const size_t close = s.rfind(')'); // (the command name may hold spaces and parentheses)
  if (close == std::string::npos) return false;
  std::istringstream in(s.substr(close + 1));
  std::string tok;
  for (int field = 3; in >> tok; field++) {
    if (field == 3) *state = tok[0];
    if (field == 22) {
      *start = std::strtoull(tok.c_str(), nullptr, 10);
      return true;
    }
  }
  return false;
}

// Who holds a lock: its one line,
//   nltopo-lock pid=<pid> host=<host name> boot=<boot id> start=<ticks since boot> time=<seconds since the epoch>
struct Owner {
  long pid = 0;
  std::string host, boot;
  unsigned long long start = 0;
  long long time = 0;

  static Owner Me()
  {
    Owner o;
    char host[256] = "";
    char state;
    o.pid = (long)getpid();
    gethostname(host, sizeof(host) - 1);
    o.host = host;
    o.boot = FirstLine("/proc/sys/kernel/random/boot_id");
    ProcStat(o.pid, &state, &o.start);
    o.time = (long long)std::time(nullptr);
    return o;
  }
  std::string Line() const
  {
    return "nltopo-lock pid=" + std::to_string(pid) + " host=" + host + " boot=" + boot + " start=" + std::to_string(start) + " time=" + std::to_string(time);
  }
  bool Parse(const std::string &line)
  {
    std::istringstream in(line);
    std::string tok;
    if (!(in >> tok) || tok != "nltopo-lock") return false;
    int seen = 0;
    while (in >> tok) {
      const size_t eq = tok.find('=');
      if (eq == std::string::npos) continue;
      const std::string k = tok.substr(0, eq), v = tok.substr(eq + 1);
      if (k == "pid") pid = std::atol(v.c_str()), seen++;
      else if (k == "host") host = v, seen++;
      else if (k == "boot") boot = v;
      else if (k == "start") start = std::strtoull(v.c_str(), nullptr, 10);
      else if (k == "time") time = std::atoll(v.c_str());
    }
    return seen == 2 && pid > 1;
  }
  std::string Since() const
  {
    char buf[64] = "?";
    const std::time_t t = (std::time_t)time;
    if (const std::tm *tm = std::localtime(&t)) std::strftime(buf, sizeof(buf), "%Y-%m-%d %H:%M:%S", tm);
    return buf;
  }
};

enum class Liveness { Running, Gone, Unknown };

// Whether the owner's process still runs. Gone only when that is certain on
// this host: *why then says how it is known.
Liveness Check(const Owner &o, const Owner &me, std::string *why)
{
  if (o.host != me.host) return Liveness::Unknown;
  if (!o.boot.empty() && !me.boot.empty() && o.boot != me.boot) {
    *why = "this host has restarted since";
    return Liveness::Gone;
  }
  if (kill((pid_t)o.pid, 0) && errno == ESRCH) {
    *why = "it is no longer running";
    return Liveness::Gone;
  }
  char state = 0;
  unsigned long long start = 0;
  if (ProcStat(o.pid, &state, &start)) {
    if (state == 'Z' || state == 'X') {
      *why = "it has exited (a zombie not yet reaped)";
      return Liveness::Gone;
    }
    if (o.start && start != o.start) {
      *why = "it is no longer running (its process id now belongs to another process)";
      return Liveness::Gone;
    }
  }
  return Liveness::Running;
}

// Removes a stale lock whose line is `line`. Compare-and-remove under
// <lock>.takeover (itself created exclusively): no two runs can both remove
// a lock, and none removes a lock created after it judged the old one stale.
// Returns "" or the refusal.
std::string RemoveStale(const std::string &path, const std::string &lock, const std::string &line, const Owner &me)
{
  const std::string guard = lock + ".takeover";
  const int fd = open(guard.c_str(), O_WRONLY | O_CREAT | O_EXCL, 0644);
  if (fd < 0)
    return "-output " + path + ": its lock " + lock + " is stale and another run is taking it over right now (if none is, remove " + guard + "); try again";
  const std::string mine = me.Line() + "\n";
  const bool wrote = write(fd, mine.data(), mine.size()) == (ssize_t)mine.size();
  close(fd);
  if (wrote && FirstLine(lock) == line) unlink(lock.c_str());
  unlink(guard.c_str());
  return "";
}

// Rank 0: creates the lock, taking over a stale one. Returns "" or the one-line refusal; *note is set after a takeover.
std::string Claim(const std::string &path, const std::string &lock, const Owner &me, std::string *note)
{
  for (int attempt = 0; attempt < 4; attempt++) {
    const int fd = open(lock.c_str(), O_WRONLY | O_CREAT | O_EXCL, 0644);
    if (fd >= 0) {
      const std::string line = me.Line() + "\n";
      const bool wrote = write(fd, line.data(), line.size()) == (ssize_t)line.size();
      const int err = errno;
      close(fd);
      if (wrote) return "";
      unlink(lock.c_str());
      return "cannot write -output " + path + ": " + std::strerror(err);
    }
    if (errno != EEXIST) return "cannot write -output " + path + ": " + std::strerror(errno);
    // Held. An owner between its open and its write: its line within a second.
    Owner o;
    std::string line;
    bool gone = false;
    for (int i = 0; i < 50 && !o.Parse(line = FirstLine(lock)); i++) {
      if (access(lock.c_str(), F_OK)) {
        gone = true; // released meanwhile: try again
        break;
      }
      usleep(20000);
    }
    if (gone) continue;
    if (!o.Parse(line)) return "-output " + path + " is locked by " + lock + ", which names no nltopo run: if no run is writing " + path + ", remove " + lock;
    std::string why;
    switch (Check(o, me, &why)) {
    case Liveness::Running:
      return "-output " + path + " is being written by another run (process " + std::to_string(o.pid) + " on this host, since " + o.Since() +
             "): wait for it to end, or choose another -output";
    case Liveness::Unknown:
      return "-output " + path + " is being written by another run (process " + std::to_string(o.pid) + " on host " + o.host + ", since " + o.Since() +
             "): wait for it to end, or choose another -output; if that run is over (killed), remove " + lock;
    case Liveness::Gone: {
      const std::string err = RemoveStale(path, lock, line, me);
      if (!err.empty()) return err;
      *note = "took over its lock " + lock + " from process " + std::to_string(o.pid) + " (since " + o.Since() + "): " + why + " (killed?)";
      break;
    }
    }
  }
  return "-output " + path + ": cannot claim its lock " + lock + ": other runs keep taking it; try again";
}

} // namespace

std::vector<std::string> FilesNamed(const std::string &prefix)
{
  const size_t slash = prefix.find_last_of('/');
  const std::string dir = slash == std::string::npos ? "." : prefix.substr(0, slash + 1);
  const std::string head = slash == std::string::npos ? prefix : prefix.substr(slash + 1);
  std::vector<std::string> files;
  if (DIR *d = opendir(dir.c_str())) {
    while (dirent *e = readdir(d))
      if (!std::strncmp(e->d_name, head.c_str(), head.size())) files.push_back((slash == std::string::npos ? "" : dir) + e->d_name);
    closedir(d);
  }
  return files;
}

PetscErrorCode OutputClaim::Acquire(MPI_Comm comm, const std::string &path)
{
  PetscMPIInt rank;
  char msg[1024] = "";
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  if (!rank) {
    const Owner me = Owner::Me();
    const std::string lock = LockPath(path);
    std::string note;
    const std::string refusal = Claim(path, lock, me, &note);
    if (refusal.empty()) {
      path_ = path;
      lock_ = lock;
      owner_ = me.Line();
      RecordFound();
      // Only the holder writes temporaries: any left are a killed run's.
      std::string removed;
      std::vector<std::string> tmp = FilesNamed(path + ".tmp."), ptmp = FilesNamed(PartialPath(path) + ".tmp.");
      tmp.insert(tmp.end(), ptmp.begin(), ptmp.end());
      for (const std::string &f : tmp)
        if (!std::remove(f.c_str())) removed += (removed.empty() ? "" : ", ") + f;
      if (!removed.empty()) note += (note.empty() ? "removed " : "; removed its temporaries ") + removed + (note.empty() ? ", left by a killed run" : "");
      if (!note.empty()) {
        std::fprintf(stderr, "nltopo: warning: -output %s: %s\n", path.c_str(), note.c_str());
        std::fflush(stderr);
      }
    }
    PetscCall(PetscStrncpy(msg, refusal.c_str(), sizeof(msg)));
  }
  PetscCallMPI(MPI_Bcast(msg, sizeof(msg), MPI_CHAR, 0, comm));
  PetscCheck(!msg[0], comm, PETSC_ERR_FILE_OPEN, "%s", msg);
  PetscFunctionReturn(0);
}

static unsigned long Inode(const std::string &f)
{
  struct stat st;
  return stat(f.c_str(), &st) ? 0 : (unsigned long)st.st_ino;
}

void OutputClaim::RecordFound()
{
  if (lock_.empty()) return;
  partial_found_ = !access(PartialPath(path_).c_str(), F_OK);
  journals_found_.clear();
  for (const std::string &f : FilesNamed(path_ + ".journal.")) journals_found_.emplace_back(f, Inode(f));
}

void OutputClaim::Release(RunEnd end)
{
  if (lock_.empty()) return;
  const std::string partial = PartialPath(path_);
  std::vector<std::string> gone = FilesNamed(path_ + ".tmp."), more = FilesNamed(partial + ".tmp.");
  gone.insert(gone.end(), more.begin(), more.end());
  if (end == RunEnd::Complete || (end == RunEnd::Failed && !partial_found_)) gone.push_back(partial);
  if (end != RunEnd::Interrupted)
    for (const std::string &f : FilesNamed(path_ + ".journal.")) {
      bool found = false;
      for (const auto &j : journals_found_) found = found || (j.first == f && j.second == Inode(f));
      if (end == RunEnd::Complete || !found) gone.push_back(f); // (a journal recreated under a found name has another inode)
    }
  for (const std::string &f : gone) std::remove(f.c_str());
  if (FirstLine(lock_) == owner_) unlink(lock_.c_str()); // (never another run's)
  lock_.clear();
  owner_.clear();
}

} // namespace nltopo
