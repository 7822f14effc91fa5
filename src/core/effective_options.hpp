#pragma once
// The effective value of every option a run read, defaults included: each
// option table's Read notes its rows' values (core/option_table.hpp), and the
// time integrators their type where the code chooses it (core/ts_traits.hpp
// TSDefaultType). The output's provenance records them (root attribute
// effective_options, io/output.cpp), so that a resume or an overwrite compares
// what the runs used, not only what they were given (io/run_options.hpp): a
// changed code default is caught.
#include <string>

namespace nltopo {

// Notes an option's effective value ("-lattice_k", "1"); the last note wins.
void NoteEffectiveOption(const std::string &name, const std::string &value);
// The notes as text, one "-name value" per line, in name order ("" if none).
std::string EffectiveOptionsText();
// Forgets every note (a test that runs several configurations in one process).
void ClearEffectiveOptions();
// While alive, notes are ignored: the option audit reads every study's
// options to learn their names (core/options_audit.cpp), which this run does
// not use.
class EffectiveOptionsPause {
public:
  EffectiveOptionsPause();
  ~EffectiveOptionsPause();
  EffectiveOptionsPause(const EffectiveOptionsPause &) = delete;
  EffectiveOptionsPause &operator=(const EffectiveOptionsPause &) = delete;
};

} // namespace nltopo
