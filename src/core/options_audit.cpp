#include "core/options_audit.hpp"
#include "core/option_help.hpp"
#include "core/effective_options.hpp"
#include "core/option_table.hpp"
#include "core/ts_traits.hpp"
#include "core/text.hpp"
#include <petscts.h>
#include <slepceps.h>
#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <vector>

namespace nltopo {

namespace {
// The capture RunStudyFromOptions holds while the running study declares its solvers.
std::vector<std::string> *g_solver_capture = nullptr;

// The option classes of the objects a solver of each kind creates under its
// prefix: a TS its SNES, KSP and PC (and their matrices' -mat_*), an SNES its
// nonlinear preconditioner, KSP and PC, an EPS its ST (with the ST's own KSP,
// -<prefix>st_ksp_*), BV, DS, RG and FN.
void CaptureSolverPrefix(const char *prefix, std::initializer_list<const char *> classes)
{
  if (!g_solver_capture) return;
  for (const char *c : classes) {
    const std::string p = std::string(prefix) + c;
    if (std::find(g_solver_capture->begin(), g_solver_capture->end(), p) == g_solver_capture->end()) g_solver_capture->push_back(p);
  }
}
} // namespace

SolverPrefixCapture::SolverPrefixCapture() { g_solver_capture = &prefixes_; }
SolverPrefixCapture::~SolverPrefixCapture() { g_solver_capture = nullptr; }

// A throw-away object of a solver class, configured from the database.
template <typename T, PetscErrorCode (*Create)(MPI_Comm, T *), PetscErrorCode (*Prefix)(T, const char[]), PetscErrorCode (*FromOptions)(T),
          PetscErrorCode (*Destroy)(T *)>
static PetscErrorCode Declare(MPI_Comm comm, const char *prefix)
{
  T obj;
  PetscFunctionBeginUser;
  PetscCall(Create(comm, &obj));
  PetscCall(Prefix(obj, prefix));
  PetscCall(FromOptions(obj));
  PetscCall(Destroy(&obj));
  PetscFunctionReturn(0);
}

PetscErrorCode DeclareTS(MPI_Comm comm, const char *prefix)
{
  char type[64] = "";
  PetscBool set;
  PetscFunctionBeginUser;
  CaptureSolverPrefix(prefix, {"ts_", "snes_", "ksp_", "pc_", "mat_"});
  PetscCall(Declare<TS, TSCreate, TSSetOptionsPrefix, TSSetFromOptions, TSDestroy>(comm, prefix));
  // the provenance's effective type: given, or the code's default for this prefix (a default that changes is then caught on resume)
  PetscCall(PetscOptionsGetString(NULL, prefix, "-ts_type", type, sizeof(type), &set));
  if (!set && TSDefaultType(prefix)) PetscCall(PetscStrncpy(type, TSDefaultType(prefix), sizeof(type)));
  if (type[0]) NoteEffectiveOption(std::string("-") + prefix + "ts_type", type);
  NoteSolverPrefix((std::string(prefix) + "ts_").c_str(), (std::string("TS, type ") + (type[0] ? type : "PETSc's default")).c_str());
  PetscFunctionReturn(0);
}
PetscErrorCode DeclareSNES(MPI_Comm comm, const char *prefix)
{
  CaptureSolverPrefix(prefix, {"snes_", "npc_", "ksp_", "pc_", "mat_"});
  NoteSolverPrefix((std::string(prefix) + "snes_").c_str(), "SNES; its KSP and PC: -" + std::string(prefix) + "ksp_*, -" + std::string(prefix) + "pc_*");
  return Declare<SNES, SNESCreate, SNESSetOptionsPrefix, SNESSetFromOptions, SNESDestroy>(comm, prefix);
}
PetscErrorCode DeclareEPS(MPI_Comm comm, const char *prefix)
{
  CaptureSolverPrefix(prefix, {"eps_", "st_", "bv_", "ds_", "rg_", "fn_"});
  NoteSolverPrefix((std::string(prefix) + "eps_").c_str(), "SLEPc EPS");
  return Declare<EPS, EPSCreate, EPSSetOptionsPrefix, EPSSetFromOptions, EPSDestroy>(comm, prefix);
}

namespace {

struct Unused {
  std::vector<std::string> names, values; // names without the leading '-'
  std::vector<bool> has_value;            // a flag has none ("" is a value)
};

PetscErrorCode UnusedOptions(Unused *u)
{
  PetscInt n;
  char **names, **values;
  PetscFunctionBeginUser;
  PetscCall(PetscOptionsLeftGet(NULL, &n, &names, &values));
  for (PetscInt i = 0; i < n; i++) {
    u->names.emplace_back(names[i]);
    u->values.emplace_back(values[i] ? values[i] : "");
    u->has_value.push_back(values[i] != NULL);
  }
  PetscCall(PetscOptionsLeftRestore(NULL, &n, &names, &values));
  PetscFunctionReturn(0);
}

// PETSc compares option names case-insensitively (strcasecmp): so does every check here.
std::string Lower(std::string s)
{
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return (char)std::tolower(c); });
  return s;
}

