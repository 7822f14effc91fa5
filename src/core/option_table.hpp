#pragma once
// Options declared once: a component's options are one table, each row its
// name, type, range, help and class; the default is the value of the
// component's options struct as default-constructed (or a row's stated rule,
// e.g. "sqrt(k_hat)"). From the table come the PetscOptions* calls (so -help
// lists them), the range checks with their one-line messages, and the
// registry that tools read: the run-options classes (io/run_options.hpp),
// the in-process validator tests and the options reference.
//
// What options must not combine to (a site beyond N, a profile that needs a
// layout) stays the component's own check after Read: a row knows one option.
#include "core/effective_options.hpp"
#include "core/option_help.hpp"
#include <petscsys.h>
#include <cmath>
#include <functional>
#include <string>
#include <vector>

namespace nltopo {

// How a resume and an overwrite compare an option (io/run_options.hpp):
// physics and numerics must agree, the extent of a run may grow on resume,
// bookkeeping is never compared.
enum class OptionClass { Physics, Extent, Bookkeeping };
const char *OptionClassName(OptionClass c);

// A numeric range; an end is open or closed. Infinite ends are allowed
// (a value must still be finite: non-finite values never pass).
struct Bounds {
  double lo = -INFINITY, hi = INFINITY;
  bool lo_open = false, hi_open = false;
  bool Contains(double x) const { return std::isfinite(x) && (lo_open ? x > lo : x >= lo) && (hi_open ? x < hi : x <= hi); }
  std::string Text(bool integer) const; // "[0, 1e6]", "(0, 0.1)", "1..100"
};
inline Bounds Closed(double lo, double hi) { return {lo, hi, false, false}; }
inline Bounds LeftOpen(double lo, double hi) { return {lo, hi, true, false}; }
inline Bounds RightOpen(double lo, double hi) { return {lo, hi, false, true}; }
inline Bounds Open(double lo, double hi) { return {lo, hi, true, true}; }

enum class OptionType { Real, Int, Bool, Enum, String, RealList, StringList };
const char *OptionTypeName(OptionType t);

// One row as tools see it (no binding to a struct).
struct OptionInfo {
  std::string name; // with the dash and the prefix: "-lattice_k"
  OptionType type;
  Bounds bounds;                    // Real, Int
  std::vector<std::string> choices; // Enum
  std::string help, why;            // why: what the range protects, for the error line
  std::string default_text;
  OptionClass cls;
  bool only_if_set = false; // the range applies when the option is given (an unset value means "computed")
};

// Every table of the program, in registration order (static tables register
// at start-up): its rows, and its reader run on the struct's defaults (the
// in-process validator tests).
struct RegisteredOptionTable {
  std::string title; // the -help heading
  const std::vector<OptionInfo> *rows;
  std::function<PetscErrorCode(MPI_Comm)> read_defaults;
};
const std::vector<RegisteredOptionTable> &OptionTables();
void RegisterOptionTable(const char *title, const std::vector<OptionInfo> *rows, std::function<PetscErrorCode(MPI_Comm)> read_defaults);
// The row of a full option name ("-lattice_k", in any case), NULL if no table declares it.
const OptionInfo *FindOption(const std::string &name);

// The option prefixes of nltopo's components ("-wp_"), registered by each
// study's contract (studies/registry.cpp): the options a resume or an
// overwrite compares (io/run_options.hpp) and nltopo's own option blocks,
// refused before any work when unused (core/options_audit.hpp). A prefix is
// registered once.
void RegisterComponentPrefixes(const std::vector<std::string> &prefixes);
const std::vector<std::string> &ComponentPrefixes();

// The one-line message of a value outside a row's range:
// "-lattice_k must lie in [1e-06, 1e+06], got 0".
std::string RangeMessage(const OptionInfo &row, double value);

// A component's table, bound to its options struct S.
template <class S> class OptionTable {
public:
  // prefix: "lattice_", or NULL for options without one (-output).
  OptionTable(const char *prefix, const char *title) : prefix_(prefix), title_(title) {}
  ~OptionTable() = default;
  OptionTable(const OptionTable &) = delete;
  OptionTable &operator=(const OptionTable &) = delete;

  OptionTable &Real(const char *name, PetscReal S::*m, Bounds b, const char *help, OptionClass c = OptionClass::Physics)
  {
    Row r = NewRow(name, OptionType::Real, b, help, c);
    r.info.default_text = Num(S{}.*m, false);
    r.read = [m](PetscOptionItems *PetscOptionsObject, const char *opt, const char *text, S *s, PetscBool *set) -> PetscErrorCode {
      return PetscOptionsReal(opt, text, NULL, s->*m, &(s->*m), set);
    };
    r.value = [m](const S &s) { return (double)(s.*m); };
    r.text = [m](const S &s) { return Num(s.*m, false); };
    rows_.push_back(std::move(r));
    return *this;
  }
  OptionTable &Int(const char *name, PetscInt S::*m, Bounds b, const char *help, OptionClass c = OptionClass::Physics)
  {
    Row r = NewRow(name, OptionType::Int, b, help, c);
    r.info.default_text = Num((double)(S{}.*m), true);
    r.read = [m](PetscOptionItems *PetscOptionsObject, const char *opt, const char *text, S *s, PetscBool *set) -> PetscErrorCode {
      return PetscOptionsInt(opt, text, NULL, s->*m, &(s->*m), set);
    };
    r.value = [m](const S &s) { return (double)(s.*m); };
    r.text = [m](const S &s) { return Num((double)(s.*m), true); };
    rows_.push_back(std::move(r));
    return *this;
  }
  OptionTable &Bool(const char *name, PetscBool S::*m, const char *help, OptionClass c = OptionClass::Physics)
  {
    Row r = NewRow(name, OptionType::Bool, Bounds{}, help, c);
    r.info.default_text = (S{}.*m) ? "true" : "false";
    r.read = [m](PetscOptionItems *PetscOptionsObject, const char *opt, const char *text, S *s, PetscBool *set) -> PetscErrorCode {
      return PetscOptionsBool(opt, text, NULL, s->*m, &(s->*m), set);
    };
    r.text = [m](const S &s) { return std::string((s.*m) ? "true" : "false"); };
    rows_.push_back(std::move(r));
    return *this;
  }
  // An enum-valued member E (an enum class whose values are 0..n-1 in the order of names).
  template <class E> OptionTable &Enum(const char *name, E S::*m, const char *const *names, int n, const char *help, OptionClass c = OptionClass::Physics)
  {
    Row r = NewRow(name, OptionType::Enum, Bounds{}, help, c);
    r.info.choices.assign(names, names + n);
    r.info.default_text = names[static_cast<int>(S{}.*m)];
    r.read = [m, names, n](PetscOptionItems *PetscOptionsObject, const char *opt, const char *text, S *s, PetscBool *set) -> PetscErrorCode {
      PetscInt k = static_cast<PetscInt>(s->*m);
      PetscCall(PetscOptionsEList(opt, text, NULL, names, n, names[k], &k, set));
      s->*m = static_cast<E>(k);
      return 0;
    };
    r.text = [m, names](const S &s) { return std::string(names[static_cast<int>(s.*m)]); };
    rows_.push_back(std::move(r));
    return *this;
  }
  // A text value (a file, a configuration string); "" when not given.
  OptionTable &String(const char *name, std::string S::*m, const char *help, OptionClass c = OptionClass::Physics)
  {
    Row r = NewRow(name, OptionType::String, Bounds{}, help, c);
    r.info.default_text = S{}.*m;
    r.read = [m](PetscOptionItems *PetscOptionsObject, const char *opt, const char *text, S *s, PetscBool *set) -> PetscErrorCode {
      char buf[PETSC_MAX_PATH_LEN];
      PetscCall(PetscStrncpy(buf, (s->*m).c_str(), sizeof(buf)));
      PetscCall(PetscOptionsString(opt, text, NULL, buf, buf, sizeof(buf), set));
      s->*m = buf;
      return 0;
    };
    r.text = [m](const S &s) { return s.*m; };
    rows_.push_back(std::move(r));
    return *this;
  }
  // A comma-separated list of at most max_count reals, each in b (checked by Read); the word none gives the
  // empty list (a list an options file sets, cleared on the command line).
  OptionTable &RealList(const char *name, std::vector<PetscReal> S::*m, PetscInt max_count, Bounds b, const char *help, OptionClass c = OptionClass::Physics)
  {
    Row r = NewRow(name, OptionType::RealList, b, help, c);
    r.info.default_text = ListText(S{}.*m);
    r.read = [m, max_count](PetscOptionItems *PetscOptionsObject, const char *opt, const char *text, S *s, PetscBool *set) -> PetscErrorCode {
      char word[8] = "";
      PetscBool given, none = PETSC_FALSE;
      PetscCall(PetscOptionsGetString(PetscOptionsObject->options, PetscOptionsObject->prefix, opt, word, sizeof word, &given));
      if (given) PetscCall(PetscStrcasecmp(word, "none", &none));
      if (none) {
        (s->*m).clear(), *set = PETSC_TRUE;
        return 0;
      }
      // one more than allowed, so that a longer list is refused rather than cut; the current values for -help
      std::vector<PetscReal> v(s->*m);
      v.resize(max_count + 1);
      PetscInt n = max_count + 1;
      PetscCall(PetscOptionsRealArray(opt, text, NULL, v.data(), &n, set));
      PetscCheck(!*set || n <= max_count, PetscOptionsObject->comm, PETSC_ERR_USER, "-%s%s takes at most %" PetscInt_FMT " values",
                 PetscOptionsObject->prefix ? PetscOptionsObject->prefix : "", opt + 1, max_count);
      if (*set) s->*m = std::vector<PetscReal>(v.begin(), v.begin() + n);
      return 0;
    };
    r.values = [m](const S &s) { return std::vector<double>((s.*m).begin(), (s.*m).end()); };
    r.text = [m](const S &s) { return ListText(s.*m); };
    rows_.push_back(std::move(r));
    return *this;
  }
  // A comma-separated list of at most max_count words.
  OptionTable &StringList(const char *name, std::vector<std::string> S::*m, PetscInt max_count, const char *help, OptionClass c = OptionClass::Physics)
  {
    Row r = NewRow(name, OptionType::StringList, Bounds{}, help, c);
    const S defaults{}; // not S{}.*m in the loop: the temporary would end before the loop runs
    for (const std::string &w : defaults.*m) r.info.default_text += (r.info.default_text.empty() ? "" : ",") + w;
    r.read = [m, max_count](PetscOptionItems *PetscOptionsObject, const char *opt, const char *text, S *s, PetscBool *set) -> PetscErrorCode {
      std::vector<char *> v(max_count + 1, nullptr); // one more than allowed: a longer list is refused, not cut
      PetscInt n = max_count + 1;
      PetscCall(PetscOptionsStringArray(opt, text, NULL, v.data(), &n, set));
      if (*set && n > max_count) {
        for (PetscInt k = 0; k < n; k++) PetscCall(PetscFree(v[k]));
        SETERRQ(PetscOptionsObject->comm, PETSC_ERR_USER, "-%s%s takes at most %" PetscInt_FMT " values",
                PetscOptionsObject->prefix ? PetscOptionsObject->prefix : "", opt + 1, max_count);
      }
      if (*set) {
        (s->*m).clear();
        for (PetscInt k = 0; k < n; k++) (s->*m).push_back(v[k]);
      }
      for (PetscInt k = 0; k < n; k++) PetscCall(PetscFree(v[k]));
      return 0;
    };
    r.text = [m](const S &s) {
      std::string t;
      for (const std::string &w : s.*m) t += (t.empty() ? "" : ",") + w;
      return t;
    };
    rows_.push_back(std::move(r));
    return *this;
  }
  // Modifiers of the last row.
  OptionTable &Why(const char *why) { return rows_.back().info.why = why, *this; }
  OptionTable &Default(const char *rule) { return rows_.back().info.default_text = rule, *this; }
  OptionTable &OnlyIfSet() { return rows_.back().info.only_if_set = true, *this; }

  // Registers the table for tools (once; DeclareOptionTable calls it). seed: the values its
  // reader starts from where a default is computed at run time (a row with a Default rule).
  const OptionTable &Register(const S &seed = S{})
  {
    infos_.clear();
    for (const Row &r : rows_) infos_.push_back(r.info);
    RegisterOptionTable(title_, &infos_, [this, seed](MPI_Comm comm) -> PetscErrorCode {
      S s = seed;
      return Read(comm, &s);
    });
    return *this;
  }
  const std::vector<OptionInfo> &Rows() const { return infos_; }
  // Whether the row called name ("amplitude") was given, from Read's set.
  bool Given(const std::vector<PetscBool> &set, const char *name) const
  {
    for (size_t k = 0; k < rows_.size() && k < set.size(); k++)
      if (rows_[k].short_name.compare(1, std::string::npos, name) == 0) return set[k];
    return false;
  }

  // Reads the block into s (whose values are the defaults going in) and checks
  // every row's range; set[k] (optional) says whether row k was given.
  PetscErrorCode Read(MPI_Comm comm, S *s, std::vector<PetscBool> *set = nullptr) const
  {
    std::vector<PetscBool> given(rows_.size(), PETSC_FALSE);
    PetscFunctionBeginUser;
    PetscOptionsBegin(comm, prefix_, title_, NULL);
    for (size_t k = 0; k < rows_.size(); k++)
      PetscCall(rows_[k].read(PetscOptionsObject, rows_[k].short_name.c_str(), rows_[k].info.help.c_str(), s, &given[k]));
    PetscOptionsEnd();
    for (size_t k = 0; k < rows_.size(); k++) {
      const Row &r = rows_[k];
      if (r.info.only_if_set && !given[k]) continue;
      if (r.value) {
        const double x = r.value(*s);
        PetscCheck(r.info.bounds.Contains(x), comm, PETSC_ERR_USER, "%s", RangeMessage(r.info, x).c_str());
      }
      if (r.values)
        for (double x : r.values(*s)) PetscCheck(r.info.bounds.Contains(x), comm, PETSC_ERR_USER, "%s", RangeMessage(r.info, x).c_str());
    }
    for (const Row &r : rows_)
      if (r.text) NoteEffectiveOption(r.info.name, r.text(*s)); // the run's provenance (core/effective_options.hpp)
    if (HelpCollecting()) {                                     // -help: this block, with the values this run would use (core/option_help.hpp)
      std::vector<HelpRow> help;
      for (size_t k = 0; k < rows_.size(); k++) help.push_back({&rows_[k].info, rows_[k].text ? rows_[k].text(*s) : std::string(), (bool)given[k]});
      NoteHelpBlock(prefix_, title_, std::move(help));
    }
    if (set) *set = given;
    PetscFunctionReturn(0);
  }

private:
  struct Row {
    OptionInfo info;
    std::string short_name; // "-k" (PetscOptionsBegin adds the prefix)
    std::function<PetscErrorCode(PetscOptionItems *, const char *, const char *, S *, PetscBool *)> read;
    std::function<double(const S &)> value;               // numeric rows
    std::function<std::vector<double>(const S &)> values; // list rows, each entry in the bounds
    std::function<std::string(const S &)> text;           // the value as the provenance records it
  };
  Row NewRow(const char *name, OptionType t, Bounds b, const char *help, OptionClass c) const
  {
    Row r;
    r.short_name = std::string("-") + name;
    r.info.name = std::string("-") + (prefix_ ? prefix_ : "") + name;
    r.info.type = t;
    r.info.bounds = b;
    r.info.help = help;
    const bool bounded = std::isfinite(b.lo) || std::isfinite(b.hi);
    if ((t == OptionType::Real || t == OptionType::Int) && bounded) r.info.help += "; in " + b.Text(t == OptionType::Int);
    r.info.cls = c;
    return r;
  }
  static std::string Num(double x, bool integer);
  static std::string ListText(const std::vector<PetscReal> &v)
  {
    std::string t;
    for (PetscReal x : v) t += (t.empty() ? "" : ",") + Num(x, false);
    return t;
  }
  const char *prefix_, *title_;
  std::vector<Row> rows_;
  std::vector<OptionInfo> infos_;
};

std::string OptionNumberText(double x, bool integer);

// A component's table, built once by rows(t) and registered: call it at
// namespace scope, `static const auto &kTable = DeclareOptionTable<S>(prefix,
// title, [](OptionTable<S> &t) { t.Real(...).Int(...); });`, so the table is
// known at start-up. Each call site (its lambda) owns its table.
template <class S, class Rows> const OptionTable<S> &DeclareOptionTable(const char *prefix, const char *title, Rows rows, const S &seed = S{})
{
  static OptionTable<S> t(prefix, title);
  static const bool built = (rows(t), t.Register(seed), true);
  (void)built;
  return t;
}
template <class S> std::string OptionTable<S>::Num(double x, bool integer) { return OptionNumberText(x, integer); }

} // namespace nltopo
