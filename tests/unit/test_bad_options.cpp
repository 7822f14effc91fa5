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
#include "core/options_input.hpp"
#include <regex>
#include <sys/stat.h>

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
      // the same value held by two options: the one of the type that failed (fuzz seed 3275416688), else both
      {"nltopo: error: -sweep_resume 2: not a boolean", W + "-sweep_resume 2"}, // W holds -sweep_omega_n 2
      {"-sweep_energy_list a or -sweep_omega_list a: not a real number", W + "-sweep_omega_list a -sweep_energy_list a"},
      {"-sweep_lyapunov (the tangent flow of the free lattice after the cut-off) needs a conservative lattice; -lattice_damping 0.01", W + "-sweep_lyapunov -lattice_damping 0.01"},
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
      // -study floquet_scaling: integer, ascending sizes each within the dense Floquet route; the sizes are its own
      {"-scaling_cells 5.5: cells per side are integers", "-study floquet_scaling -scaling_cells 5.5"},
      {"-scaling_cells must ascend, got 5 after 10", "-study floquet_scaling -scaling_cells 10,5"},
      {"-scaling_cells 300: 2N = 2404 > -floquet_mf_dense_max 2048", "-study floquet_scaling -scaling_cells 5,300"},
      {"-scaling_energy_windows must ascend", "-study floquet_scaling -scaling_energy_windows 0,2,1"},
      {"-lattice_cells is set by -study floquet_scaling (-scaling_cells)", "-study floquet_scaling -lattice_cells 5"},
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
      // -study stabilitymap: the sizes are -smap_cells, the events -smap_kinds, the window of p is needed
      {"-lattice_cells.*-smap_cells", "-study stabilitymap -lattice_cells 5 -cont_codim2_min 0.3 -cont_codim2_max 0.5"},
      {"-cont_codim2.*-smap_kinds", "-study stabilitymap -smap_cells 5 -cont_codim2 insulated:hh@1.75 -cont_codim2_min 0.3 -cont_codim2_max 0.5"},
      {"-study stabilitymap needs -cont_codim2_min and -cont_codim2_max", "-study stabilitymap -smap_cells 5"},
      {"-smap_check 0.9 lies outside", "-study stabilitymap -smap_cells 5 -cont_codim2_min 0.3 -cont_codim2_max 0.5 -smap_check 0.9"},
      {"-smap_kinds 4: the kinds followed", "-study stabilitymap -smap_cells 5 -cont_codim2_min 0.3 -cont_codim2_max 0.5 -smap_kinds 5,4"},
      {"-smap_cells 2.5: cells per side are integers", "-study stabilitymap -smap_cells 2.5 -cont_codim2_min 0.3 -cont_codim2_max 0.5"},
      {"-smap_group_size 3 must divide the number of ranks", "-study stabilitymap -smap_cells 5 -cont_codim2_min 0.3 -cont_codim2_max 0.5 -smap_group_size 3"},
      {"-study stabilitymap locates the branch's events", "-study stabilitymap -smap_cells 5 -cont_codim2_min 0.3 -cont_codim2_max 0.5 -cont_bifurcations 0"},
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

