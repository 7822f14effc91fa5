// Bad options, in-process (docs/errors.md "The error contract"): each command line below
// runs the driver's code path (RunStudyFromOptions on PETSC_COMM_WORLD, the
// one-line error handler) and must fail with exactly one line on stderr (all
// ranks together) that names the option or value, no source path in it, and
// neither the output file nor a temporary left behind. The path is collective
// (every rank reads and checks the options; the audit of unused options
// reduces over ranks), so these run at 1 and 2 ranks (unit_np1, unit_np2).
//
// They replace, one for one, the cases of tests/scenes/bad_input.sh that die
// in option checking: before any work (the option readers, the range checks,
// the audit of misspelt, foreign and type-mismatched options, the value
// shapes), or in the checks a study makes of its options at the start of its
// run (a conservative lattice, a fixed-step integrator, the linear_gamma_list
// size). The table below is that list: each row was an
//   expect_error "<pattern>" o.h5 <command line>
// line of bad_input.sh, with the same pattern (a basic regular expression, as
// grep's) and the same command line ($S, $C, $W, $P, $L as there).
// bad_input.sh keeps what needs a process: argv preflight (-options_file),
// files (-output, -cont_resume, -perturb_fep, -sweep_resume), runs that fail
// after work (the end-of-run audit, -cont_switch events, a diverging run) and
// the write faults.
#include "bad_options.hpp"
#include <regex>

using namespace nltopo;
using namespace nltopo::test;

