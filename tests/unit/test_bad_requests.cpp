// Requests nltopo cannot honour as asked (issue 34, class 8 and 13b, 13c), in-process
// as test_bad_options.cpp: each is refused with one line naming the request
// and the real cause, instead of being replaced by another value, computed
// twice, or blamed on the wrong option; at 1 and 2 ranks (unit_np1, unit_np2).
#include "bad_options.hpp"
#include <regex>

using namespace nltopo;
using namespace nltopo::test;

namespace {

struct BadRequest {
  std::string pattern, args;
};

const std::string kContinuation = "-study continuation -lattice_cells 5 -cont_energy_max 1e-4 -cont_max_points 2 -cont_verbose 0 ";

const std::vector<BadRequest> &Requests()
{
  static const std::vector<BadRequest> cases = {
      // class 8: a value outside the valid range, refused instead of replaced
      {"-stability_omega 1.5: below the insulated branch, which starts at its linear frequency 1.73205081",
       "-study stability -lattice_cells 5 -stability_omega 1.75,1.5 -stability_periods 2 -stability_sample_periods 1"},
      {"-cont_omega_max is set by -study stability", "-study stability -lattice_cells 5 -stability_omega 1.75 -cont_omega_max 3"},
      {"-cont_energy_max is set by -study perturb", "-study perturb -lattice_cells 5 -perturb_energy_list 1e-3 -cont_energy_max 1"},
      {"-cont_energy_max is set by -study workprecision -wp_scene shooting", "-study workprecision -wp_scene shooting -lattice_cells 5 -cont_energy_max 1"},
      {"E\\* = 1e-07 lies below the insulated branch's first orbit (E = 1e-05, -cont_energy_min)",
       "-study perturb -lattice_cells 5 -perturb_energy_list 1e-7,1e-3"},
      {"-force_mode_index 3: linear mode indices count all N = 22 modes, but N > -linear_dense_max 10",
       "-study simulate -lattice_cells 5 -linear_dense_max 10 -force_profile mode -force_mode_index 3 -sim_t_final 5"},
      {"-cont_branch mode3: linear mode indices count all N = 22 modes", kContinuation + "-linear_dense_max 10 -cont_branch mode3"},
      // 13b: a branch listed twice
      {"-cont_branch: insulated is listed twice", kContinuation + "-cont_branch insulated,interface,insulated"},
      {"-cont_branch: 3 (as mode3 too) is listed twice", kContinuation + "-cont_branch 3,mode3"},
      {"-cont_branch: interface and mode21 are the same linear mode (mode21)", kContinuation + "-cont_branch interface,mode21"},
      // 13c: no insulated mode, and why
      {"no insulated mode: -lattice_cells 2 is too few cells for the insulated mode to form at -lattice_gamma 0.4", kContinuation + "-lattice_cells 2"},
      {"no insulated mode: -lattice_gamma 0 closes the gap", kContinuation + "-lattice_gamma 0"},
      {"no insulated mode: -lattice_layout left has no interface", kContinuation + "-lattice_layout left"},
      {"-study stability follows the insulated branch, and this lattice has no insulated mode: -lattice_cells 1 is too few cells",
       "-study stability -lattice_cells 1"},
      {"-force_profile exponential fits the insulated mode, and this lattice has none: -lattice_gamma 0 closes the gap",
       "-study simulate -lattice_cells 5 -lattice_gamma 0 -force_profile exponential -sim_t_final 5"},
  };
  return cases;
}

} // namespace

TEST_CASE("requests out of range, twice or without an insulated mode: refused in-process with one line naming the cause", "[options]")
{
  const std::string dir = SharedTempDir();
  REQUIRE(!dir.empty());
  for (const BadRequest &c : Requests()) {
    const Refusal r = RunRefused(SplitArgs(c.args), dir);
    int lines = 0, all_lines = 0, failed = r.code ? 1 : 0, all_failed = 0, files = (int)r.files.size(), max_files = 0;
    for (char ch : r.err) lines += ch == '\n';
    MPI_Allreduce(&lines, &all_lines, 1, MPI_INT, MPI_SUM, PETSC_COMM_WORLD);
    MPI_Allreduce(&failed, &all_failed, 1, MPI_INT, MPI_MIN, PETSC_COMM_WORLD);
    MPI_Allreduce(&files, &max_files, 1, MPI_INT, MPI_MAX, PETSC_COMM_WORLD);
    char text[2048] = "";
    if (!Rank()) PCHK(PetscStrncpy(text, r.err.c_str(), sizeof(text)));
    MPI_Bcast(text, sizeof(text), MPI_CHAR, 0, PETSC_COMM_WORLD);
    INFO("nltopo " << c.args << "\nprinted: " << text);
    CHECK(all_failed == 1);
    CHECK(all_lines == 1);
    CHECK(std::regex_search(text, std::regex(c.pattern, std::regex::basic)));
    CHECK(max_files == 0);
    for (const std::string &f : r.files) std::remove((dir + "/" + f).c_str());
  }
  MPI_Barrier(PETSC_COMM_WORLD);
  if (!Rank()) rmdir(dir.c_str());
}