// nltopo's own option blocks (complete in every options function) as opposed
// to the options of solver objects with these prefixes (-sim_ts_*, -nnm_snes_*, ...).
// n: lower case, without the dash.
bool OwnComponent(const std::string &n)
{
  static const char *solver_prefixes[] = {"sim_", "nnm_start_", "nnm_", "linear_", "floquet_mf_", "floquet_"};
  static const char *classes[] = {"ts_", "snes_", "npc_", "ksp_", "pc_", "eps_", "st_", "bv_", "ds_", "rg_", "fn_", "mat_", "dm_", "tao_", "sf_"};
  bool own = StartsWith(n, "study") || StartsWith(n, "output");
  for (const std::string &p : ComponentPrefixes()) own = own || StartsWith(n, p.c_str() + 1); // the registered prefixes carry the dash
  if (!own) return false;
  for (const char *p : solver_prefixes)
    if (StartsWith(n, p))
      for (const char *c : classes)
        if (n.compare(std::strlen(p), std::strlen(c), c) == 0) return false;
  return true;
}

// An option of one TS type's own block (-<prefix>ts_<family>_*) while the
// prefix runs a TS of another family: unused whatever happens later, so it can
// be refused before any work (PETSc reads a type's block only for that type).
// Sets *line when n is such an option. The families and the type each prefix
// runs by default come from the integrator table (core/ts_traits.hpp).
void TypeMismatch(const std::string &n, std::string *line)
{
  static const char *ts_prefixes[] = {"sim_", "nnm_"};
  for (const char *p : ts_prefixes) {
    const std::string head = std::string(p) + "ts_";
    if (!StartsWith(n, head.c_str())) continue;
    std::string option_family; // the longest family whose block n is in
    for (size_t i = 0; i < TSTraitsCount(); i++) {
      const char *f = TSTraitsAt(i).family;
      if (f && std::strlen(f) > option_family.size() && StartsWith(n, (head + f + "_").c_str())) option_family = f;
    }
    if (option_family.empty()) return;
    char type[64];
    PetscBool set = PETSC_FALSE;
    if (PetscStrncpy(type, TSDefaultType(p), sizeof(type))) return;
    if (PetscOptionsGetString(NULL, NULL, ("-" + head + "type").c_str(), type, sizeof(type), &set)) return;
    const TSTraits *selected = TSTraitsFind(type);
    if (!selected || (selected->family && option_family == selected->family)) return; // a type of nltopo's table only
    *line = ": not used by this run (-" + head + "type is " + type + (set ? "" : ", the default") + "; the option belongs to -" + head + "type " +
            option_family + ")";
    return;
  }
}

std::string *g_capture = nullptr;

PetscErrorCode CapturePrintf(MPI_Comm, const char format[], ...)
{
  char buf[2048];
  va_list ap;
  va_start(ap, format);
  std::vsnprintf(buf, sizeof(buf), format, ap);
  va_end(ap);
  if (g_capture) g_capture->append(buf);
  return 0;
}

// Solver objects print their type lists with PetscFPrintf(comm, stdout, ...).
PetscErrorCode (*g_saved_vfprintf)(FILE *, const char[], va_list) = nullptr;

PetscErrorCode CaptureVFPrintf(FILE *fd, const char format[], va_list ap)
{
  if (fd != stdout || !g_capture) return g_saved_vfprintf(fd, format, ap);
  char buf[4096];
  std::vsnprintf(buf, sizeof(buf), format, ap);
  g_capture->append(buf);
  return 0;
}

