// The option tables (core/option_table.hpp), in-process: every numeric row of
// every registered table refuses a value just outside each finite end of its
// range and a non-finite value, with the one line that names the option, and
// accepts each closed end; every row is documented and classed, and its
// default lies in its range.
#include "core/errors.hpp"
#include "core/option_table.hpp"
#include "helpers.hpp"
#include "io/run_options.hpp"
#include <cstdio>
#include <cstdlib>
#include <map>
#include <set>

using namespace nltopo;

namespace {

// Runs the table's reader with "name value" in the database; the option is removed after.
PetscErrorCode ReadWith(const RegisteredOptionTable &t, const std::string &name, const std::string &value, PetscErrorCode *code, std::string *msg)
{
  char buf[1024];
  PetscFunctionBeginUser;
  PetscCall(PetscOptionsSetValue(NULL, name.c_str(), value.c_str()));
  PetscCall(CaptureError([&]() { return t.read_defaults(PETSC_COMM_WORLD); }, code, buf, sizeof buf));
  PetscCall(PetscOptionsClearValue(NULL, name.c_str()));
  *msg = buf;
  PetscFunctionReturn(0);
}

std::string Text(double x, bool integer)
{
  char buf[64];
  if (integer) std::snprintf(buf, sizeof buf, "%lld", (long long)x);
  else std::snprintf(buf, sizeof buf, "%.17g", x);
  return buf;
}

bool Numeric(const OptionInfo &r) { return r.type == OptionType::Real || r.type == OptionType::Int; }

} // namespace

TEST_CASE("option tables: every row is named once, documented, classed, and its default lies in its range", "[options]")
{
  REQUIRE(OptionTables().size() >= 5);
  std::set<std::string> names;
  size_t rows = 0;
  for (const RegisteredOptionTable &t : OptionTables())
    for (const OptionInfo &r : *t.rows) {
      INFO(r.name);
      rows++;
      CHECK(names.insert(r.name).second);
      CHECK(r.name.size() > 2);
      CHECK(r.help.size() >= 10);
      CHECK(std::string(OptionClassName(r.cls)) != "?");
      CHECK(!r.default_text.empty());
      if (r.type == OptionType::Enum) CHECK(r.choices.size() >= 2);
      char *end = nullptr;
      const double d = std::strtod(r.default_text.c_str(), &end);
      if (Numeric(r) && end && *end == '\0' && !r.only_if_set && (std::isfinite(r.bounds.lo) || std::isfinite(r.bounds.hi))) CHECK(r.bounds.Contains(d));
    }
  CHECK(rows >= 25);
  const OptionInfo *k = FindOption("-lattice_k");
  REQUIRE(k);
  CHECK(k->cls == OptionClass::Physics);
  CHECK(RangeMessage(*k, 0) == "-lattice_k must lie in [1e-6, 1e6] (a positive stiffness), got 0");
  CHECK(FindOption("-no_such_option") == nullptr);
}

TEST_CASE("option tables: each range is checked where it is read, with one line naming the option", "[options]")
{
  size_t refused = 0, accepted = 0;
  for (const RegisteredOptionTable &t : OptionTables())
    for (const OptionInfo &r : *t.rows) {
      if (!Numeric(r)) continue;
      const bool integer = r.type == OptionType::Int;
      INFO(r.name);
      PetscErrorCode code;
      std::string msg;
      // a non-finite value never passes, whatever the range
      if (!integer) {
        PCHK(ReadWith(t, r.name, "nan", &code, &msg));
        CHECK(code != 0);
        CHECK(msg.find(r.name) != std::string::npos);
        refused++;
      }
      for (int side = 0; side < 2; side++) {
        const double end = side ? r.bounds.hi : r.bounds.lo;
        const bool open = side ? r.bounds.hi_open : r.bounds.lo_open;
        if (!std::isfinite(end) || (integer && std::abs(end) >= PETSC_MAX_INT)) continue;
        const double step = integer ? 1 : 0.5 * std::max(std::abs(end), 1e-3);
        const double outside = open ? end : (side ? end + step : end - step);
        PCHK(ReadWith(t, r.name, Text(outside, integer), &code, &msg));
        INFO("value " << Text(outside, integer) << ": " << msg);
        CHECK(code != 0);
        CHECK(msg == RangeMessage(r, outside));
        refused++;
        if (!open) {
          PCHK(ReadWith(t, r.name, Text(end, integer), &code, &msg));
          INFO("value " << Text(end, integer) << ": " << msg);
          CHECK(code == 0);
          accepted++;
        }
      }
    }
  CHECK(refused >= 30);
  CHECK(accepted >= 10);
}

