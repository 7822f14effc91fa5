#include "core/ts_traits.hpp"
#include <cstring>
#include <utility>
#include <vector>

namespace nltopo {

namespace {

// clang-format off
// PETSc 3.18's types that run nltopo's problems (irk with a preconditioner
// other than ilu, -sim_pc_type none). Not here: glee (its default adaptivity
// rejects the first step; most schemes have no interpolant), glle (no
// interpolant), mimex (crashes), mprk (needs "slow"/"fast" splits), alpha2
// (second-order implicit form), pseudo, discgrad, radau5, sundials.
// Interpolants: euler, basicsymplectic, the theta family and alpha are linear
// in t; rk reuses its weights (linear) except 5dp; bdf's is of its order (1 at
// the least); eimex's is cubic Hermite; arkimex, rosw and irk have one only
// for some schemes, ssp none.
std::vector<TSTraits> &Rows()
{
  static std::vector<TSTraits> rows = {
    //  type             family             explicit rollback fixed  pos.only accel  split interp scheme getter
    {TSRK,              "rk",              true,    true,    false, false,   false, false, 1, "TSRKGetType_C"},
    {TSEULER,           nullptr,           true,    false,   false, false,   false, false, 1, nullptr},
    {TSSSP,             "ssp",             true,    false,   false, false,   false, false, 0, "TSSSPGetType_C"},
    {TSBASICSYMPLECTIC, "basicsymplectic", true,    false,   true,  true,    false, true,  1, "TSBasicSymplecticGetType_C"},
    {TSBEULER,          "theta",           false,   true,    false, false,   false, false, 1, nullptr},
    {TSCN,              "theta",           false,   true,    false, false,   false, false, 1, nullptr},
    {TSTHETA,           "theta",           false,   true,    false, false,   false, false, 1, nullptr},
    {TSALPHA,           "alpha",           false,   true,    false, false,   false, false, 1, nullptr},
    {TSBDF,             "bdf",             false,   true,    false, false,   false, false, 1, nullptr},
    {TSARKIMEX,         "arkimex",         false,   true,    false, false,   false, false, 0, "TSARKIMEXGetType_C"},
    {TSROSW,            "rosw",            false,   true,    false, false,   false, false, 0, "TSRosWGetType_C"},
    {TSIRK,             "irk",             false,   true,    false, false,   false, false, 0, "TSIRKGetType_C"},
    {TSEIMEX,           "eimex",           false,   false,   false, false,   false, false, 3, nullptr},
  };
  return rows;
}
// clang-format on

// The defaults of -<prefix>ts_type: the forced runs' rk (5dp, rtol = atol =
// 1e-8, timeint/simulation.cpp); the shooting's symsplit (bm4, 128 steps per
// period, orbits/flow.cpp: the measured best, benchmarks/README.md). The
// literal, as core cannot include timeint/ts_symsplit.hpp's TSSYMSPLIT.
const std::pair<const char *, const char *> kDefaultTypes[] = {{"sim_", TSRK}, {"nnm_", "symsplit"}};

} // namespace

const TSTraits *TSTraitsFind(const char *type)
{
  if (!type) return nullptr;
  for (const TSTraits &r : Rows())
    if (!std::strcmp(r.type, type)) return &r;
  return nullptr;
}

void TSTraitsRegister(const TSTraits &row)
{
  for (TSTraits &r : Rows())
    if (!std::strcmp(r.type, row.type)) {
      r = row;
      return;
    }
  Rows().push_back(row);
}

size_t TSTraitsCount() { return Rows().size(); }

const TSTraits &TSTraitsAt(size_t i) { return Rows()[i]; }

std::string TSTraitsNames()
{
  std::string s;
  for (const TSTraits &r : Rows()) s += (s.empty() ? "" : ", ") + std::string(r.type);
  return s;
}

PetscErrorCode TSGetTraits(TS ts, const TSTraits **traits)
{
  TSType type;
  const char *prefix;
  PetscFunctionBeginUser;
  PetscCall(TSGetType(ts, &type));
  PetscCall(TSGetOptionsPrefix(ts, &prefix));
  *traits = TSTraitsFind(type);
  PetscCheck(*traits, PetscObjectComm((PetscObject)ts), PETSC_ERR_USER, "-%sts_type %s: not in nltopo's integrator table (%s)", prefix ? prefix : "",
             type ? type : "(none)", TSTraitsNames().c_str());
  PetscFunctionReturn(0);
}

PetscErrorCode TSGetSchemeName(TS ts, std::string *scheme)
{
  const TSTraits *tr;
  PetscFunctionBeginUser;
  scheme->clear();
  PetscCall(TSGetTraits(ts, &tr));
  if (!tr->scheme_getter) PetscFunctionReturn(0);
  PetscErrorCode (*get)(TS, const char **) = nullptr;
  PetscCall(PetscObjectQueryFunction((PetscObject)ts, tr->scheme_getter, &get));
  PetscCheck(get, PetscObjectComm((PetscObject)ts), PETSC_ERR_PLIB, "TS type %s composes no %s", tr->type, tr->scheme_getter);
  const char *name = nullptr;
  PetscCall(get(ts, &name));
  if (name) *scheme = name;
  PetscFunctionReturn(0);
}

PetscErrorCode TSGetIntegratorName(TS ts, std::string *name)
{
  TSType type;
  std::string scheme;
  PetscFunctionBeginUser;
  PetscCall(TSGetType(ts, &type));
  PetscCall(TSGetSchemeName(ts, &scheme));
  *name = scheme.empty() ? std::string(type) : std::string(type) + " " + scheme;
  PetscFunctionReturn(0);
}

const char *TSDefaultType(const char *prefix)
{
  for (const auto &d : kDefaultTypes)
    if (prefix && !std::strcmp(d.first, prefix)) return d.second;
  return nullptr;
}

} // namespace nltopo