// "  -name <...>: help" lines of PETSc's -help output. The text after the name
// tells the kind: "-x: <TRUE : TRUE>" a flag, "-x <now 25 : formerly 25>" an
// integer (a real prints "<1. : 1.>", a string or list "<now abc : ...>").
void ParseHelp(const std::string &text, std::set<std::string> *names, std::map<std::string, OptionKind> *kinds)
{
  size_t pos = 0;
  while (pos < text.size()) {
    size_t end = text.find('\n', pos);
    if (end == std::string::npos) end = text.size();
    size_t i = pos;
    while (i < end && text[i] == ' ') i++;
    if (i > pos && i + 1 < end && text[i] == '-' && std::isalpha((unsigned char)text[i + 1])) {
      size_t j = i + 1;
      while (j < end && (std::isalnum((unsigned char)text[j]) || text[j] == '_')) j++;
      if (j == end || text[j] == ' ' || text[j] == '<' || text[j] == ':') {
        std::string n = text.substr(i + 1, j - i - 1);
        std::transform(n.begin(), n.end(), n.begin(), [](unsigned char c) { return (char)std::tolower(c); });
        names->insert(n);
        if (kinds) {
          const std::string rest = text.substr(j, end - j);
          OptionKind k = OptionKind::Other;
          if (!rest.compare(0, 7, ": <TRUE") || !rest.compare(0, 8, ": <FALSE")) k = OptionKind::Flag;
          else if (!rest.compare(0, 6, " <now ")) {
            size_t d = 6;
            if (d < rest.size() && rest[d] == '-') d++;
            const size_t digits = d;
            while (d < rest.size() && std::isdigit((unsigned char)rest[d])) d++;
            if (d > digits && !rest.compare(d, 11, " : formerly")) k = OptionKind::Integer;
          }
          kinds->emplace(n, k);
        }
      }
    }
    pos = end + 1;
  }
}

size_t EditDistance(const std::string &a, const std::string &b)
{
  const size_t n = a.size(), m = b.size();
  std::vector<std::vector<size_t>> d(n + 1, std::vector<size_t>(m + 1));
  for (size_t i = 0; i <= n; i++) d[i][0] = i;
  for (size_t j = 0; j <= m; j++) d[0][j] = j;
  for (size_t i = 1; i <= n; i++)
    for (size_t j = 1; j <= m; j++) {
      const size_t cost = a[i - 1] == b[j - 1] ? 0 : 1;
      d[i][j] = std::min({d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + cost});
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1]) d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1); // transposition
    }
  return d[n][m];
}

} // namespace

// PETSc 3.18's and SLEPc's own options: read by PetscInitialize, PetscFinalize
// and the library itself, never by an object nltopo configures (the
// PetscInitialize and PetscFinalize manual pages, and the option names the
// library reads). -options_file, -options_file_yaml, -options_string_yaml,
// -prefix_push and -prefix_pop never reach the database.
bool PetscGlobalOption(const std::string &name)
{
  static const std::set<std::string> exact = {
      "help", "version", "info", "info_exclude", "history", "citations",
      // logging (-log_view and its companions)
      "log", "log_all", "log_exclude", "log_exclude_actions", "log_exclude_objects", "log_summary", "log_sync", "log_threshold", "log_trace", "log_view",
      "log_view_gpu_time", "log_view_memory", "log_mpe", "log_perfstubs",
      // memory
      "malloc", "malloc_coalesce", "malloc_debug", "malloc_dump", "malloc_hbw", "malloc_info", "malloc_requested_size", "malloc_test", "malloc_view",
      "malloc_view_threshold", "memory_view", "objects_dump", "get_total_flops",
      // the options database
      "options_left", "options_view", "options_monitor", "options_monitor_cancel", "options_suppress_deprecated_warnings", "skip_petscrc",
      // errors, signals, debuggers
      "on_error_abort", "on_error_attach_debugger", "on_error_emacs", "on_error_mpiabort", "mpi_return_on_error", "start_in_debugger",
      "stop_for_debugger", "debugger_nodes", "debugger_ranks", "debugger_pause", "no_signal_handler", "fp_trap", "check_pointer_intensity",
      "checkfunctionlist", "error_output_none", "error_output_stdout", "mpidump", "petsc_sleep", "petsc_ci", "petsc_ci_portable_error_output",
      // MPI, devices, graphics, bindings
      "use_gpu_aware_mpi", "mpi_linear_solver_server", "mpi_linear_solver_server_view", "nox", "nox_warning", "x_virtual", "display", "python",
      "library_preload"};
  static const char *families[] = {"saws", "device", "viewer", "draw"}; // -saws_*, -device_*, -viewer_*, -draw_*
  const std::string n = Lower(name);
  if (exact.count(n)) return true;
  for (const char *f : families)
    if (n == f || StartsWith(n, (std::string(f) + "_").c_str())) return true;
  return false;
}