namespace {

const std::string S = "-study simulate -sim_t_final 5 ";
const std::string C = "-study continuation -lattice_cells 5 -cont_energy_max 1e-4 -cont_max_points 3 -cont_verbose 0 ";
const std::string W = "-study sweep -sweep_omega_n 2 -sweep_energy_n 1 -sim_t_final 20 ";
const std::string P = "-study workprecision -sim_t_final 5 -wp_twins 1 -wp_repeats 1 ";
const std::string L = "-study linear -lattice_cells 5 ";

struct BadCase {
  std::string pattern, args;
};

// pattern | command line (the rows in the order of bad_input.sh)
const std::vector<BadCase> &OptionCases()
{
  static const std::vector<BadCase> cases = {
      // -study workprecision: configurations hold integrator options only
      {"-lattice_k is not an integrator option", P + "-wp_configs ' -sim_ts_type rk -lattice_k 2'"},
      {"-wp_configs has no value", P + "-wp_configs '-sim_ts_type rk'"},
      {"-wp_repeats", P + "-wp_repeats 0"},
      {"leave out -sim_ts_rtol", P + "-wp_reference ' -sim_ts_type rkn -sim_ts_rtol 1e-9'"},
      {"-sweep_mcr_tol needs a fixed-step integrator", W + "-sweep_mcr_tol 1e-3 -sim_ts_type rk"},
      {"-sweep_mcr_tol", W + "-sweep_mcr_tol 2"},
      // the study and the lattice
      {"unknown -study nope", "-study nope"},
      {"-lattice_cells", "-study linear -lattice_cells 0"},
      {"-lattice_k", "-study linear -lattice_k -1"},
      {"-lattice_gamma0", S + "-lattice_gamma0 -0.5"},
      {"-lattice_gamma ", "-study linear -lattice_gamma 1.2"},
      {"-force_energy", S + "-force_energy -1"},
      // damping: refused by the studies that need a conservative lattice and by the integrators of u'' = a(t, u)
      {"-lattice_damping must lie in", S + "-lattice_damping -1"},
      {"-study continuation needs a conservative lattice; -lattice_damping 0.1 adds", C + "-lattice_damping 0.1"},
      {"-study linear (the normal modes of K) needs a conservative lattice; -lattice_damping 0.1", L + "-lattice_damping 0.1"},
      {"-study stability needs a conservative lattice; -lattice_damping 0.2", "-study stability -lattice_cells 5 -lattice_damping 0.2"},
      {"-sim_ts_type rkn integrates u'' = a(t, u); -lattice_damping 0.1", S + "-lattice_damping 0.1 -sim_ts_type rkn"},
      {"-sim_ts_type symsplit integrates u'' = a(t, u); -lattice_damping 0.1", S + "-lattice_damping 0.1 -sim_ts_type symsplit -sim_ts_dt 0.1"},
      {"-lattice_layout", "-study linear -lattice_layout sideways"},
      {"-force_profile", S + "-force_profile sideways"},
      // misspelt, foreign and type-mismatched options: the closest known option is named
      {"did you mean -force_omega?", S + "-force_omgea 2.0"},
      {"did you mean -sim_t_final?", S + "-sim_tfinal 3"},
      {"-sweep_omega_n 3: not an option of -study simulate (it belongs to -study sweep)", S + "-sweep_omega_n 3"},
      {"-nnm_orbit_rtol 0.1: not an option of -study simulate", S + "-nnm_orbit_rtol 0.1"},
      {"-sim_ts_rk_type 5dp: not used by this run (-sim_ts_type is symsplit; the option belongs to -sim_ts_type rk)",
       W + "-sim_ts_type symsplit -sim_ts_dt 0.1 -sim_ts_rk_type 5dp"},
      {"-nnm_ts_rk_type 5dp: not used by this run (-nnm_ts_type is symsplit, the default; the option belongs to -nnm_ts_type rk)", C + "-nnm_ts_rk_type 5dp"},
      {"-nnm_monodromy tsforward needs -nnm_ts_type rk (forward sensitivities); the default -nnm_ts_type is symsplit, whose tangent map is its own",
       C + "-nnm_monodromy tsforward"},
      // options a study sets itself are refused, not read and overwritten
      {"-sim_progress is set by -study sweep", W + "-sim_progress 1"},
      {"-sim_sample_dt is set by -study zak", "-study zak -zak_energy_list 0.01 -sim_t_final 300 -lattice_cells 4 -sim_sample_dt 0.5"},
      {"-sim_t_final is set by -study stability", "-study stability -lattice_cells 5 -sim_t_final 10"},
      {"-sim_progress is set by -study perturb", "-study perturb -lattice_cells 5 -sim_progress 1"},
      {"-force_omega is set by", W + "-force_omega 2"},
      // values: garbage, NaN, inf, wrong types
      {"-force_omega abc: not a real number", S + "-force_omega abc"},
      {"-lattice_cells 2.5: not an integer", "-study linear -lattice_cells 2.5"},
      {"-sim_store_u maybe: not a boolean", S + "-sim_store_u maybe"},
      {"-sim_ts_type foo", S + "-sim_ts_type foo"},
      {"-kcorr_record must lie in (0, 1e6], got inf", W + "-sweep_kcorr -kcorr_record inf"},
      {"-floquet_tol must lie in (0, 1), got inf", C + "-floquet -floquet_tol inf"},
      {"-sim_t_final must lie in \\[1e-6, 1e9\\], got nan", "-study simulate -sim_t_final nan"},
      {"-force_omega must lie in \\[1e-6, 1e3\\], got -inf", S + "-force_omega -inf"},
      {"-sweep_energy_list must lie in \\[1e-12, 1e12\\], got nan", W + "-sweep_energy_list 1,nan"},
      {"-sim_ts_rtol 1e999: the value must be a finite number", S + "-sim_ts_rtol 1e999"},
      {"-linear_bv_orthog_eta inf: the value must be a finite number", L + "-linear_bv_orthog_eta inf"},
      // values PETSc would silently drop or wrap: a missing value, an integer beyond 32 bits
      {"-lattice_k: no value given", L + "-lattice_k ''"},
      {"-perturb_delta_list: no value given", "-study perturb -lattice_cells 5 -perturb_delta_list"},
      {"-lattice_cells 4294967301: out of the integer range", "-study linear -lattice_cells 4294967301"},
      {"-sim_ts_max_steps 99999999999: out of the integer range", S + "-sim_ts_max_steps 99999999999"},
      // ranges
      {"-linear_nq", L + "-linear_nq 2"},
      // -linear_gamma_list min:max:n (the topological transition)
      {"-linear_gamma_list 0.5:1: expected min:max:n", L + "-linear_gamma_list 0.5:1"},
      {"-linear_gamma_list abc: expected min:max:n", L + "-linear_gamma_list abc"},
      {"-linear_gamma_list -1:1:2.5: expected min:max:n", L + "-linear_gamma_list -1:1:2.5"},
      {"-linear_gamma_list -1:1:1: n must lie in \\[2, 100000\\]", L + "-linear_gamma_list -1:1:1"},
      {"-linear_gamma_list -1.5:1:5: min and max must satisfy -1 <= min < max <= 1", L + "-linear_gamma_list -1.5:1:5"},
      {"-linear_gamma_list 0.5:0.5:3: min and max must satisfy", L + "-linear_gamma_list 0.5:0.5:3"},
      {"-linear_gamma_list nan:1:3: min and max must satisfy", L + "-linear_gamma_list nan:1:3"},
      {"-linear_gamma_list -1:1:3 needs all N eigenfrequencies: N = 22 exceeds -linear_dense_max 10", L + "-linear_dense_max 10 -linear_gamma_list -1:1:3"},
      {"-linear_gamma_list -1:1:3: not an option of -study simulate (it belongs to -study linear)", S + "-linear_gamma_list -1:1:3"},
      {"-kcorr_nc", W + "-sweep_kcorr -kcorr_nc 0"},
      {"-zak_theta_tol", "-study zak -zak_energy_list 0.01 -sim_t_final 300 -lattice_cells 4 -zak_theta_tol 4"},
      {"-stability_periods", "-study stability -lattice_cells 5 -stability_periods 0"},
      {"-cont_checkpoint_seconds", C + "-cont_checkpoint_seconds -1"},
      {"-cont_bifurcations needs -floquet without -floquet_mf", C + "-cont_bifurcations"},
      {"-cont_bifurcations needs -floquet without -floquet_mf", C + "-floquet -floquet_mf -cont_bifurcations 1"},
      {"-floquet_mf_dense_max must lie in 0\\.\\.20000, got -1", C + "-floquet -floquet_mf -floquet_mf_dense_max -1"},
      {"-cont_bif_tol must lie in \\[1e-14, 0\\.01\\], got 0.", C + "-floquet -cont_bif_tol 0"},
      {"-cont_bif_angle_tol must lie in (0, 1), got 2.", C + "-floquet -cont_bif_angle_tol 2"},
      {"-cont_bif_resonance_order must lie in 0\\.\\.12, got 13", C + "-floquet -cont_bif_resonance_order 13"},
      {"-cont_switch insulated: expected <branch>:<event index>", C + "-floquet -cont_switch insulated"},
      {"-cont_switch insulated:x: expected <branch>:<event index>", C + "-floquet -cont_switch insulated:x"},
      {"-cont_switch needs -cont_bifurcations", C + "-cont_switch insulated:0"},
      {"-cont_switch optical_top:0: no branch optical_top among -cont_branch", C + "-floquet -cont_switch optical_top:0"},
      {"-cont_switch_step must lie in (0, 1), got 0.", C + "-floquet -cont_switch_step 0"},
      {"-cont_switch insulated:3: given twice", C + "-floquet -cont_switch insulated:3,insulated:3"},
      // a switched family's events: only that of another -cont_switch (a period doubling's family has no _plus/_minus)
      {"-cont_switch insulated_bp3_plus:2: no branch insulated_bp3_plus among -cont_branch or the families of the other -cont_switch events",
       C + "-floquet -cont_switch insulated_bp3_plus:2"},
      {"-cont_switch insulated_pd3_minus:1: no branch insulated_pd3_minus among", C + "-floquet -cont_switch insulated:3,insulated_pd3_minus:1"},
      {"-sim_store_u_stride", S + "-sim_store_u_stride 0"},
      {"-nnm_mf_pc_parametric_weight must lie in (0, 1\\], got 0",
       "-study continuation -lattice_cells 5 -nnm_jacobian mf -nnm_mf_pc parametric -nnm_mf_pc_parametric_weight 0"},
      {"-nnm_orbit_rtol must lie in \\[0, 1), got -1", "-study continuation -lattice_cells 5 -nnm_orbit_rtol -1"},
      // resource guard: the estimate is named before anything is allocated
      {"-lattice_cells must lie in 1..2500000, got 20000000", "-study simulate -lattice_cells 20000000 -sim_t_final 1000"},
      {"-linear_dense_max must lie in 0\\.\\.10000 (the dense path holds N x N.*), got 1000000",
       "-study linear -lattice_cells 40000 -linear_dense_max 1000000"},
      {"-sim_store_u: .* more than 2.5e8 values", "-study simulate -lattice_cells 100000 -sim_store_u -sim_sample_dt 0.01 -sim_t_final 1000"},
  };
  return cases;
}

} // namespace