// A word that is neither an option nor an option's value is an error (PETSc
// skips it silently: -sweep_energy_list 0.1, 1 would run one energy); the
// rule is PETSc's own (PetscOptionsValidKey, PetscOptionsInsertArgs and
// PetscOptionsInsertString), so the legitimate look-alikes stay legal.
TEST_CASE("bad options: stray words on the command line and in PETSC_OPTIONS, and their legitimate look-alikes", "[options][serial]")
{
  struct Words {
    std::string pattern, line; // pattern "": accepted
  };
  const std::vector<Words> argv = {
      {"command line: '1' is neither an option nor an option's value (after -sweep_energy_list 0.1,)", "-study sweep -sweep_energy_list 0.1, 1"},
      {"'extra' is neither an option nor an option's value (after -study linear)", "-study linear extra"},
      {"'scene.opts' .* (before any option); did you mean -options_file scene.opts?", "scene.opts -study linear"},
      {"'b.opts' is neither .* (after -options_file a.opts)", "-options_file a.opts b.opts"},
      {"'-2' is neither .* (after -force_energy 1)", "-study simulate -force_energy 1 -2"},
      {"'' is neither .* (after -lattice_k 2)", "-study linear -lattice_k 2 ''"},
      {"", "-study workprecision -wp_configs ' -sim_ts_type symsplit -sim_ts_dt 0.2' -wp_repeats 1"},
      {"", "-study linear -lattice_cubic -50 -lattice_gamma -0.5 -force_energy -.5 -lattice_k -1e-3 -x -inf"},
      {"", "-study sweep -sweep_energy_list 0.1,1 -sim_store_u -sim_progress 0"},
      {"", "-prefix_push lattice_ -cells 5 -prefix_pop -study linear -lattice_k ''"},
      {"", "-study linear -output 'my file.h5' -log_view :log.txt"},
  };
  for (const Words &w : argv) {
    const std::string line = StrayArgument(SplitArgs(w.line));
    INFO("nltopo " << w.line << "\n-> " << line);
    if (w.pattern.empty()) CHECK(line.empty());
    else CHECK(std::regex_search(line, std::regex(w.pattern, std::regex::basic)));
  }
  const std::vector<Words> env = {
      {"PETSC_OPTIONS: 'file.h5' is neither .* (after -output my\\\\); PETSc splits it at spaces (a backslash does not escape one)", "-output my\\ file.h5"},
      {"PETSC_OPTIONS: '1' is neither", "-sweep_energy_list 0.1, 1"},
      {"", "-output \"my file.h5\" -lattice_cubic -1"},
      {"", " -log_view   -lattice_k 2 "},
  };
  for (const Words &w : env) {
    const std::string line = StrayInOptionsString(w.line, "PETSC_OPTIONS");
    INFO("PETSC_OPTIONS='" << w.line << "'\n-> " << line);
    if (w.pattern.empty()) CHECK(line.empty());
    else CHECK(std::regex_search(line, std::regex(w.pattern, std::regex::basic)));
  }
}

namespace {
// Writes the files (name, content) into dir on rank 0.
void WriteFiles(const std::string &dir, const std::vector<std::pair<std::string, std::string>> &files)
{
  if (!Rank())
    for (const auto &f : files) {
      std::FILE *o = std::fopen((dir + "/" + f.first).c_str(), "wb");
      REQUIRE(o);
      std::fwrite(f.second.data(), 1, f.second.size(), o);
      std::fclose(o);
    }
  MPI_Barrier(PETSC_COMM_WORLD);
}

// CheckOptionsSources on the command line (words, after the program name), run in dir.
std::string SourcesLine(const std::string &dir, const std::vector<std::string> &words)
{
  char cwd[4096];
  REQUIRE(getcwd(cwd, sizeof cwd));
  REQUIRE(chdir(dir.c_str()) == 0);
  std::vector<std::string> all = {"nltopo"};
  all.insert(all.end(), words.begin(), words.end());
  std::vector<char *> argv;
  for (std::string &w : all) argv.push_back(&w[0]);
  const std::string line = CheckOptionsSources(PETSC_COMM_WORLD, (int)argv.size(), argv.data());
  REQUIRE(chdir(cwd) == 0);
  return line;
}
} // namespace

