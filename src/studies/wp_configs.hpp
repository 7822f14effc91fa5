#pragma once
// What the work-precision studies share: the configuration lists (parsed,
// validated, applied to the options database for one scope and restored),
// their labels, and the error measures.
#include "core/handle.hpp"
#include "studies/workprecision.hpp"
#include <petscvec.h>
#include <algorithm>
#include <cctype>
#include <cmath>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace nltopo {
namespace wp {

using OptionPairs = std::vector<std::pair<std::string, std::string>>;

inline std::string Join(const std::vector<std::string> &v, const char *sep)
{
  std::string s;
  for (const auto &x : v) s += (s.empty() ? "" : sep) + x;
  return s;
}

inline std::vector<std::string> SplitList(const std::string &s, char sep)
{
  std::vector<std::string> out;
  std::string item;
  std::istringstream in(s);
  while (std::getline(in, item, sep)) {
    const size_t a = item.find_first_not_of(" \t"), b = item.find_last_not_of(" \t");
    out.push_back(a == std::string::npos ? "" : item.substr(a, b - a + 1));
  }
  return out;
}

inline bool LooksLikeValue(const std::string &tok)
{
  if (tok.empty()) return false;
  if (tok[0] != '-') return true;
  return tok.size() > 1 && (std::isdigit((unsigned char)tok[1]) || tok[1] == '.'); // a negative number
}

inline std::string LowerName(std::string s)
{
  for (char &c : s) c = (char)std::tolower((unsigned char)c);
  return s;
}

// "-a 1 -b -c x" -> (-a, 1), (-b, ""), (-c, x); only integrator options.
// shooting: the configurations of a shooting point take -nnm_ts_* and -nnm_steps_per_period.
inline PetscErrorCode ParseConfig(MPI_Comm comm, const char *what, const std::string &cfg, OptionPairs *out, bool shooting = false)
{
  std::istringstream in(cfg);
  std::vector<std::string> tok;
  for (std::string t; in >> t;) tok.push_back(t);
  PetscFunctionBeginUser;
  out->clear();
  PetscCheck(!tok.empty(), comm, PETSC_ERR_USER, "%s: an empty configuration (two commas in a row?)", what);
  for (size_t i = 0; i < tok.size(); i++) {
    const std::string &name = tok[i];
    PetscCheck(name.size() > 1 && name[0] == '-' && !LooksLikeValue(name), comm, PETSC_ERR_USER, "%s \"%s\": %s is not an option name", what, cfg.c_str(),
               name.c_str());
    const std::string low = LowerName(name); // PETSc's option names are case-insensitive
    const bool ok =
        shooting ? low.rfind("-nnm_ts_", 0) == 0 || low == "-nnm_steps_per_period" : low.rfind("-sim_ts_", 0) == 0 || low == "-sim_dt_quartic_energy";
    PetscCheck(ok, comm, PETSC_ERR_USER, "%s \"%s\": %s is not an integrator option (configurations take %s; the scene's options go outside)", what,
               cfg.c_str(), name.c_str(), shooting ? "-nnm_ts_* and -nnm_steps_per_period" : "-sim_ts_* and -sim_dt_quartic_energy");
    std::string value;
    if (i + 1 < tok.size() && LooksLikeValue(tok[i + 1])) value = tok[++i];
    out->push_back({name, value});
  }
  PetscFunctionReturn(0);
}

// Sets a configuration's options for one scope and restores the database
// after: options the scene had are given their old values back (and marked
// used: the study read them), new ones are removed.
class ScopedConfig {
public:
  PetscErrorCode Apply(const OptionPairs &opts)
  {
    PetscFunctionBeginUser;
    for (const auto &[name, value] : opts) {
      const char *old;
      PetscBool found;
      PetscCall(PetscOptionsFindPair(NULL, NULL, name.c_str(), &old, &found));
      saved_.push_back({name, found ? (old ? old : "") : std::string("\x01")});
      PetscCall(PetscOptionsSetValue(NULL, name.c_str(), value.empty() ? NULL : value.c_str()));
    }
    PetscFunctionReturn(0);
  }
  // One line for the first option of the configuration that the run did not read.
  PetscErrorCode CheckUsed(MPI_Comm comm, const char *what, const std::string &cfg) const
  {
    PetscFunctionBeginUser;
    for (const auto &[name, old] : saved_) {
      PetscBool used;
      PetscCall(PetscOptionsUsed(NULL, name.c_str() + 1, &used)); // the database holds names without the dash
      if (old != "\x01") continue;                                // an option the scene also sets keeps the scene's "used" mark: not checkable
      PetscCheck(used, comm, PETSC_ERR_USER, "%s \"%s\": %s was not used by that run (an option of another TS type, or misspelt)", what, cfg.c_str(),
                 name.c_str());
    }
    PetscFunctionReturn(0);
  }
  PetscErrorCode Restore()
  {
    PetscFunctionBeginUser;
    for (auto it = saved_.rbegin(); it != saved_.rend(); ++it) {
      if (it->second == "\x01") PetscCall(PetscOptionsClearValue(NULL, it->first.c_str()));
      else {
        PetscBool set;
        PetscCall(PetscOptionsSetValue(NULL, it->first.c_str(), it->second.empty() ? NULL : it->second.c_str()));
        PetscCall(PetscOptionsHasName(NULL, NULL, it->first.c_str(), &set)); // the scene's option stays "used"
      }
    }
    saved_.clear();
    PetscFunctionReturn(0);
  }
  ~ScopedConfig() { (void)Restore(); }

private:
  std::vector<std::pair<std::string, std::string>> saved_; // "\x01": was not set
};

inline bool EndsWith(const std::string &s, const std::string &end) { return s.size() >= end.size() && s.compare(s.size() - end.size(), end.size(), end) == 0; }

inline void Label(const OptionPairs &opts, std::string *method, std::string *accuracy)
{
  std::vector<std::string> m, a;
  std::string rtol, atol, dt, steps;
  for (const auto &[given, value] : opts) {
    const std::string name = LowerName(given);
    if (name == "-sim_ts_rtol") rtol = value;
    else if (name == "-sim_ts_atol") atol = value;
    else if (name == "-sim_ts_dt") dt = value;
    else if (name == "-nnm_steps_per_period") steps = value;
    else if (EndsWith(name, "_type") || EndsWith(name, "_scheme")) m.push_back(value);
    else m.push_back(name.substr(1) + "=" + value);
  }
  if (!rtol.empty()) a.push_back("tol " + rtol + (atol.empty() || atol == rtol ? "" : "/" + atol));
  if (!dt.empty() && rtol.empty()) a.push_back("dt " + dt);
  if (!steps.empty()) a.push_back(steps + " steps/period");
  *method = m.empty() ? "(scene)" : Join(m, " ");
  *accuracy = a.empty() ? "(scene)" : Join(a, " ");
}

// One configuration of a study: parsed, labelled, applied for its runs
// (run(&wall) o.repeats times; it keeps the last run's results itself),
// checked that every option of it was read, the database restored; the row
// gets the configuration, its labels and the median wall time.
template <class RunFn>
inline PetscErrorCode TimeConfiguration(MPI_Comm comm, const std::string &cfg, bool shooting, PetscInt repeats, RunFn run, WorkPrecisionRow *row)
{
  OptionPairs opts;
  ScopedConfig sc;
  std::vector<PetscReal> walls;
  PetscFunctionBeginUser;
  PetscCall(ParseConfig(comm, "-wp_configs: configuration", cfg, &opts, shooting));
  row->config = cfg;
  Label(opts, &row->method, &row->accuracy);
  PetscCall(sc.Apply(opts));
  for (PetscInt k = 0; k < repeats; k++) {
    PetscReal w;
    PetscCall(run(&w));
    walls.push_back(w);
  }
  PetscCall(sc.CheckUsed(comm, "-wp_configs: configuration", cfg));
  PetscCall(sc.Restore());
  std::sort(walls.begin(), walls.end());
  const size_t m = walls.size() / 2;
  row->wall = walls.size() % 2 ? walls[m] : 0.5 * (walls[m - 1] + walls[m]);
  PetscFunctionReturn(0);
}

inline PetscReal Rel(PetscReal a, PetscReal b) { return b != 0 ? std::abs(a - b) / std::abs(b) : std::abs(a - b); }

inline PetscErrorCode StateDistance(Vec a, Vec b, PetscReal *d)
{
  OwnedVec w;
  PetscReal nb;
  PetscFunctionBeginUser;
  PetscCall(VecDuplicate(a, w.out()));
  PetscCall(VecWAXPY(w, -1.0, b, a));
  PetscCall(VecNorm(w, NORM_2, d));
  PetscCall(VecNorm(b, NORM_2, &nb));
  if (nb > 0) *d /= nb;
  PetscFunctionReturn(0);
}

} // namespace wp
} // namespace nltopo
