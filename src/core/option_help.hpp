#pragma once
// nltopo's own -help: the selected study's options, grouped by component,
// each with the value this run would use, its default, range and help. main
// takes -help out of the arguments before PETSc starts (PETSc would print its
// generic block first), and the study's options function runs with the
// collection on: every option table it reads notes its rows here, every solver
// object it declares notes its prefix. `-help petsc` keeps PETSc's own -help,
// which lists the solver options too.
#include <string>
#include <vector>

namespace nltopo {

struct OptionInfo; // core/option_table.hpp

struct HelpRow {
  const OptionInfo *info;
  std::string value; // as this run would use it
  bool given;
};

void SetOwnHelp(bool on); // main: -help without "petsc"
bool OwnHelp();
// While collecting, OptionTable::Read and the Declare* solver functions note what they read.
void StartHelpCollection();
bool HelpCollecting();
void NoteHelpBlock(const char *prefix, const char *title, std::vector<HelpRow> rows);
void NoteSolverPrefix(const std::string &prefix, const std::string &kind); // prefix: "sim_ts_"
// The collected options: the blocks under the study's own prefixes first, then
// the components' blocks in the order the study read them, then the solver prefixes.
std::string HelpText(const char *study, const std::vector<std::string> &own_prefixes);

} // namespace nltopo