OptionOwner ClassifyOption(const std::string &name, const std::vector<std::string> &solver_prefixes)
{
  // Options of the objects nltopo creates without a prefix (vectors, matrices,
  // the lattice's DMDA, their scatters: -vec_view, -mat_view, -dm_view,
  // -sf_type, ...): PETSc reads them when the objects are assembled or used.
  static const char *unprefixed_views[] = {"vec_", "mat_", "dm_", "sf_", "vecscatter_", "is_"};
  const std::string n = Lower(name);
  if (PetscGlobalOption(n)) return OptionOwner::Petsc;
  if (OwnComponent(n) || FindOption("-" + n)) return OptionOwner::Nltopo;
  for (const std::string &p : solver_prefixes)
    if (StartsWith(n, p.c_str())) return OptionOwner::Solver;
  for (const char *v : unprefixed_views)
    if (StartsWith(n, v)) return OptionOwner::Solver;
  return OptionOwner::Unknown;
}

std::string ClosestOption(const std::string &name, const std::set<std::string> &candidates)
{
  std::string best;
  size_t best_d = std::max<size_t>(2, name.size() / 4) + 1; // at most ~a quarter of the letters wrong
  for (const std::string &c : candidates) {
    const size_t d = EditDistance(name, c);
    if (d < best_d) best_d = d, best = c;
  }
  return best;
}

PetscErrorCode CheckFiniteOptionValues(MPI_Comm comm, const OptionList &given, bool solvers_only)
{
  PetscFunctionBeginUser;
  for (const auto &o : given) {
    const std::string &name = o.first, &v = o.second;
    const bool own = OwnComponent(Lower(name));
    if (solvers_only && own) continue;
    size_t pos = 0;
    while (pos <= v.size()) {
      size_t end = v.find(',', pos);
      if (end == std::string::npos) end = v.size();
      std::string tok = v.substr(pos, end - pos);
      tok.erase(0, tok.find_first_not_of(" \t"));
      tok.erase(tok.find_last_not_of(" \t") + 1);
      if (!tok.empty()) {
        char *stop;
        const double x = std::strtod(tok.c_str(), &stop);
        std::string low = tok;
        std::transform(low.begin(), low.end(), low.begin(), [](unsigned char c) { return (char)std::tolower(c); });
        const bool norm_name = low == "infinity" && !own; // PETSc's norm type names (-ts_adapt_wnormtype infinity)
        PetscCheck(*stop || std::isfinite(x) || norm_name, comm, PETSC_ERR_USER, "-%s %s: the value must be a finite number", name.c_str(), v.c_str());
      }
      pos = end + 1;
    }
  }
  PetscFunctionReturn(0);
}

PetscErrorCode ListGivenOptions(OptionList *given)
{
  Unused u;
  PetscFunctionBeginUser;
  PetscCall(UnusedOptions(&u));
  for (size_t i = 0; i < u.names.size(); i++) given->emplace_back(u.names[i], u.values[i]);
  PetscFunctionReturn(0);
}

