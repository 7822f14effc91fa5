#include "core/errors.hpp"
#include "core/option_table.hpp"
#include <cctype>
#include <cstdio>
#include <string>
#include <vector>
#include <cstdlib>
#include <cerrno>
#include <cstring>
#include <strings.h>
#include <unistd.h>

namespace nltopo {

static std::string g_output_path;

void SetOutputContext(const char *path) { g_output_path = path ? path : ""; }

// The option (-name value) whose value is the word w (case-insensitive), "" if none or several.
// The option given with value w ("-name w"). Where several hold w, those of
// the type that failed to parse (a table's type: wanted), else all of them
// ("-a 2 or -b 2"); "" when none does.
static std::string OptionWithValue(const std::string &w, std::initializer_list<OptionType> wanted = {})
{
  char *all = NULL;
  if (w.empty() || PetscOptionsGetAll(NULL, &all) || !all) return "";
  std::vector<std::string> tok, hits, typed;
  for (char *t = std::strtok(all, " "); t; t = std::strtok(NULL, " ")) tok.emplace_back(t);
  PetscFree(all);
  for (size_t i = 0; i + 1 < tok.size(); i++)
    if (tok[i][0] == '-' && std::isalpha((unsigned char)tok[i][1]) && !strcasecmp(tok[i + 1].c_str(), w.c_str())) {
      hits.push_back(tok[i] + " " + tok[i + 1]);
      const OptionInfo *row = FindOption(tok[i]);
      for (OptionType t : wanted)
        if (row && row->type == t) typed.push_back(hits.back());
    }
  const std::vector<std::string> &pick = hits.size() > 1 && !typed.empty() ? typed : hits;
  std::string out;
  for (const std::string &h : pick) out += (out.empty() ? "" : " or ") + h;
  return out;
}

// A word of the message after the marker, e.g. "Input string abc has ..." -> "abc".
static std::string WordAfter(const char *mess, const char *marker)
{
  const char *p = mess ? std::strstr(mess, marker) : NULL;
  if (!p) return "";
  p += std::strlen(marker);
  while (*p == ' ') p++;
  const char *e = p;
  while (*e && *e != ' ' && *e != '\n') e++;
  return std::string(p, e);
}
static bool interrupt_reported = false;

bool InterruptReported() { return interrupt_reported; }

PetscErrorCode OneLineErrorHandler(MPI_Comm comm, int line, const char *fun, const char *file, PetscErrorCode n, PetscErrorType p, const char *mess, void *ctx)
{
  if (p != PETSC_ERROR_INITIAL) return n;
  int rank = 0, size = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &size);
  if (rank) return n;       // collective errors print once
  if (n == PETSC_ERR_SIG) { // a stop signal (core/signals.hpp): silent on the way out, then the study's one line
    if (mess && mess[0] && mess[0] != ' ') {
      std::fprintf(stderr, "nltopo: %s\n", mess);
      std::fflush(stderr);
      interrupt_reported = true;
    }
    return n;
  }
  if (fun && !std::strncmp(fun, "PetscOptions", 12)) { // an option error is raised on every rank alike (often on PETSC_COMM_SELF): print once
    int world_rank = 0;
    MPI_Comm_rank(PETSC_COMM_WORLD, &world_rank);
    if (world_rank) return n;
  }
  const char *text = NULL;
  PetscErrorMessage(n, &text, NULL);
  const bool user = n == PETSC_ERR_USER || n == PETSC_ERR_FILE_OPEN || n == PETSC_ERR_FILE_READ || n == PETSC_ERR_FILE_WRITE || n == PETSC_ERR_FP ||
                    n == PETSC_ERR_NOT_CONVERGED;
  // A value PETSc cannot parse: name the option that holds it (its messages name only the value).
  static const struct {
    const char *fun, *marker, *what;
    std::initializer_list<OptionType> types; // the tables' types whose values this parser reads
  } parse[] = {{"PetscOptionsStringToReal", "Input string", "not a real number", {OptionType::Real, OptionType::RealList}},
               {"PetscOptionsStringToScalar", "Input string", "not a number", {OptionType::Real, OptionType::RealList}},
               {"PetscOptionsStringToInt", "Input string", "not an integer", {OptionType::Int}},
               {"PetscOptionsStringToBool", "Unknown logical value:", "not a boolean (true/false, yes/no, 1/0)", {OptionType::Bool}}};
  for (const auto &q : parse)
    if (fun && !std::strcmp(fun, q.fun)) {
      const std::string v = WordAfter(mess, q.marker), opt = OptionWithValue(v, q.types);
      std::fprintf(stderr, "nltopo: error: %s: %s\n", opt.empty() ? ("'" + v + "'").c_str() : opt.c_str(), q.what);
      std::fflush(stderr);
      return n;
    }
  if (n == PETSC_ERR_LIB && mess && std::strstr(mess, "HDF5") && !g_output_path.empty())
    std::fprintf(stderr, "nltopo: error: cannot write -output %s: %s (disk full, over quota, or the file or its directory removed?)\n", g_output_path.c_str(),
                 mess);
  else if (user) std::fprintf(stderr, "nltopo: error: %s\n", mess && mess[0] ? mess : text);
  else {
    // PETSc's own message, without its source location; when it quotes a
    // value the user gave (an unknown type name), name that option too.
    std::string opt, m = mess ? mess : "";
    for (size_t i = 0; i < m.size() && opt.empty();) {
      while (i < m.size() && !std::isalnum((unsigned char)m[i])) i++;
      size_t j = i;
      while (j < m.size() && (std::isalnum((unsigned char)m[j]) || m[j] == '_' || m[j] == '.')) j++;
      const std::string w = m.substr(i, j - i);
      if (w.size() >= 2 && !std::isdigit((unsigned char)w[0])) opt = OptionWithValue(w);
      i = j;
    }
    int world_rank = 0;
    MPI_Comm_rank(PETSC_COMM_WORLD, &world_rank);
    if (!opt.empty() && world_rank) return n; // a bad option value fails alike on every rank: print once
    std::fprintf(stderr, "nltopo: error: %s%s%s: %s\n", opt.empty() ? "" : opt.c_str(), opt.empty() ? "" : ": ", text ? text : "PETSc error", m.c_str());
  }
  std::fflush(stderr);
  return n;
}

PetscErrorCode RejectGivenOptions(MPI_Comm comm, std::initializer_list<const char *> names, const char *set_by)
{
  PetscFunctionBeginUser;
  for (const char *name : names) {
    PetscBool set;
    PetscCall(PetscOptionsHasName(NULL, NULL, name, &set));
    PetscCheck(!set, comm, PETSC_ERR_USER, "%s is set by %s; remove it", name, set_by);
  }
  PetscFunctionReturn(0);
}

PetscErrorCode FailTogether(MPI_Comm comm, PetscErrorCode code, const char *msg)
{
  PetscMPIInt rank, size, first, who;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCallMPI(MPI_Comm_size(comm, &size));
  first = code ? rank : size;
  PetscCallMPI(MPI_Allreduce(&first, &who, 1, MPI_INT, MPI_MIN, comm));
  if (who == size) PetscFunctionReturn(0);
  int c = (int)code;
  char buf[1024] = "";
  if (rank == who) PetscCall(PetscStrncpy(buf, msg ? msg : "", sizeof(buf)));
  PetscCallMPI(MPI_Bcast(&c, 1, MPI_INT, who, comm));
  PetscCallMPI(MPI_Bcast(buf, sizeof(buf), MPI_CHAR, who, comm));
  SETERRQ(comm, (PetscErrorCode)c, "%s", buf);
}

} // namespace nltopo
