#include "core/option_help.hpp"
#include "core/option_table.hpp"
#include <algorithm>

namespace nltopo {

namespace {

struct Block {
  std::string prefix, title;
  std::vector<HelpRow> rows;
};

bool g_own = false, g_collecting = false;
std::vector<Block> g_blocks;
std::vector<std::pair<std::string, std::string>> g_solvers; // prefix, kind

// Where a block's prefix stands in the study's own prefixes; -1 if not there.
int Rank(const std::string &prefix, const std::vector<std::string> &own)
{
  const std::string dashed = "-" + prefix;
  for (size_t i = 0; i < own.size(); i++)
    if (!prefix.empty() && dashed.compare(0, own[i].size(), own[i]) == 0) return (int)i;
  return -1;
}

std::string RowText(const HelpRow &r)
{
  const OptionInfo &o = *r.info;
  std::string line = "  " + o.name + " <" + (r.value.empty() ? std::string(o.type == OptionType::Bool ? "false" : "") : r.value) + ">";
  if (r.given) line += " (given)";
  line += "\n      " + o.help;
  if (!o.choices.empty()) {
    std::string c;
    for (const std::string &x : o.choices) c += (c.empty() ? "" : ", ") + x;
    line += " {" + c + "}";
  }
  if (!o.default_text.empty()) line += " [default: " + o.default_text + "]";
  return line + "\n";
}

} // namespace

void SetOwnHelp(bool on) { g_own = on; }
bool OwnHelp() { return g_own; }
void StartHelpCollection() { g_collecting = true; }
bool HelpCollecting() { return g_collecting; }

void NoteHelpBlock(const char *prefix, const char *title, std::vector<HelpRow> rows)
{
  for (Block &b : g_blocks)
    if (b.title == title && b.prefix == (prefix ? prefix : "")) return; // a block read twice is listed once
  g_blocks.push_back({prefix ? prefix : "", title, std::move(rows)});
}

void NoteSolverPrefix(const std::string &prefix, const std::string &kind)
{
  for (const auto &s : g_solvers)
    if (s.first == prefix) return;
  g_solvers.push_back({prefix, kind});
}

std::string HelpText(const char *study, const std::vector<std::string> &own_prefixes)
{
  std::vector<const Block *> order;
  for (const Block &b : g_blocks) order.push_back(&b);
  std::stable_sort(order.begin(), order.end(), [&](const Block *a, const Block *b) {
    const int ra = Rank(a->prefix, own_prefixes), rb = Rank(b->prefix, own_prefixes);
    return (ra < 0 ? 1000 : ra) < (rb < 0 ? 1000 : rb);
  });
  std::string o = "nltopo -study " + std::string(study) + ": its options, the study's own first, with the value this run would use\n";
  for (const Block *b : order) {
    o += "\n" + b->title + (b->prefix.empty() ? std::string() : " (-" + b->prefix + "*)") + ":\n";
    for (const HelpRow &r : b->rows) o += RowText(r);
  }
  if (!g_solvers.empty()) {
    o += "\nSolver objects (PETSc and SLEPc options under these prefixes; `-help petsc` lists them all):\n";
    for (const auto &s : g_solvers) o += "  -" + s.first + "*  (" + s.second + ")\n";
  }
  o += "\nEvery option: docs/options.md. Nothing was computed.\n";
  return o;
}

} // namespace nltopo