PetscErrorCode CheckOptionValueShapes(MPI_Comm comm, const char *study, OptionsFn options, const OptionList &given)
{
  std::map<std::string, std::set<std::string>> known;
  std::map<std::string, OptionKind> kinds;
  PetscFunctionBeginUser;
  PetscCall(CollectKnownOptions(comm, {{study, options}}, &known, &kinds));
  for (const auto &o : given) {
    const std::string &n = o.first, &v = o.second; // n as given: the lines name it so
    const auto k = kinds.find(Lower(n));
    if (k == kinds.end() || PetscGlobalOption(n)) continue;      // unknown names are the unused-options audit's
    if (k->second != OptionKind::Flag && OwnComponent(Lower(n))) // solver options may take an optional value (-sim_ts_monitor)
      PetscCheck(!v.empty(), comm, PETSC_ERR_USER, "-%s: no value given (-help shows its default and meaning)", n.c_str());
    if (k->second == OptionKind::Integer && !v.empty()) {
      errno = 0;
      char *stop;
      const long long x = std::strtoll(v.c_str(), &stop, 10);
      const bool whole = *stop == '\0'; // anything else is PETSc's "not an integer"
      PetscCheck(!whole || (errno != ERANGE && x >= -(long long)PETSC_MAX_INT && x <= (long long)PETSC_MAX_INT), comm, PETSC_ERR_USER,
                 "-%s %s: out of the integer range [-%d, %d]", n.c_str(), v.c_str(), (int)PETSC_MAX_INT, (int)PETSC_MAX_INT);
    }
  }
  PetscFunctionReturn(0);
}

PetscErrorCode CollectKnownOptions(MPI_Comm comm, const std::map<std::string, OptionsFn> &studies, std::map<std::string, std::set<std::string>> *known,
                                   std::map<std::string, OptionKind> *kinds)
{
  PetscBool had_help;
  Unused before;
  PetscFunctionBeginUser;
  // The options functions read the run's own database (its values choose the
  // solver types whose options they list); what they mark used is unmarked
  // after, so that the audit's verdicts, and -options_left's listing at the
  // end, stay true.
  PetscCall(UnusedOptions(&before));
  PetscCall(PetscOptionsHasName(NULL, NULL, "-help", &had_help));
  if (!had_help) PetscCall(PetscOptionsSetValue(NULL, "-help", NULL));
  auto saved = PetscHelpPrintf;
  g_saved_vfprintf = PetscVFPrintf;
  PetscHelpPrintf = CapturePrintf;
  PetscVFPrintf = CaptureVFPrintf;
  PetscCall(PetscPushErrorHandler(PetscReturnErrorHandler, NULL));
  for (const auto &s : studies) {
    std::string text;
    // PETSc prints each options block once per process; the blocks this run
    // has read already count as printed, so forget them.
    PetscCall(PetscOptionsHelpPrintedDestroy(&PetscOptionsHelpPrintedSingleton));
    g_capture = &text;
    {
      EffectiveOptionsPause pause; // names only: not this run's values
      (void)s.second(comm);        // a validation error of another study's options stops its listing, nothing else
    }
    g_capture = nullptr;
    ParseHelp(text, &(*known)[s.first], kinds);
  }
  PetscCall(PetscOptionsHelpPrintedDestroy(&PetscOptionsHelpPrintedSingleton)); // a -help listing after this prints every block
  PetscCall(PetscPopErrorHandler());
  PetscHelpPrintf = saved;
  PetscVFPrintf = g_saved_vfprintf;
  if (!had_help) PetscCall(PetscOptionsClearValue(NULL, "-help"));
  for (size_t i = 0; i < before.names.size(); i++) {
    PetscBool used;
    const std::string name = "-" + before.names[i];
    PetscCall(PetscOptionsUsed(NULL, before.names[i].c_str(), &used));
    if (!used) continue;
    PetscCall(PetscOptionsClearValue(NULL, name.c_str())); // set again: unused
    PetscCall(PetscOptionsSetValue(NULL, name.c_str(), before.has_value[i] ? before.values[i].c_str() : NULL));
  }
  PetscFunctionReturn(0);
}

