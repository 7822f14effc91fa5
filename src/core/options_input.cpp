#include "core/options_input.hpp"
#include "core/errors.hpp"
#include "core/text.hpp"
#include <cctype>
#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fcntl.h>
#include <map>
#include <strings.h>
#include <sys/stat.h>
#include <unistd.h>
#include <utility>

namespace nltopo {

namespace {

// -------------------------------------------------------------------------
// Small helpers

bool IsKey(const char *t)
{
  PetscBool key = PETSC_FALSE;
  if (t && PetscOptionsValidKey(t, &key)) return false;
  return key;
}
bool Is(const char *t, const char *name) { return t && !strcasecmp(t, name); } // PETSc matches these keys case-insensitively

// A word as the user can read it in one line: control and non-ASCII bytes as \xNN, at most 40 characters.
std::string Printable(const std::string &w)
{
  std::string o;
  for (unsigned char c : w) {
    if (o.size() >= 40) return o + "...";
    if (c < 0x20 || c >= 0x7f) {
      char hex[8];
      std::snprintf(hex, sizeof hex, "\\x%02X", c);
      o += hex;
    } else o += (char)c;
  }
  return o;
}

// Rank 0's string on every rank of comm.
void BcastString(MPI_Comm comm, std::string *s)
{
  int n = (int)s->size();
  MPI_Bcast(&n, 1, MPI_INT, 0, comm);
  s->resize(n);
  if (n) MPI_Bcast(&(*s)[0], n, MPI_CHAR, 0, comm);
}

// PETSc's tokens of a string (PetscToken: split at spaces, "..." one token
// without its quotes; consecutive spaces make no empty token, a leading one does).
std::vector<std::string> PetscTokens(const std::string &text)
{
  std::vector<std::string> out;
  PetscToken token;
  char *t = NULL;
  if (PetscTokenCreate(text.c_str(), ' ', &token)) return out;
  while (!PetscTokenFind(token, &t) && t) out.emplace_back(t);
  PetscTokenDestroy(&token);
  return out;
}

// -------------------------------------------------------------------------
// Files on a pipe: PETSc opens an options file twice (once to sniff for
// YAML, once to read it), so a pipe loses its first bytes; and the check
// below reads it once more. Rank 0 (the rank that reads command-line files)
// copies such a file once into a temporary regular file and reads that.

std::map<std::string, std::string> g_spooled; // temporary -> the name given

std::string Spool(const char *name, std::string *copy)
{
  const char *dir = std::getenv("TMPDIR");
  std::string path = std::string(dir && dir[0] ? dir : "/tmp") + "/nltopo-options-XXXXXX";
  std::vector<char> buf(path.begin(), path.end());
  buf.push_back(0);
  const int out = mkstemp(buf.data());
  if (out < 0) return std::string("cannot copy -options_file ") + name + " (a pipe) to a temporary file: " + std::strerror(errno);
  const int in = open(name, O_RDONLY);
  if (in < 0) {
    const std::string e = std::strerror(errno);
    close(out), unlink(buf.data());
    return std::string("cannot read -options_file ") + name + ": " + e;
  }
  char chunk[65536];
  ssize_t n;
  bool ok = true;
  while ((n = read(in, chunk, sizeof chunk)) > 0) ok = ok && write(out, chunk, (size_t)n) == n;
  ok = ok && n == 0;
  close(in);
  ok = close(out) == 0 && ok;
  if (!ok) {
    unlink(buf.data());
    return std::string("cannot copy -options_file ") + name + " (a pipe) to a temporary file";
  }
  *copy = buf.data();
  g_spooled[*copy] = name;
  return "";
}

// Rank 0: every -options_file of the command line that is not a regular file
// or a directory (a pipe, /dev/stdin) is replaced by its copy in argv.
std::string SpoolPipes(int argc, char **argv)
{
  static std::vector<std::string> copies; // argv points into them until the process ends
  copies.reserve(argc);
  for (int i = 1; i + 1 < argc; i++) {
    if (!Is(argv[i], "-options_file")) continue;
    struct stat st;
    if (stat(argv[i + 1], &st) || S_ISREG(st.st_mode) || S_ISDIR(st.st_mode)) continue; // PETSc's own reading says what is wrong
    std::string copy;
    const std::string e = Spool(argv[i + 1], &copy);
    if (!e.empty()) return e;
    copies.push_back(copy);
    argv[i + 1] = &copies.back()[0];
  }
  return "";
}

// A message with the temporary copies named as the user gave them.
std::string Unspooled(std::string m)
{
  for (const auto &s : g_spooled)
    for (size_t p; (p = m.find(s.first)) != std::string::npos;) m.replace(p, s.first.size(), s.second);
  return m;
}

// -------------------------------------------------------------------------
// Options files that include each other. PETSc reads a nested -options_file
// as it meets it, with no limit, so a -> b -> a recurses until the stack
// overflows. Before PETSc reads anything, rank 0 follows the include lines
// (a line whose first word is -options_file, in any case, split into words
// as PETSc does: '#' starts a comment, tabs are spaces, "..." is one word) of
// every file and refuses a missing or unreadable file, a directory, a cycle
// and a nesting deeper than kMaxDepth. The syntax itself is PETSc's reader's
// (CheckOptionsSources).

constexpr int kMaxDepth = 32;

struct Walk {
  std::vector<std::pair<dev_t, ino_t>> stack; // the files being read, outermost first
  std::vector<std::string> names;
  std::string error;
};

// PETSc's name of a file (PetscOptionsFilename): ${VARIABLES} replaced, then ~ and the separators fixed.
std::string PetscFileName(const std::string &given)
{
  char replaced[PETSC_MAX_PATH_LEN], fixed[PETSC_MAX_PATH_LEN];
  if (PetscStrreplace(PETSC_COMM_SELF, given.c_str(), replaced, sizeof replaced) || PetscFixFilename(replaced, fixed)) return given;
  return fixed;
}

bool Yaml(const std::string &f)
{
  auto ends = [&](const char *e) { return f.size() >= std::strlen(e) && !strcasecmp(f.c_str() + f.size() - std::strlen(e), e); };
  return ends(":yaml") || ends(".yaml") || ends(".yml") || ends(".json");
}

void WalkFile(Walk *w, const std::string &given, const std::string &from);

// The include lines of an open regular file.
void WalkLines(Walk *w, std::FILE *f, const std::string &name)
{
  char *line = NULL;
  size_t cap = 0;
  for (long no = 1; w->error.empty() && getline(&line, &cap, f) >= 0; no++) {
    std::string s = line;
    const size_t hash = s.find('#');
    if (hash != std::string::npos) s.resize(hash);
    for (char &c : s)
      if (c == '\t' || c == '\r' || c == '\n') c = ' ';
    std::vector<std::string> t = PetscTokens(s);
    if (!t.empty() && t[0].empty()) t.erase(t.begin()); // a line that begins with spaces
    if (t.empty() || !Is(t[0].c_str(), "-options_file")) continue;
    const std::string at = "options file " + name + " line " + std::to_string(no);
    if (t.size() < 2) w->error = at + ": -options_file needs a file name";
    else WalkFile(w, t[1], at);
  }
  std::free(line);
}

// from: where the file is named ("command line", "PETSC_OPTIONS", "options file a.opts line 3").
void WalkFile(Walk *w, const std::string &given, const std::string &from)
{
  std::string name = PetscFileName(given);
  const bool yaml = Yaml(name);
  if (name.size() > 5 && !strcasecmp(name.c_str() + name.size() - 5, ":yaml")) name.resize(name.size() - 5);
  // "cannot read -options_file a.opts: ...", "options file a.opts line 2: cannot read options file b.opts: ..."
  const bool argv = from == "command line";
  const std::string head = argv ? "" : from + ": ", shown = argv ? "-options_file " + given : "options file " + given;
  struct stat st;
  if (stat(name.c_str(), &st)) {
    w->error = head + "cannot read " + shown + ": " + std::strerror(errno);
    return;
  }
  if (S_ISDIR(st.st_mode)) {
    w->error = head + shown + " is a directory";
    return;
  }
  if (!S_ISREG(st.st_mode) && !argv) { // PETSc opens a file twice: a pipe it is not given a copy of loses its start
    w->error = head + shown + " is not a regular file (a pipe?): PETSc would lose its start; name a pipe on the command line, or save it to a file";
    return;
  }
  if (!S_ISREG(st.st_mode) || yaml) return; // a pipe on the command line was copied to a file; YAML files have no includes
  for (size_t k = 0; k < w->stack.size(); k++)
    if (w->stack[k] == std::make_pair(st.st_dev, st.st_ino)) {
      std::string chain;
      for (size_t j = k; j < w->names.size(); j++) chain += w->names[j] + " -> ";
      w->error = from + ": options files include each other (" + chain + given + "); PETSc would read them forever";
      return;
    }
  if ((int)w->stack.size() >= kMaxDepth) {
    w->error = from + ": options files nested deeper than " + std::to_string(kMaxDepth) + " (at " + given + ")";
    return;
  }
  std::FILE *f = std::fopen(name.c_str(), "r");
  if (!f) {
    w->error = head + "cannot read " + shown + ": " + std::strerror(errno);
    return;
  }
  w->stack.emplace_back(st.st_dev, st.st_ino);
  w->names.push_back(given);
  WalkLines(w, f, given);
  w->stack.pop_back();
  w->names.pop_back();
  std::fclose(f);
}

// The files the command line and PETSC_OPTIONS name, and the petscrc files PETSc reads.
std::string WalkIncludes(int argc, char **argv)
{
  Walk w;
  bool skip_rc = false;
  for (int i = 1; i < argc && w.error.empty(); i++) {
    skip_rc = skip_rc || Is(argv[i], "-skip_petscrc");
    if (Is(argv[i], "-options_file") && i + 1 < argc && argv[i + 1][0] != '-') WalkFile(&w, argv[++i], "command line");
  }
  if (const char *env = std::getenv("PETSC_OPTIONS")) {
    const std::vector<std::string> t = PetscTokens(env);
    for (size_t i = 0; i < t.size() && w.error.empty(); i++)
      if (Is(t[i].c_str(), "-options_file")) {
        if (i + 1 < t.size()) WalkFile(&w, t[++i], "PETSC_OPTIONS");
        else w.error = "PETSC_OPTIONS: -options_file needs a file name";
      }
  }
  if (!skip_rc && w.error.empty()) {
    char home[PETSC_MAX_PATH_LEN] = "";
    (void)PetscGetHomeDirectory(home, sizeof home);
    for (const std::string &rc : {std::string(home) + "/.petscrc", std::string(".petscrc"), std::string("petscrc")}) {
      struct stat st;
      if (w.error.empty() && home[0] && !stat(rc.c_str(), &st) && S_ISREG(st.st_mode)) WalkFile(&w, rc, "command line");
    }
  }
  return w.error;
}

// -------------------------------------------------------------------------
// PETSc's reader, on rank 0 alone, into a throw-away database: its first
// error is kept (not printed) and made one line.

std::string g_petsc_error;

PetscErrorCode KeepFirstError(MPI_Comm, int, const char *, const char *, PetscErrorCode n, PetscErrorType p, const char *mess, void *)
{
  if (p == PETSC_ERROR_INITIAL && g_petsc_error.empty()) g_petsc_error = mess && mess[0] ? mess : "error";
  return n;
}

// "Error in options file F line 3: extra token x" -> {"options file F line 3", "extra token x"}.
bool SplitFileLine(const std::string &m, const char *head, std::string *where, std::string *detail)
{
  if (m.compare(0, std::strlen(head), head)) return false;
  const std::string rest = m.substr(std::strlen(head));
  for (size_t p = rest.find(" line "); p != std::string::npos; p = rest.find(" line ", p + 1)) {
    size_t d = p + 6;
    while (d < rest.size() && std::isdigit((unsigned char)rest[d])) d++;
    if (d > p + 6 && !rest.compare(d, 2, ": ")) {
      *where = "options file " + rest.substr(0, d);
      *detail = rest.substr(d + 2);
      return true;
    }
  }
  return false;
}

// PETSc 3.18's messages of its options reader, as nltopo's lines.
std::string OneLine(const std::string &m)
{
  std::string where, d;
  if (SplitFileLine(m, "Unknown first token in options file ", &where, &d)) {
    if (!d.compare(0, 3, "\xEF\xBB\xBF")) return where + ": the file starts with a UTF-8 byte-order mark; save it without one";
    return where + ": '" + Printable(d) + "' is not an option (a line is -name [value], or a # comment)";
  }
  if (SplitFileLine(m, "Error in options file ", &where, &d)) {
    if (StartsWith(d, "extra token ")) {
      const std::string tok = d.substr(std::strlen("extra token "));
      if (IsKey(tok.c_str())) return where + ": two options on one line (" + tok + " after a value); put each on its own line";
      return where + ": '" + Printable(tok) + "' after the value" +
             (tok[0] == '!' ? " (comments start with #)" : " (a value with spaces is quoted, -name \"a b\"; one option per line)");
    }
    const char *two = "cannot specify two options per line ";
    if (StartsWith(d, two)) return where + ": two options on one line " + d.substr(std::strlen(two)) + "; put each on its own line";
    if (StartsWith(d, "invalid option ")) return where + ": '" + Printable(d.substr(std::strlen("invalid option "))) + "' is not an option name";
    return where + ": " + Printable(d);
  }
  if (StartsWith(m, "Unable to open options file")) return "cannot read options file" + m.substr(std::strlen("Unable to open options file"));
  if (StartsWith(m, "Specified options file ")) return "options file " + m.substr(std::strlen("Specified options file "));
  if (m.find("Missing filename for -options_file") != std::string::npos) return "-options_file needs a file name";
  if (m.find("Missing prefix for -prefix_push") != std::string::npos) return "-prefix_push needs a prefix (a word without a leading -)";
  std::string one;
  for (char c : m) one += c == '\n' ? ' ' : c;
  return "reading the options: " + one;
}

// Any spelling of -lattice_gamma with an upper-case letter: the same option
// in PETSc's case-insensitive database, and not the cubic coefficient.
bool GammaTrap(const char *name) { return !strcasecmp(name, "lattice_gamma") && std::strcmp(name, "lattice_gamma"); }

// Sees every option as it is set, with the name as written (the database
// keeps the first spelling of a name: -lattice_gamma from a file, then
// -lattice_Gamma on the command line, is stored as lattice_gamma).
PetscErrorCode GammaMonitor(const char name[], const char[], void *ctx)
{
  auto *found = static_cast<std::string *>(ctx);
  const char *n = name[0] == '-' ? name + 1 : name;
  if (found->empty() && GammaTrap(n)) *found = n;
  return 0;
}

// Rank 0: PETSc reads argv, PETSC_OPTIONS, the petscrc files and every file
// they name into a throw-away database, as PetscInitialize will.
std::string PetscReads(int argc, char **argv)
{
  PetscOptions db;
  std::string line;
  std::vector<char *> args; // without the options monitor, which would print every option twice
  for (int i = 0; i < argc; i++)
    if (!Is(argv[i], "-options_monitor") && !Is(argv[i], "-options_monitor_cancel")) args.push_back(argv[i]);
  int n = (int)args.size();
  char **a = args.data();
  if (PetscOptionsCreate(&db)) return "cannot create an options database";
  const MPI_Comm world = PETSC_COMM_WORLD;
  PETSC_COMM_WORLD = PETSC_COMM_SELF; // PetscOptionsInsert reads files on "rank 0 of the world": this rank, alone
  g_petsc_error.clear();
  std::string trap;
  if (!PetscOptionsPush(db)) { // the monitor is set on the default database
    PetscOptionsMonitorSet(GammaMonitor, &trap, NULL);
    PetscOptionsPop();
  }
  PetscPushErrorHandler(KeepFirstError, NULL);
  const PetscErrorCode ierr = PetscOptionsInsert(db, &n, &a, NULL);
  PetscPopErrorHandler();
  PETSC_COMM_WORLD = world;
  if (ierr) line = OneLine(g_petsc_error);
  else if (!trap.empty())
    line = "-" + trap + " is the same option as -lattice_gamma (PETSc option names are case-insensitive); set the cubic coefficient with -lattice_cubic";
  else {
    PetscInt k;
    char **names, **values;
    if (!PetscOptionsLeftGet(db, &k, &names, &values)) {
      for (PetscInt i = 0; i < k && line.empty(); i++)
        if (GammaTrap(names[i]))
          line = "-" + std::string(names[i]) +
                 " is the same option as -lattice_gamma (PETSc option names are case-insensitive); set the cubic coefficient with -lattice_cubic";
      PetscOptionsLeftRestore(db, &k, &names, &values);
    }
  }
  PetscOptionsDestroy(&db);
  return line;
}

std::string StrayLine(const std::string &where, const std::string &word, const std::string &after, const char *hint)
{
  std::string l = where + ": '" + Printable(word) + "' is neither an option nor an option's value";
  l += after.empty() ? " (before any option)" : " (after " + after + ")";
  if (word.size() > 5 && word.compare(word.size() - 5, 5, ".opts") == 0) return l + "; did you mean -options_file " + word + "?";
  return l + "; " + hint;
}

} // namespace

// PetscOptionsInsertArgs: a key takes the next word as its value unless that
// word is a key too; -options_file and -prefix_push take the next word; any
// other word is skipped silently. Here it is an error.
std::string StrayArgument(const std::vector<std::string> &args)
{
  std::string after;
  for (size_t i = 0; i < args.size();) {
    const char *t = args[i].c_str();
    if (!IsKey(t)) return StrayLine("command line", args[i], after, "write a list without spaces (0.1,1) and quote a value with spaces");
    const bool takes_word = Is(t, "-options_file") || Is(t, "-options_file_yaml") || Is(t, "-options_string_yaml") || Is(t, "-prefix_push");
    if (takes_word && (i + 1 == args.size() || args[i + 1][0] == '-')) // PETSc refuses it too, with a traceback
      return args[i] + (Is(t, "-prefix_push") ? " needs a prefix (a word without a leading -)" : " needs a file name");
    if (takes_word || (!Is(t, "-prefix_pop") && i + 1 < args.size() && !IsKey(args[i + 1].c_str()))) {
      after = args[i] + (i + 1 < args.size() ? " " + args[i + 1] : std::string());
      i += 2;
    } else {
      after = args[i];
      i += 1;
    }
  }
  return "";
}

// PetscOptionsInsertString: the same rule over PETSc's words of the string.
std::string StrayInOptionsString(const std::string &text, const char *where)
{
  const std::vector<std::string> t = PetscTokens(text);
  std::string after;
  for (size_t i = 0; i < t.size();) {
    const char *w = t[i].c_str();
    if (t[i].empty()) { // a leading space
      i++;
      continue;
    }
    if (!IsKey(w))
      return StrayLine(where, t[i], after, "PETSc splits it at spaces (a backslash does not escape one); quote a value with spaces in double quotes");
    const bool takes_word = Is(w, "-options_file") || Is(w, "-options_file_yaml") || Is(w, "-options_string_yaml") || Is(w, "-prefix_push");
    if (takes_word || (!Is(w, "-prefix_pop") && i + 1 < t.size() && !IsKey(t[i + 1].c_str()))) {
      after = t[i] + (i + 1 < t.size() ? " " + t[i + 1] : std::string());
      i += 2;
    } else {
      after = t[i];
      i += 1;
    }
  }
  return "";
}

std::string CheckOptionsSources(MPI_Comm comm, int argc, char **argv)
{
  int rank = 0;
  std::string line;
  MPI_Comm_rank(comm, &rank);
  if (!rank) {
    line = StrayArgument(std::vector<std::string>(argv + 1, argv + argc));
    if (line.empty())
      if (const char *env = std::getenv("PETSC_OPTIONS")) line = StrayInOptionsString(env, "PETSC_OPTIONS");
    if (line.empty()) line = WalkIncludes(argc, argv);
    if (line.empty()) line = PetscReads(argc, argv);
    line = Unspooled(line);
  }
  BcastString(comm, &line);
  return line;
}

std::string ArgumentsDifferAcrossRanks(MPI_Comm comm, int argc, char **argv)
{
  int rank, size, first, who;
  std::string mine, zero;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &size);
  for (int i = 1; i < argc; i++) mine += std::string(argv[i]) + '\0';
  zero = mine;
  BcastString(comm, &zero);
  first = mine == zero ? size : rank;
  MPI_Allreduce(&first, &who, 1, MPI_INT, MPI_MIN, comm);
  if (who == size) return "";
  std::string line;
  if (rank == who) {
    auto words = [](const std::string &s) {
      std::vector<std::string> v;
      for (size_t p = 0, e; p < s.size(); p = e + 1) v.push_back(s.substr(p, (e = s.find('\0', p)) - p));
      return v;
    };
    const std::vector<std::string> a = words(zero), b = words(mine);
    size_t k = 0;
    while (k < a.size() && k < b.size() && a[k] == b[k]) k++;
    auto from = [](const std::vector<std::string> &v, size_t k) {
      std::string s;
      for (size_t j = k; j < v.size() && j < k + 3; j++) s += (s.empty() ? "" : " ") + Printable(v[j]);
      return s.empty() ? std::string("nothing") : "'" + s + (k + 3 < v.size() ? " ...'" : "'");
    };
    line = "rank " + std::to_string(who) + " was started with other options than rank 0 (after argument " + std::to_string(k) + ", rank " +
           std::to_string(who) + " has " + from(b, k) + ", rank 0 " + from(a, k) + "); every rank must be given the same command line";
  }
  int n = (int)line.size();
  MPI_Bcast(&n, 1, MPI_INT, who, comm);
  line.resize(n);
  if (n) MPI_Bcast(&line[0], n, MPI_CHAR, who, comm);
  return line;
}