TEST_CASE("option tables: a row's class is how a resume and an overwrite compare the option", "[options]")
{
  // The names that io/run_options.cpp classed by hand before their tables declared them keep that class.
  const std::map<std::string, OptionClass> was = {
      {"-sim_progress", OptionClass::Bookkeeping},    {"-cont_verbose", OptionClass::Bookkeeping}, {"-cont_checkpoint_seconds", OptionClass::Bookkeeping},
      {"-cont_resume", OptionClass::Bookkeeping},     {"-cont_energy_max", OptionClass::Extent},   {"-cont_max_points", OptionClass::Extent},
      {"-cont_omega_max", OptionClass::Extent},       {"-cont_mcr_min", OptionClass::Extent},      {"-cont_branch", OptionClass::Extent},
      {"-sim_sample_dt", OptionClass::Extent},        {"-sim_t_final", OptionClass::Physics},      {"-cont_energy_min", OptionClass::Physics},
      {"-cont_switch", OptionClass::Physics},         {"-floquet", OptionClass::Physics},          {"-floquet_mf_nev", OptionClass::Physics},
      {"-nnm_steps_per_period", OptionClass::Physics}};
  for (const auto &w : was) {
    INFO(w.first);
    const OptionInfo *row = FindOption(w.first);
    REQUIRE(row);
    CHECK(row->cls == w.second);
  }
  // Every declared row under a compared prefix: bookkeeping never differs, the extent only for an overwrite, physics always.
  size_t compared = 0;
  for (const RegisteredOptionTable &t : OptionTables())
    for (const OptionInfo &r : *t.rows) {
      bool under = false;
      for (const std::string &p : ComponentPrefixes()) under |= r.name.compare(0, p.size(), p) == 0;
      if (!under) continue;
      INFO(r.name << " (" << OptionClassName(r.cls) << ")");
      // a resume compares -floquet* options only when it computes the multipliers
      const std::string floquet = r.name.compare(0, 8, "-floquet") == 0 && r.name != "-floquet" ? " -floquet 1" : "";
      const RunRecord file{r.name + " 0" + floquet, ""}, run{r.name + " 1" + floquet, ""};
      CHECK(FirstOptionDifference(file, run, OptionRule::Resume).empty() == (r.cls != OptionClass::Physics));
      CHECK(FirstOptionDifference(file, run, OptionRule::Overwrite).empty() == (r.cls == OptionClass::Bookkeeping));
      compared++;
    }
  CHECK(compared >= 50);
}

TEST_CASE("option tables: a real list reads its values, refuses a longer list, and the word none gives the empty list", "[options]")
{
  struct L {
    std::vector<PetscReal> v{0.3, 0.5};
  };
  OptionTable<L> t("tlist_", "a list (test)"); // not registered: no option of the tool's
  t.RealList("values", &L::v, 3, Closed(0, 1), "a test list");
  auto read = [&](const char *value, L *l, PetscErrorCode *code) {
    char buf[512];
    if (value) PCHK(PetscOptionsSetValue(NULL, "-tlist_values", value));
    PCHK(CaptureError([&]() { return t.Read(PETSC_COMM_WORLD, l); }, code, buf, sizeof buf));
    if (value) PCHK(PetscOptionsClearValue(NULL, "-tlist_values"));
  };
  PetscErrorCode code;
  L unset, two, none, upper, longer, outside;
  read(nullptr, &unset, &code);
  CHECK((code == 0 && unset.v == std::vector<PetscReal>{0.3, 0.5}));
  read("0.1,0.2", &two, &code);
  CHECK((code == 0 && two.v == std::vector<PetscReal>{0.1, 0.2}));
  read("none", &none, &code);
  CHECK((code == 0 && none.v.empty()));
  read("NONE", &upper, &code);
  CHECK((code == 0 && upper.v.empty()));
  read("0.1,0.2,0.3,0.4", &longer, &code);
  CHECK(code != 0);
  read("0.1,2", &outside, &code);
  CHECK(code != 0);
}