// The contract for one refused run (all ranks together): it failed, with
// exactly one line matching pattern and no source path, and left no file.
static void CheckRefusal(const Refusal &r, const BadCase &c, const std::string &dir)
{
  const std::regex source_path("\\.c:[0-9]", std::regex::basic);
  // rank 0 prints the line of a collective error: its text, and the line count of all ranks
  int lines = 0, all_lines = 0, failed = r.code ? 1 : 0, all_failed = 0, files = (int)r.files.size(), max_files = 0, output = 0, any_output = 0;
  for (const std::string &f : r.files) output += f == "o.h5";
  MPI_Allreduce(&output, &any_output, 1, MPI_INT, MPI_MAX, PETSC_COMM_WORLD);
  for (char ch : r.err) lines += ch == '\n';
  MPI_Allreduce(&lines, &all_lines, 1, MPI_INT, MPI_SUM, PETSC_COMM_WORLD);
  MPI_Allreduce(&failed, &all_failed, 1, MPI_INT, MPI_MIN, PETSC_COMM_WORLD);
  MPI_Allreduce(&files, &max_files, 1, MPI_INT, MPI_MAX, PETSC_COMM_WORLD);
  char text[2048] = "";
  if (!Rank()) PCHK(PetscStrncpy(text, r.err.c_str(), sizeof(text)));
  MPI_Bcast(text, sizeof(text), MPI_CHAR, 0, PETSC_COMM_WORLD);
  std::string left;
  for (const std::string &f : r.files) left += f + " ";
  INFO("nltopo " << c.args << "\nprinted: " << text << "left: " << left);
  CHECK(all_failed == 1);
  CHECK(all_lines == 1);
  CHECK(std::regex_search(text, std::regex(c.pattern, std::regex::basic)));
  CHECK(!std::regex_search(text, source_path));
  CHECK(any_output == 0);
  CHECK(max_files == 0); // nor a temporary or journal
  for (const std::string &f : r.files) std::remove((dir + "/" + f).c_str());
}