// Options files as PETSc reads them: each problem is one line naming the file
// and the line, the same on every rank (rank 0 reads), never a traceback,
// never an endless recursion; -lattice_Gamma is refused however it reaches
// the database (a nested file, -prefix_push).
TEST_CASE("bad options: options files, read by PETSc's reader before the run, each problem in one line naming file and line", "[options]")
{
  const std::string dir = SharedTempDir();
  REQUIRE(!dir.empty());
  WriteFiles(dir, {{"ok.opts", "# a scene\n\n   -study linear   # comment\n-lattice_cells\t6\r\n-lattice_cubic -1.5\n-wp_configs \" -sim_ts_type symsplit\"\n"},
                   {"bom.opts", "\xEF\xBB\xBF-study linear\n"},
                   {"bang.opts", "-study linear\n-lattice_cells 5 !\n"},
                   {"two.opts", "-study linear -lattice_cells 5\n"},
                   {"space.opts", "-study linear\n-output my file.h5\n"},
                   {"garbage.opts", std::string("-study linear\n\x01\x9c\xfe\x7f binary\n", 26)},
                   {"nested.opts", "-study linear\n-options_file gone.opts\n"},
                   {"a.opts", "-lattice_k 1\n-options_file b.opts\n"},
                   {"b.opts", "-lattice_k 2\n-options_file a.opts\n"},
                   {"self.opts", "-options_file self.opts\n"},
                   {"bare.opts", "-options_file\n"},
                   {"push.opts", "-prefix_push lattice_\n-Gamma 0.5\n-prefix_pop\n"},
                   {"outer.opts", "-study linear\n-OPTIONS_FILE push.opts\n"},
                   {"gamma.opts", "-options_file ok.opts\n-LATTICE_gamma 0.2\n"},
                   {"piped.opts", "-study linear\n-options_file fifo\n"}});
  if (!Rank()) REQUIRE(mkdir((dir + "/adir").c_str(), 0700) == 0);
  if (!Rank()) REQUIRE(mkfifo((dir + "/fifo").c_str(), 0600) == 0); // never opened: a pipe named in a file is refused from its stat
  MPI_Barrier(PETSC_COMM_WORLD);
  struct FileCase {
    std::string pattern; // "" : accepted
    std::vector<std::string> words;
  };
  const std::vector<FileCase> cases = {
      {"", {"-options_file", "ok.opts"}},
      {"", {"-study", "linear", "-lattice_cubic", "-2", "-options_file", "ok.opts", "-lattice_k", "0.5"}},
      {"^options file bom.opts line 1: the file starts with a UTF-8 byte-order mark; save it without one$", {"-options_file", "bom.opts"}},
      {"^options file bang.opts line 2: '!' after the value (comments start with #)$", {"-options_file", "bang.opts"}},
      {"^options file two.opts line 1: two options on one line", {"-options_file", "two.opts"}},
      {"^options file space.opts line 2: 'file.h5' after the value (a value with spaces is quoted", {"-options_file", "space.opts"}},
      {"^options file garbage.opts line 2: '\\\\x01\\\\x9C\\\\xFE\\\\x7F' is not an option", {"-options_file", "garbage.opts"}},
      {"^options file nested.opts line 2: cannot read options file gone.opts: No such file or directory$", {"-options_file", "nested.opts"}},
      {"^cannot read -options_file gone.opts: No such file or directory$", {"-study", "linear", "-options_file", "gone.opts"}},
      {"^-options_file adir is a directory$", {"-options_file", "adir"}},
      {"options files include each other (a.opts -> b.opts -> a.opts)", {"-options_file", "a.opts"}},
      {"options files include each other (self.opts -> self.opts)", {"-Options_File", "self.opts"}},
      {"^options file bare.opts line 1: -options_file needs a file name$", {"-options_file", "bare.opts"}},
      {"^-options_file needs a file name$", {"-study", "linear", "-options_file", "-lattice_k", "2"}},
      {"^-lattice_Gamma is the same option as -lattice_gamma .*-lattice_cubic$", {"-options_file", "outer.opts"}},
      {"^-lattice_Gamma is the same option", {"-study", "linear", "-prefix_push", "lattice_", "-Gamma", "0.5", "-prefix_pop"}},
      // after -lattice_gamma: the database keeps the first spelling of a name, the check sees each as it is set
      {"^-lattice_Gamma is the same option", {"-study", "linear", "-lattice_gamma", "0.4", "-lattice_Gamma", "0.5"}},
      {"^options file piped.opts line 2: options file fifo is not a regular file (a pipe?)", {"-options_file", "piped.opts"}},
      {"^-LATTICE_gamma is the same option", {"-options_file", "gamma.opts"}},
      {"^command line: '1' is neither an option nor an option's value", {"-study", "sweep", "-sweep_energy_list", "0.1,", "1"}},
  };
  for (const FileCase &c : cases) {
    const std::string line = SourcesLine(dir, c.words);
    std::string cmd;
    for (const std::string &w : c.words) cmd += " " + w;
    INFO("nltopo" << cmd << "\n-> " << line);
    if (c.pattern.empty()) CHECK(line.empty());
    else CHECK(std::regex_search(line, std::regex(c.pattern, std::regex::basic)));
    CHECK(line.find('\n') == std::string::npos);
  }
  // PETSC_OPTIONS (rank 0's, as PETSc reads it): a missing file and a stray word
  const char *saved = std::getenv("PETSC_OPTIONS");
  const std::string keep = saved ? saved : "";
  setenv("PETSC_OPTIONS", "-options_file gone.opts", 1);
  CHECK(SourcesLine(dir, {"-study", "linear"}) == "PETSC_OPTIONS: cannot read options file gone.opts: No such file or directory");
  setenv("PETSC_OPTIONS", "-output my\\ file.h5", 1);
  CHECK(std::regex_search(SourcesLine(dir, {"-study", "linear"}), std::regex("^PETSC_OPTIONS: 'file.h5' is neither", std::regex::basic)));
  setenv("PETSC_OPTIONS", "-options_file ok.opts -output \"my file.h5\"", 1);
  CHECK(SourcesLine(dir, {"-study", "linear"}).empty());
  if (saved) setenv("PETSC_OPTIONS", keep.c_str(), 1);
  else unsetenv("PETSC_OPTIONS");
  MPI_Barrier(PETSC_COMM_WORLD);
  if (!Rank()) {
    for (const std::string &f : DirEntries(dir)) {
      if (f == "adir") rmdir((dir + "/" + f).c_str());
      else std::remove((dir + "/" + f).c_str());
    }
    rmdir(dir.c_str());
  }
}

