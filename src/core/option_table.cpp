#include "core/option_table.hpp"
#include <algorithm>
#include <cstdio>
#include <strings.h>

namespace nltopo {

const char *OptionClassName(OptionClass c)
{
  switch (c) {
  case OptionClass::Physics: return "physics";
  case OptionClass::Extent: return "extent";
  case OptionClass::Bookkeeping: return "bookkeeping";
  }
  return "?";
}

const char *OptionTypeName(OptionType t)
{
  switch (t) {
  case OptionType::Real: return "real";
  case OptionType::Int: return "int";
  case OptionType::Bool: return "bool";
  case OptionType::Enum: return "enum";
  case OptionType::String: return "string";
  case OptionType::RealList: return "real list";
  case OptionType::StringList: return "string list";
  }
  return "?";
}

// %g without the padded exponent: 1e-06 -> 1e-6, 1e+06 -> 1e6.
std::string OptionNumberText(double x, bool integer)
{
  if (std::isinf(x)) return x > 0 ? "inf" : "-inf";
  char buf[64];
  const double k = x != 0 ? std::round(std::log10(std::abs(x))) : 0;
  if (!integer && std::abs(k) >= 3 && std::abs(x) == std::pow(10.0, k)) { // 1e3, not 1000
    std::snprintf(buf, sizeof buf, "%se%d", x < 0 ? "-1" : "1", (int)k);
    return buf;
  }
  if (integer && std::abs(x) < 1e15) std::snprintf(buf, sizeof buf, "%lld", (long long)x);
  else std::snprintf(buf, sizeof buf, "%g", x);
  std::string s = buf;
  const size_t e = s.find('e');
  if (e == std::string::npos) return s;
  std::string mant = s.substr(0, e), exp = s.substr(e + 1);
  const bool neg = exp[0] == '-';
  size_t i = (exp[0] == '-' || exp[0] == '+') ? 1 : 0;
  while (i + 1 < exp.size() && exp[i] == '0') i++;
  return mant + "e" + (neg ? "-" : "") + exp.substr(i);
}

std::string Bounds::Text(bool integer) const
{
  if (integer && !lo_open && !hi_open && std::isfinite(lo) && std::isfinite(hi)) return OptionNumberText(lo, true) + ".." + OptionNumberText(hi, true);
  return std::string(lo_open ? "(" : "[") + OptionNumberText(lo, integer) + ", " + OptionNumberText(hi, integer) + (hi_open ? ")" : "]");
}

static std::vector<RegisteredOptionTable> &Tables()
{
  static std::vector<RegisteredOptionTable> t;
  return t;
}

const std::vector<RegisteredOptionTable> &OptionTables() { return Tables(); }

void RegisterOptionTable(const char *title, const std::vector<OptionInfo> *rows, std::function<PetscErrorCode(MPI_Comm)> read_defaults)
{
  for (const auto &t : Tables())
    if (t.rows == rows) return;
  Tables().push_back({title ? title : "", rows, std::move(read_defaults)});
}

const OptionInfo *FindOption(const std::string &name)
{
  for (const auto &t : Tables())
    for (const OptionInfo &r : *t.rows)
      if (!strcasecmp(r.name.c_str(), name.c_str())) return &r; // PETSc's names are case-insensitive
  return nullptr;
}

static std::vector<std::string> &Prefixes()
{
  static std::vector<std::string> p;
  return p;
}

void RegisterComponentPrefixes(const std::vector<std::string> &prefixes)
{
  for (const std::string &p : prefixes)
    if (std::find(Prefixes().begin(), Prefixes().end(), p) == Prefixes().end()) Prefixes().push_back(p);
}

const std::vector<std::string> &ComponentPrefixes() { return Prefixes(); }

std::string RangeMessage(const OptionInfo &row, double value)
{
  const bool integer = row.type == OptionType::Int;
  std::string m = row.name + " must lie in " + row.bounds.Text(integer);
  if (!row.why.empty()) m += " (" + row.why + ")";
  return m + ", got " + OptionNumberText(value, integer);
}

} // namespace nltopo