TEST_CASE("bad options: each refused in-process with one line naming it, no output and no temporary left", "[options]")
{
  const std::string dir = SharedTempDir();
  REQUIRE(!dir.empty());
  for (const BadCase &c : OptionCases()) CheckRefusal(RunRefused(SplitArgs(c.args), dir), c, dir);
  MPI_Barrier(PETSC_COMM_WORLD);
  if (!Rank()) rmdir(dir.c_str());
}

// Options that nothing in the run reads (neither nltopo's tables, nor the
// study's solver objects, nor PETSc itself) and the resource guards the
// options decide are refused before any set-up: no study enters its Setup
// stage, and a large scene is refused as fast as a 5-cell one.
TEST_CASE("bad options: unknown options and resource guards are refused before any set-up, as fast as on a 5-cell scene", "[options]")
{
  const std::string dir = SharedTempDir();
  REQUIRE(!dir.empty());
  const std::vector<BadCase> cases = {
      {"unknown option -forc_energy 0.5 (did you mean -force_energy?)", "-study simulate -lattice_cells 25000 -forc_energy 0.5"},
      {"unknown option -forc_energy 0.5 (did you mean -force_energy?)", "-study sweep -lattice_cells 25000 -sweep_omega_n 8 -sweep_energy_n 8 -forc_energy 0.5"},
      {"unknown option -forc_energy 0.5 (did you mean -force_energy?)", "-study zak -lattice_cells 25000 -forc_energy 0.5"},
      {"unknown option -ts_type rk", "-study simulate -lattice_cells 25000 -ts_type rk"},
      {"unknown option -sim_tss_type rk (did you mean -sim_ts_type?)", "-study simulate -lattice_cells 25000 -sim_tss_type rk"},
      {"unknown option -linear_epss_nev 4 (did you mean -linear_eps_nev?)", "-study linear -lattice_cells 25000 -linear_epss_nev 4"},
      {"-nnm_snes_rtol 1e-3: not an option of -study simulate (it belongs to -study continuation)", "-study simulate -lattice_cells 25000 -nnm_snes_rtol 1e-3"},
      {"-floquet_eps_nev 3: not an option of -study simulate", "-study simulate -lattice_cells 25000 -floquet_eps_nev 3"},
      {"dense shooting Jacobian .* more than this machine's", "-study continuation -lattice_cells 100000"},
      {"dense shooting Jacobian .* more than this machine's", "-study perturb -lattice_cells 100000"},
      {"dense shooting Jacobian .* more than this machine's", "-study stability -lattice_cells 100000"},
      {"dense shooting Jacobian .* more than this machine's", "-study workprecision -wp_scene shooting -lattice_cells 100000"},
  };
  // The same mistake on a 5-cell scene: the time a refusal of the options takes.
  double small = 0;
  for (const char *study : {"simulate", "sweep", "continuation"}) {
    const Refusal r = RunRefused(SplitArgs(std::string("-study ") + study + " -lattice_cells 5 -forc_energy 0.5"), dir);
    CheckRefusal(r, {"unknown option -forc_energy", study}, dir);
    small = std::max(small, r.seconds);
  }
  for (const BadCase &c : cases) {
    const Refusal r = RunRefused(SplitArgs(c.args), dir);
    CheckRefusal(r, c, dir);
    INFO("nltopo " << c.args << ": " << r.seconds << " s, a 5-cell scene's refusal " << small << " s");
    CHECK(r.setups == 0);
    CHECK(r.seconds < 3 * small + 0.5); // margin for a loaded machine; the run itself takes 30 s and more
  }
  MPI_Barrier(PETSC_COMM_WORLD);
  if (!Rank()) rmdir(dir.c_str());
}