// Ranks started with different options (an MPMD launch, a per-rank file that
// differs) fail together with one line, before anything else: the command
// lines are compared before PETSc starts (ArgumentsDifferAcrossRanks), the
// databases when the study starts (CheckOptionsAgree).
TEST_CASE("bad options: options that differ between ranks fail together in one line", "[options]")
{
  int size;
  MPI_Comm_size(PETSC_COMM_WORLD, &size);
  std::vector<std::string> words = {"nltopo", "-study", "simulate", "-sim_t_final", "5"};
  if (Rank() == size - 1 && size > 1) words.insert(words.end(), {"-force_omega", "abc"});
  std::vector<char *> argv;
  for (std::string &w : words) argv.push_back(&w[0]);
  const std::string line = ArgumentsDifferAcrossRanks(PETSC_COMM_WORLD, (int)argv.size(), argv.data());
  INFO(line);
  if (size == 1) CHECK(line.empty());
  else CHECK(line == "rank " + std::to_string(size - 1) + " was started with other options than rank 0 (after argument 4, rank " + std::to_string(size - 1) +
                         " has '-force_omega abc', rank 0 nothing); every rank must be given the same command line");
  if (size == 1) return; // the database check below needs a second rank
  const std::string dir = SharedTempDir();
  REQUIRE(!dir.empty());
  const Refusal r = RunRefused(SplitArgs(S + (Rank() == 1 ? "-force_omega abc" : "-force_omega 2")), dir);
  CheckRefusal(r, {"the options differ between ranks: rank 1 has '-force_omega abc', rank 0 '-force_omega 2'", S}, dir);
  CHECK(r.setups == 0);
  MPI_Barrier(PETSC_COMM_WORLD);
  if (!Rank()) rmdir(dir.c_str());
}

// Who reads an option, as the audit decides before any work: PETSc's own
// global options (an inventory, not prefixes: -hello is not -h), nltopo's,
// the declared solver objects', or nobody.
TEST_CASE("bad options: every option is nltopo's, a declared solver's, PETSc's own, or unknown", "[options][serial]")
{
  RegisterStudyContracts(); // the component prefixes
  const std::vector<std::string> solvers = {"sim_ts_", "sim_snes_", "sim_ksp_", "sim_pc_", "sim_mat_", "linear_eps_", "linear_st_"};
  const std::vector<std::pair<std::string, OptionOwner>> cases = {
      {"log_view", OptionOwner::Petsc},         {"Log_View", OptionOwner::Petsc},          {"malloc_debug", OptionOwner::Petsc},
      {"options_left", OptionOwner::Petsc},     {"viewer_binary_skip_info", OptionOwner::Petsc}, {"info", OptionOwner::Petsc},
      {"no_signal_handler", OptionOwner::Petsc}, {"lattice_k", OptionOwner::Nltopo},        {"LATTICE_K", OptionOwner::Nltopo},
      {"force_omgea", OptionOwner::Nltopo},     {"study", OptionOwner::Nltopo},            {"option_tables", OptionOwner::Nltopo},
      {"sim_ts_rtol", OptionOwner::Solver},     {"Sim_TS_Adapt_Type", OptionOwner::Solver}, {"linear_st_ksp_type", OptionOwner::Solver},
      {"mat_view", OptionOwner::Solver},        {"sf_type", OptionOwner::Solver},          {"forc_energy", OptionOwner::Unknown},
      {"ts_type", OptionOwner::Unknown},        {"nnm_snes_rtol", OptionOwner::Unknown},   {"hello", OptionOwner::Unknown},
      {"mpi_foo", OptionOwner::Unknown},        {"petsc_foo", OptionOwner::Unknown},       {"test_x", OptionOwner::Unknown},
      {"logview", OptionOwner::Unknown},        {"sim_tss_type", OptionOwner::Nltopo}}; // under -sim_, not a solver class: a misspelt nltopo option
  for (const auto &c : cases) {
    INFO("-" << c.first);
    CHECK(ClassifyOption(c.first, solvers) == c.second);
  }
}
