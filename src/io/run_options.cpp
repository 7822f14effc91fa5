#include "io/run_options.hpp"
#include "io/schema.hpp"
#include "core/effective_options.hpp"
#include "core/option_table.hpp"
#include "io/input.hpp"
#include "core/text.hpp"
#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <map>
#include <sys/stat.h>
#include <vector>

namespace nltopo {

namespace {

enum class Kind { Ignore, Extent, Physics };

Kind Classify(const std::string &key)
{
  const std::vector<std::string> &prefixes = ComponentPrefixes();
  if (std::none_of(prefixes.begin(), prefixes.end(), [&](const std::string &p) { return StartsWith(key, p.c_str()); })) return Kind::Ignore;
  if (const OptionInfo *row = FindOption(key)) // nltopo's own option: its table's class
    return row->cls == OptionClass::Bookkeeping ? Kind::Ignore : row->cls == OptionClass::Extent ? Kind::Extent : Kind::Physics;
  // a solver option (-sim_ts_*, -nnm_snes_*, ...): its monitors and views are bookkeeping, the rest numerics
  for (const char *d : {"monitor", "_view", "converged_reason"})
    if (key.find(d) != std::string::npos) return Kind::Ignore;
  return Kind::Physics;
}

// Options nltopo itself puts into the database when the user did not: absent = this value.
const std::map<std::string, std::string> &InternalDefaults()
{
  static const std::map<std::string, std::string> d = {{"-nnm_start_pc_svd_zero_sing", "1e-9"}};
  return d;
}

std::string Lower(std::string s)
{
  for (char &c : s) c = (char)std::tolower((unsigned char)c);
  return s;
}

// A key is "-" followed by a letter (so -0.5 and -.5 are values), as PETSc reads them.
bool IsKey(const std::string &tok) { return tok.size() > 1 && tok[0] == '-' && std::isalpha((unsigned char)tok[1]); }

// PetscOptionsGetAll's "-a 1 -b -c x y" as {-a: "1", -b: "", -c: "x y"} (names lower-case: PETSc's are case-insensitive).
std::map<std::string, std::string> Parse(const std::string &all)
{
  std::map<std::string, std::string> m;
  std::string key;
  size_t i = 0;
  while (i < all.size()) {
    while (i < all.size() && std::isspace((unsigned char)all[i])) i++;
    size_t j = i;
    while (j < all.size() && !std::isspace((unsigned char)all[j])) j++;
    if (j == i) break;
    const std::string tok = all.substr(i, j - i);
    i = j;
    if (IsKey(tok)) {
      key = Lower(tok);
      m[key] = "";
    } else if (!key.empty()) {
      std::string &v = m[key];
      v += (v.empty() ? "" : " ") + tok;
    }
  }
  return m;
}

// One element of a value: a number, a boolean, or a string.
bool SameElement(std::string a, std::string b)
{
  auto number = [](const std::string &s, double *x) {
    if (s.empty()) return false;
    char *end;
    errno = 0;
    *x = std::strtod(s.c_str(), &end);
    return *end == 0 && errno == 0;
  };
  auto boolean = [](std::string s) -> int {
    s = Lower(s);
    if (s.empty() || s == "true" || s == "yes" || s == "on") return 1;
    if (s == "false" || s == "no" || s == "off") return 0;
    return -1;
  };
  double x, y;
  int bx = boolean(a), by = boolean(b);
  if (bx >= 0) a = bx ? "1" : "0";
  if (by >= 0) b = by ? "1" : "0";
  if (number(a, &x) && number(b, &y)) return x == y;
  return Lower(a) == Lower(b);
}

bool SameValue(const std::string &a, const std::string &b)
{
  auto split = [](const std::string &s) {
    std::vector<std::string> v;
    size_t i = 0;
    for (;;) {
      size_t j = s.find(',', i);
      v.push_back(s.substr(i, j == std::string::npos ? std::string::npos : j - i));
      if (j == std::string::npos) break;
      i = j + 1;
    }
    return v;
  };
  const auto va = split(a), vb = split(b);
  if (va.size() != vb.size()) return false;
  for (size_t k = 0; k < va.size(); k++)
    if (!SameElement(va[k], vb[k])) return false;
  return true;
}

std::string Shown(const std::string &key, const std::string &value) { return value.empty() ? key : key + " " + value; }

// Rank 0's result, on every rank: a non-empty message fails all of them.
PetscErrorCode FailIfMessage(MPI_Comm comm, PetscErrorCode code, std::string msg)
{
  char buf[2048] = "";
  PetscMPIInt rank;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  if (!rank) PetscCall(PetscStrncpy(buf, msg.c_str(), sizeof(buf)));
  PetscCallMPI(MPI_Bcast(buf, sizeof(buf), MPI_CHAR, 0, comm));
  PetscCheck(!buf[0], comm, code, "%s", buf);
  PetscFunctionReturn(0);
}

std::string RunOptions()
{
  char *opts = NULL;
  std::string s;
  if (!PetscOptionsGetAll(NULL, &opts) && opts) s = opts;
  PetscFree(opts);
  return s;
}

// effective_options' "-name value" lines.
std::map<std::string, std::string> ParseLines(const std::string &text)
{
  std::map<std::string, std::string> m;
  size_t i = 0;
  while (i < text.size()) {
    size_t j = text.find('\n', i);
    if (j == std::string::npos) j = text.size();
    const std::string line = text.substr(i, j - i);
    const size_t sp = line.find(' ');
    if (!line.empty()) m[Lower(line.substr(0, sp))] = sp == std::string::npos ? "" : line.substr(sp + 1);
    i = j + 1;
  }
  return m;
}

// Options given on neither side, whose effective values both records hold and that differ under the rule.
std::string EffectiveDifference(const std::map<std::string, std::string> &fe, const std::map<std::string, std::string> &re,
                                const std::map<std::string, std::string> &fg, const std::map<std::string, std::string> &rg,
                                const std::function<bool(const std::string &)> &compared)
{
  for (const auto &kv : fe) {
    const std::string &key = kv.first;
    if (fg.count(key) || rg.count(key) || !re.count(key) || !compared(key)) continue;
    if (!SameValue(kv.second, re.at(key))) return "with " + Shown(key, kv.second) + ", the default then (now " + re.at(key) + ")";
  }
  return "";
}

} // namespace

RunRecord ThisRunRecord() { return {RunOptions(), EffectiveOptionsText()}; }

std::string FirstOptionDifference(const RunRecord &file, const RunRecord &run, OptionRule rule)
{
  const auto f = Parse(file.given), r = Parse(run.given);
  const auto fe = ParseLines(file.effective), re = ParseLines(run.effective);
  // Floquet multipliers post-process each stored orbit and never feed back: a
  // resume that does not compute them (-floquet off) ignores their options.
  const auto fl = r.find("-floquet");
  const bool floquet_now = fl != r.end() && SameElement(fl->second, "1");
  auto compared = [&](const std::string &key) {
    const Kind k = Classify(key);
    if (rule == OptionRule::Resume && !floquet_now && StartsWith(key, "-floquet")) return false;
    return k == Kind::Physics || (k == Kind::Extent && rule == OptionRule::Overwrite);
  };
  // a side's value of key: given, else its effective value, else nltopo's internal default; false: unknown
  auto value = [&](const std::map<std::string, std::string> &given, const std::map<std::string, std::string> &eff, const std::string &key, std::string *v) {
    const auto g = given.find(key), e = eff.find(key), d = InternalDefaults().find(key);
    if (g != given.end()) *v = g->second;
    else if (e != eff.end()) *v = e->second;
    else if (d != InternalDefaults().end()) *v = d->second;
    else return false;
    return true;
  };
  std::map<std::string, int> keys;
  for (const auto &kv : f) keys[kv.first] |= 1;
  for (const auto &kv : r) keys[kv.first] |= 2;
  for (const auto &k : keys) {
    const std::string &key = k.first;
    if (!compared(key)) continue;
    std::string fv, rv;
    const bool known_f = value(f, fe, key, &fv), known_r = value(r, re, key, &rv);
    if (known_f && known_r && SameValue(fv, rv)) continue; // e.g. given on one side, the same default on the other
    if (k.second == 3 || InternalDefaults().count(key)) return "with " + Shown(key, fv) + " (now " + (rv.empty() ? key : rv) + ")";
    if (k.second == 1) return "with " + Shown(key, fv) + " (now not given)";
    return "without " + key + " (now " + (rv.empty() ? key : rv) + ")";
  }
  return EffectiveDifference(fe, re, f, r, compared);
}

bool SameFile(const std::string &a, const std::string &b)
{
  struct stat sa, sb;
  if (!stat(a.c_str(), &sa) && !stat(b.c_str(), &sb)) return sa.st_dev == sb.st_dev && sa.st_ino == sb.st_ino;
  return a == b;
}

PetscErrorCode CheckResumeOptions(MPI_Comm comm, const std::string &file, const char *study, const char *what)
{
  PetscMPIInt rank;
  std::string msg;
  struct stat st;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  if (!rank && !stat(file.c_str(), &st)) { // a missing file is the caller's error (it names what it expected)
    std::string s, o, e;
    if (!ReadRootAttribute(file, "study", &s) || !ReadRootAttribute(file, "options", &o))
      msg = std::string(what) + " " + file + ": not an nltopo output (no root attributes study and options)";
    else if (s != study) msg = std::string(what) + " " + file + " was written by -study " + s + " (now " + study + ")";
    else if (long v = 0; ReadRootAttribute(file, "format_version", &v), v != kFormatVersion)
      msg = std::string(what) + " " + file + " has format_version " + std::to_string(v) + " (this nltopo writes " + std::to_string(kFormatVersion) +
            "): resume it with the nltopo that wrote it, or start afresh";
    else {
      ReadRootAttribute(file, "effective_options", &e); // absent in files of before it existed
      const std::string d = FirstOptionDifference({o, e}, ThisRunRecord(), OptionRule::Resume);
      if (!d.empty()) msg = std::string(what) + " " + file + " was written " + d;
    }
  }
  PetscCall(FailIfMessage(comm, PETSC_ERR_USER, msg));
  PetscFunctionReturn(0);
}

PetscErrorCode CheckOverwrite(MPI_Comm comm, const std::string &path, const char *study, PetscBool overwrite)
{
  PetscMPIInt rank;
  std::string msg;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  if (!rank && !overwrite) {
    std::string s, o, e;
    long complete = 1;
    if (ReadRootAttribute(path, "study", &s)) { // an nltopo output
      ReadRootAttribute(path, "options", &o);
      ReadRootAttribute(path, "effective_options", &e);
      ReadRootAttribute(path, "complete", &complete);
      const std::string held = complete ? "the complete output" : "a partial output (complete = 0)";
      std::string d;
      if (s != study) d = held + " of -study " + s + " (this run: -study " + study + ")";
      else {
        d = FirstOptionDifference({o, e}, ThisRunRecord(), OptionRule::Overwrite);
        if (!d.empty()) d = held + " of a run " + d;
      }
      if (!d.empty()) msg = "-output " + path + " holds " + d + "; choose another -output or give -output_overwrite";
    }
  }
  PetscCall(FailIfMessage(comm, PETSC_ERR_FILE_WRITE, msg));
  PetscFunctionReturn(0);
}

} // namespace nltopo