// -options_left after a refusal lists the refused option as unused: the audit
// reads the options' values without marking them used ("There are no unused
// options" next to "unknown option -bogus" was the bug).
TEST_CASE("bad options: a refused option stays unused in the database (-options_left lists it)", "[options]")
{
  const std::string dir = SharedTempDir();
  REQUIRE(!dir.empty());
  for (const std::string &args : {std::string("-study linear -lattice_cells 5 -bogus 1"), std::string("-study simulate -sim_t_final 5 -sweep_omega_n 3"),
                                   std::string("-study simulate -sim_t_final 5 -force_omgea 2")}) {
    const Refusal r = RunRefused(SplitArgs(args), dir);
    INFO("nltopo " << args);
    CHECK(r.code != 0);
    const std::string refused = SplitArgs(args)[SplitArgs(args).size() - 2].substr(1);
    CHECK(std::count(r.unused.begin(), r.unused.end(), refused) == 1);
    CHECK(r.unused.size() == 1); // the study's own options were read
  }
  MPI_Barrier(PETSC_COMM_WORLD);
  if (!Rank()) rmdir(dir.c_str());
}

// PETSc compares option names case-insensitively (-Force_Energy is
// -force_energy), and so does every check of nltopo's: the missing value, the
// 32-bit integer, the audit of unused options and its did-you-mean, the
// type-mismatched solver option, the workprecision configurations.
TEST_CASE("bad options: every check compares option names as PETSc does, case-insensitively", "[options]")
{
  const std::string dir = SharedTempDir();
  REQUIRE(!dir.empty());
  const std::vector<BadCase> cases = {
      {"-Force_Energy: no value given", S + "-Force_Energy"},
      {"-LATTICE_K: no value given", L + "-LATTICE_K ''"},
      {"unknown option -Force_Omgea 2 (did you mean -force_omega?)", S + "-Force_Omgea 2"},
      {"unknown option -FORC_ENERGY 0.5 (did you mean -force_energy?)", S + "-FORC_ENERGY 0.5"},
      {"-LATTICE_CELLS 4294967301: out of the integer range", "-study linear -LATTICE_CELLS 4294967301"},
      {"-Sim_TS_Max_Steps 99999999999: out of the integer range", S + "-Sim_TS_Max_Steps 99999999999"},
      {"-Sweep_Omega_N 3: not an option of -study simulate (it belongs to -study sweep)", S + "-Sweep_Omega_N 3"},
      {"-Sim_TS_RK_Type 5dp: not used by this run (-sim_ts_type is symsplit", W + "-sim_ts_type symsplit -sim_ts_dt 0.1 -Sim_TS_RK_Type 5dp"},
      {"-Lattice_K is not an integrator option", P + "-wp_configs ' -Sim_TS_Type rk -Lattice_K 2'"},
      {"-wp_reference .*: leave out -SIM_TS_RTOL", P + "-wp_reference ' -sim_ts_type rkn -SIM_TS_RTOL 1e-9'"},
  };
  for (const BadCase &c : cases) {
    const Refusal r = RunRefused(SplitArgs(c.args), dir);
    CheckRefusal(r, c, dir);
    CHECK(r.setups == 0);
  }
  MPI_Barrier(PETSC_COMM_WORLD);
  if (!Rank()) rmdir(dir.c_str());
}
