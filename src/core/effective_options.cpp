#include "core/effective_options.hpp"
#include <cctype>
#include <map>

namespace nltopo {

static std::map<std::string, std::string> &Notes()
{
  static std::map<std::string, std::string> notes;
  return notes;
}

static int g_paused = 0;
EffectiveOptionsPause::EffectiveOptionsPause() { g_paused++; }
EffectiveOptionsPause::~EffectiveOptionsPause() { g_paused--; }

void NoteEffectiveOption(const std::string &name, const std::string &value)
{
  if (g_paused) return;
  std::string key = name;
  for (char &c : key) c = (char)std::tolower((unsigned char)c); // PETSc's option names are case-insensitive
  Notes()[key] = value;
}

std::string EffectiveOptionsText()
{
  std::string s;
  for (const auto &kv : Notes()) {
    std::string v = kv.second;
    for (char &c : v)
      if (c == '\n') c = ' '; // one line per option
    s += kv.first + (v.empty() ? "" : " " + v) + "\n";
  }
  return s;
}

void ClearEffectiveOptions() { Notes().clear(); }

} // namespace nltopo