bool PreflightArguments(int argc, char **argv)
{
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  std::string line = ArgumentsDifferAcrossRanks(MPI_COMM_WORLD, argc, argv); // before anything reads a file collectively
  if (line.empty()) {
    if (!rank) line = SpoolPipes(argc, argv);
    BcastString(MPI_COMM_WORLD, &line);
  }
  if (line.empty()) {
    // PETSc started for the check alone: no argument, no PETSC_OPTIONS, no
    // petscrc (what it reads then cannot fail), and finalized after it.
    const char *env = std::getenv("PETSC_OPTIONS"), *yaml = std::getenv("PETSC_OPTIONS_YAML");
    const std::string saved = env ? env : "", saved_yaml = yaml ? yaml : "";
    unsetenv("PETSC_OPTIONS");
    unsetenv("PETSC_OPTIONS_YAML");
    static char skip[] = "-skip_petscrc";
    static char *check_args[3] = {nullptr, skip, nullptr};
    check_args[0] = argv[0];
    int check_argc = 2;
    char **check_argv = check_args;
    const PetscErrorCode started = PetscInitializeNoPointers(check_argc, check_argv, NULL, NULL);
    if (env) setenv("PETSC_OPTIONS", saved.c_str(), 1);
    if (yaml) setenv("PETSC_OPTIONS_YAML", saved_yaml.c_str(), 1);
    if (started) line = "PETSc could not start";
    else {
      line = CheckOptionsSources(PETSC_COMM_WORLD, argc, argv);
      if (PetscFinalize() && line.empty()) line = "PETSc could not finish the options check";
    }
  }
  if (line.empty()) return true;
  if (!rank) std::fprintf(stderr, "nltopo: error: %s\n", line.c_str());
  RemoveSpooledOptionsFiles();
  return false;
}

