#include "core/option_reference.hpp"
#include "core/option_table.hpp"
#include <algorithm>
#include <cmath>
#include <vector>
#include <cstdio>

namespace nltopo {

namespace {

std::string JsonString(const std::string &s)
{
  std::string o = "\"";
  for (char c : s) {
    if (c == '"' || c == '\\') o += '\\', o += c;
    else if (c == '\n') o += "\\n";
    else if ((unsigned char)c < 0x20) {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\u%04x", c);
      o += buf;
    } else o += c;
  }
  return o + "\"";
}

std::string JsonNumber(double x)
{
  if (!std::isfinite(x)) return "null"; // an open-ended range
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.17g", x);
  return buf;
}

bool Numeric(const OptionInfo &r) { return r.type == OptionType::Real || r.type == OptionType::Int || r.type == OptionType::RealList; }

std::string RangeText(const OptionInfo &r)
{
  if (!r.choices.empty()) {
    std::string t;
    for (const std::string &c : r.choices) t += (t.empty() ? "" : ", ") + c;
    return t;
  }
  if (!Numeric(r) || (!std::isfinite(r.bounds.lo) && !std::isfinite(r.bounds.hi))) return "";
  return r.bounds.Text(r.type == OptionType::Int);
}

// A cell of a Markdown table: no line breaks, no bare pipes.
std::string Cell(const std::string &s)
{
  std::string o;
  for (char c : s) o += c == '|' ? std::string("\\|") : c == '\n' ? std::string(" ") : std::string(1, c);
  return o;
}

} // namespace

std::string OptionReferenceJson()
{
  std::string o = "[\n";
  bool first = true;
  for (const RegisteredOptionTable &t : OptionTables())
    for (const OptionInfo &r : *t.rows) {
      o += first ? "  {" : ",\n  {";
      first = false;
      o += "\"name\": " + JsonString(r.name) + ", \"table\": " + JsonString(t.title) + ", \"type\": " + JsonString(OptionTypeName(r.type));
      if (Numeric(r))
        o += ", \"min\": " + JsonNumber(r.bounds.lo) + ", \"max\": " + JsonNumber(r.bounds.hi) + ", \"min_open\": " + (r.bounds.lo_open ? "true" : "false") +
             ", \"max_open\": " + (r.bounds.hi_open ? "true" : "false");
      if (!r.choices.empty()) {
        o += ", \"choices\": [";
        for (size_t k = 0; k < r.choices.size(); k++) o += (k ? ", " : "") + JsonString(r.choices[k]);
        o += "]";
      }
      o += ", \"default\": " + JsonString(r.default_text) + ", \"class\": " + JsonString(OptionClassName(r.cls)) +
           ", \"only_if_set\": " + (r.only_if_set ? "true" : "false") + ", \"help\": " + JsonString(r.help) + ", \"why\": " + JsonString(r.why) + "}";
    }
  return o + "\n]\n";
}

std::string OptionReferenceMarkdown()
{
  std::string o = "# Options reference\n\n"
                  "Generated from the option tables in the code (`nltopo -option_tables md > docs/options.md`; a test\n"
                  "checks that this file is what the binary writes). Every option of nltopo's own, by component:\n"
                  "its type, default, range and class. The class says what a resume or an overwrite compares\n"
                  "(docs/errors.md, \"Resume rules\"): *physics* (physics and numerics: must agree), *extent*\n"
                  "(how far a run goes: may grow on resume), *bookkeeping* (never compared). Solver options\n"
                  "(`-sim_ts_*`, `-nnm_snes_*`, `-floquet_eps_*`, ...) are PETSc's and SLEPc's: `-help` lists them.\n"
                  "A *real list* is comma-separated; the word `none` gives the empty list (e.g. to clear on the\n"
                  "command line a list an options file sets).\n";
  // by title, then by first option (registration order follows the link order)
  std::vector<const RegisteredOptionTable *> tables;
  for (const RegisteredOptionTable &t : OptionTables())
    if (!t.rows->empty()) tables.push_back(&t);
  std::stable_sort(tables.begin(), tables.end(),
                   [](const RegisteredOptionTable *a, const RegisteredOptionTable *b) { return a->rows->front().name < b->rows->front().name; });
  std::stable_sort(tables.begin(), tables.end(), [](const RegisteredOptionTable *a, const RegisteredOptionTable *b) { return a->title < b->title; });
  const std::string *last = nullptr;
  for (const RegisteredOptionTable *tp : tables) {
    const RegisteredOptionTable &t = *tp;
    if (!last || *last != t.title) // tables that share a title (one -help block) share a section
      o += std::string("\n## ") + Cell(t.title) + "\n\n| option | type | default | range | class | meaning |\n|---|---|---|---|---|---|\n";
    last = &t.title;
    for (const OptionInfo &r : *t.rows) {
      std::string help = r.help;
      const std::string range = "; in " + RangeText(r); // OptionTable appends it for -help; here it has its column
      if (help.size() > range.size() && help.compare(help.size() - range.size(), range.size(), range) == 0) help.resize(help.size() - range.size());
      if (!r.why.empty()) help += " (range: " + r.why + ")";
      o += "| `" + r.name + "` | " + OptionTypeName(r.type) + " | " + Cell(r.default_text.empty() ? "(none)" : r.default_text) + " | " + Cell(RangeText(r)) +
           " | " + OptionClassName(r.cls) + " | " + Cell(help) + " |\n";
    }
  }
  return o;
}

} // namespace nltopo