// Rank 0's candidates (names as given, without the dash), kept only where
// every rank left them unused: an option counts as used if any rank used it
// (sweep ranks run different points).
static PetscErrorCode UnusedOnEveryRank(MPI_Comm comm, const std::vector<std::string> &mine, std::vector<std::string> *bad)
{
  PetscFunctionBeginUser;
  std::string packed;
  for (const std::string &n : mine) packed += n + '\n';
  int len = (int)packed.size();
  PetscCallMPI(MPI_Bcast(&len, 1, MPI_INT, 0, comm));
  if (!len) PetscFunctionReturn(0);
  packed.resize(len);
  PetscCallMPI(MPI_Bcast(&packed[0], len, MPI_CHAR, 0, comm));
  std::vector<std::string> cand;
  for (size_t pos = 0; pos < packed.size();) {
    const size_t end = packed.find('\n', pos);
    cand.push_back(packed.substr(pos, end - pos));
    pos = end + 1;
  }
  std::vector<int> used(cand.size()), any(cand.size());
  for (size_t i = 0; i < cand.size(); i++) {
    PetscBool f;
    PetscCall(PetscOptionsUsed(NULL, cand[i].c_str(), &f)); // names are stored without the dash
    used[i] = f ? 1 : 0;
  }
  PetscCallMPI(MPI_Allreduce(used.data(), any.data(), (int)cand.size(), MPI_INT, MPI_MAX, comm));
  for (size_t i = 0; i < cand.size(); i++)
    if (!any[i]) bad->push_back(cand[i]);
  PetscFunctionReturn(0);
}

PetscErrorCode AuditUnusedOptions(MPI_Comm comm, const char *study, const std::map<std::string, OptionsFn> &studies, bool early,
                                  const std::vector<std::string> &solver_prefixes)
{
  Unused u;
  PetscMPIInt rank;
  std::vector<std::string> lines, mine, bad;
  std::map<std::string, std::string> value; // as given (reading it would mark it used)
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCall(UnusedOptions(&u));
  // Early: every option but PETSc's own and those of the study's solver
  // objects, which may read them during the run (checked at the end).
  for (size_t i = 0; i < u.names.size(); i++) {
    const std::string &n = u.names[i];
    value[n] = u.values[i];
    std::string mismatch;
    if (early) TypeMismatch(Lower(n), &mismatch);
    const OptionOwner owner = ClassifyOption(n, solver_prefixes);
    if (owner != OptionOwner::Petsc && (!early || owner != OptionOwner::Solver || !mismatch.empty())) mine.push_back(n);
  }
  PetscCall(UnusedOnEveryRank(comm, mine, &bad));
  if (bad.empty()) PetscFunctionReturn(0);

  std::map<std::string, std::set<std::string>> known;
  PetscCall(CollectKnownOptions(comm, studies, &known));
  std::set<std::string> all;
  for (const auto &k : known) all.insert(k.second.begin(), k.second.end());
  for (const std::string &given : bad) {
    const std::string n = Lower(given), &v = value[given];
    const std::string shown = "-" + given + (v.empty() ? std::string() : " " + v);
    std::string owner;
    for (const auto &k : known)
      if (k.first != study && k.second.count(n)) {
        owner = k.first;
        break;
      }
    std::string line, mismatch;
    TypeMismatch(n, &mismatch);
    if (!mismatch.empty()) line = shown + mismatch;
    else if (known[study].count(n)) line = shown + ": not used by this run (it applies only to other solver types or settings; remove it)";
    else if (!owner.empty()) line = shown + ": not an option of -study " + study + " (it belongs to -study " + owner + "); remove it";
    else {
      // Early, only nltopo's own blocks and unknown names are here. At the end
      // it may be a solver option of a type this run did not select.
      std::string near = ClosestOption(n, all);
      for (const std::string &k : known[study]) // a solver option without the study's prefix: -ts_type for -sim_ts_type
        if (near.empty() && k.size() > n.size() + 1 && k.compare(k.size() - n.size(), n.size(), n) == 0 && k[k.size() - n.size() - 1] == '_') near = k;
      const std::string hint = near.empty() ? std::string(" (-help lists the options)") : " (did you mean -" + near + "?)";
      const bool solver = !early && (StartsWith(n, "sim_") || StartsWith(n, "nnm_") || StartsWith(n, "linear_") || StartsWith(n, "floquet"));
      line = solver ? shown + ": not used by this run" + hint : "unknown option " + shown + hint;
    }
    lines.push_back(line);
  }
  for (size_t i = 0; i + 1 < lines.size(); i++)
    if (!rank) std::fprintf(stderr, "nltopo: error: %s\n", lines[i].c_str());
  SETERRQ(comm, PETSC_ERR_USER, "%s", lines.back().c_str());
}

} // namespace nltopo