void RemoveSpooledOptionsFiles()
{
  for (const auto &s : g_spooled) unlink(s.first.c_str());
  g_spooled.clear();
}

PetscErrorCode CheckOptionsAgree(MPI_Comm comm)
{
  char *all = NULL;
  std::string mine, zero, line;
  uint64_t hash = 1469598103934665603ull, lo, hi; // FNV-1a of the whole database, names and values in order
  PetscFunctionBeginUser;
  PetscCall(PetscOptionsGetAll(NULL, &all));
  mine = all ? all : "";
  PetscCall(PetscFree(all));
  for (unsigned char c : mine) hash = (hash ^ c) * 1099511628211ull;
  PetscCallMPI(MPI_Allreduce(&hash, &lo, 1, MPI_UINT64_T, MPI_MIN, comm));
  PetscCallMPI(MPI_Allreduce(&hash, &hi, 1, MPI_UINT64_T, MPI_MAX, comm));
  if (lo == hi) PetscFunctionReturn(0);
  zero = mine; // they differ: rank 0's whole database, to name the first difference
  BcastString(comm, &zero);
  if (mine != zero) {
    // The first option that differs, as "-name value" on both ranks.
    const std::vector<std::string> a = PetscTokens(zero), b = PetscTokens(mine);
    size_t k = 0;
    while (k < a.size() && k < b.size() && a[k] == b[k]) k++;
    auto option = [](const std::vector<std::string> &v, size_t k) {
      if (k >= v.size()) return std::string("nothing");
      size_t s = k;
      while (s > 0 && !IsKey(v[s].c_str())) s--;
      return "'" + v[s] + (s + 1 < v.size() && !IsKey(v[s + 1].c_str()) ? " " + v[s + 1] : std::string()) + "'";
    };
    PetscMPIInt rank;
    PetscCallMPI(MPI_Comm_rank(comm, &rank));
    line = "the options differ between ranks: rank " + std::to_string(rank) + " has " + option(b, k) + ", rank 0 " + option(a, k) +
           "; every rank must be given the same options";
  }
  PetscCall(FailTogether(comm, line.empty() ? 0 : PETSC_ERR_USER, line.c_str()));
  PetscFunctionReturn(0);
}

} // namespace nltopo
