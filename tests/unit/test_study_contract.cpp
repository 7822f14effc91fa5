// The study contract (studies/registry.hpp): every option a study reads is
// under a prefix its contract registers, so a resume or an overwrite compares
// it (io/run_options.hpp); an overwrite that differs only in a study's own
// option is refused with one line naming it; Study::Run ends an interrupted
// Solve with its partial output and one line; the forced scene's
// needs-linear-modes rule is what the tone burst needs.
#include "core/effective_options.hpp"
#include "core/option_table.hpp"
#include "core/options_audit.hpp"
#include "core/ts_traits.hpp"
#include "effects/effect.hpp"
#include "helpers.hpp"
#include "core/errors.hpp"
#include "core/signals.hpp"
#include "io/input.hpp"
#include "io/output.hpp"
#include "io/run_options.hpp"
#include "studies/forced_scene.hpp"
#include "studies/registry.hpp"
#include <algorithm>
#include <cstdio>
#include <map>
#include <set>
#include <string>

using namespace nltopo;

namespace {

// CheckOverwrite's verdict on path for -study workprecision: 0 or the error, with its message.
PetscErrorCode OverwriteVerdict(const std::string &path, PetscBool overwrite, std::string *msg)
{
  PetscErrorCode ierr = 0;
  char buf[2048];
  PetscFunctionBeginUser;
  PetscCall(CaptureError([&]() { return CheckOverwrite(PETSC_COMM_WORLD, path, "workprecision", overwrite); }, &ierr, buf, sizeof(buf)));
  *msg = buf;
  PetscFunctionReturn(ierr);
}

// A study whose Solve is interrupted after one of its two runs (partial) or before any.
class StoppedStudy : public Study {
public:
  explicit StoppedStudy(bool partial) : partial_(partial) {}

protected:
  PetscErrorCode ReadOptions() override { return 0; }
  PetscErrorCode Build() override { return 0; }
  PetscErrorCode Solve() override { return PETSC_ERR_SIG; } // the silent interrupt (core/signals.hpp)
  bool Interrupted(Interruption *it) const override
  {
    *it = {partial_, partial_ ? "between test runs (1 of 2 done)" : "before the first test run ended", " [tail]"};
    return true;
  }
  PetscErrorCode Write(PetscViewer v) override { return WriteAttr(v, "/zak", "energy_threshold", (PetscReal)2); }

private:
  bool partial_;
};

} // namespace

TEST_CASE("Study::Run ends an interrupted Solve: the partial output, then one line", "[contract]")
{
  const std::string path = "contract_int.h5", part = path + ".partial.h5"; // -output only ever receives a complete output
  int rank;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  if (!rank) std::remove(path.c_str()), std::remove(part.c_str());
  MPI_Barrier(PETSC_COMM_WORLD);
  REQUIRE(PetscOptionsSetValue(NULL, "-output", path.c_str()) == 0);
  for (bool partial : {false, true}) {
    INFO("partial " << partial);
    PetscErrorCode ierr;
    char msg[2048];
    REQUIRE(CaptureError([&]() { return StoppedStudy(partial).Run(PETSC_COMM_WORLD, "zak"); }, &ierr, msg, sizeof(msg)) == 0);
    PetscLogStagePop(); // Run's Solve stage, left pushed by the error
    CHECK(ierr == PETSC_ERR_SIG);
    const std::string m = msg, head = "interrupted by " + std::string(SignalName(StopSignalSeen())) + " ";
    MPI_Barrier(PETSC_COMM_WORLD);
    std::string study;
    long complete = -1;
    if (!partial) {
      CHECK(m == head + "before the first test run ended; no output written [tail]");
      CHECK_FALSE(ReadRootAttribute(path, "study", &study));
      continue;
    }
    CHECK(m == head + "between test runs (1 of 2 done); partial output " + part + " (complete = 0) [tail]");
    CHECK_FALSE(ReadRootAttribute(path, "study", &study));
    CHECK(ReadRootAttribute(part, "study", &study));
    CHECK(study == "zak");
    CHECK(ReadRootAttribute(part, "complete", &complete));
    CHECK(complete == 0);
  }
  REQUIRE(PetscOptionsClearValue(NULL, "-output") == 0);
  MPI_Barrier(PETSC_COMM_WORLD);
  if (!rank) std::remove(part.c_str());
}

TEST_CASE("two workprecision runs that differ only in a -wp_ option do not replace each other", "[contract]")
{
  const std::string path = "contract_wp.h5";
  for (const auto &o : std::vector<std::pair<std::string, std::pair<const char *, const char *>>>{
           {"-wp_twins", {"3", "5"}}, {"-wp_repeats", {"1", "3"}}, {"-wp_twin_eps", {"1e-8", "1e-7"}}}) {
    INFO(o.first);
    REQUIRE(PetscOptionsSetValue(NULL, o.first.c_str(), o.second.first) == 0);
    {
      OutputFile out;
      REQUIRE(out.Open(PETSC_COMM_WORLD, path) == 0);
      REQUIRE(out.Commit("workprecision", 0) == 0);
    }
    std::string msg;
    CHECK(OverwriteVerdict(path, PETSC_FALSE, &msg) == 0); // the same options: the run may replace its own output
    REQUIRE(PetscOptionsSetValue(NULL, o.first.c_str(), o.second.second) == 0);
    CHECK(OverwriteVerdict(path, PETSC_FALSE, &msg) != 0);
    CHECK(msg == "-output " + path + " holds the complete output of a run with " + o.first + " " + o.second.first + " (now " + o.second.second +
                     "); choose another -output or give -output_overwrite");
    CHECK(OverwriteVerdict(path, PETSC_TRUE, &msg) == 0);
    REQUIRE(PetscOptionsClearValue(NULL, o.first.c_str()) == 0);
  }
  MPI_Barrier(PETSC_COMM_WORLD);
  int rank;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  if (!rank) std::remove(path.c_str());
}

TEST_CASE("every option a study reads is under a prefix its contract registers", "[contract]")
{
  std::map<std::string, std::set<std::string>> known;
  REQUIRE(CollectKnownOptions(PETSC_COMM_WORLD, StudyOptionFunctions(), &known) == 0);
  CHECK(known.size() == 11);
  // Never compared: where the output goes, which study runs, and monitors
  // (PETSc's own -all_ksp_monitor among them; io/run_options.hpp).
  const std::set<std::string> outside = {"output", "output_overwrite", "study", "help"};
  size_t compared = 0;
  for (const auto &k : known) {
    CHECK(k.second.size() >= (k.first == "merge" ? 3u : 5u)); // merge: -merge_inputs and the output options
    for (const std::string &name : k.second) {
      if (outside.count(name) || name.find("monitor") != std::string::npos) continue;
      INFO("-study " << k.first << ": -" << name);
      bool under = false;
      for (const std::string &p : ComponentPrefixes()) under |= ("-" + name).compare(0, p.size(), p) == 0;
      CHECK(under);
      compared += under;
    }
  }
  CHECK(compared > 100);
  // The registered prefixes themselves: the study prefixes that a forgotten line would drop.
  for (const char *p : {"-wp_", "-zak_", "-perturb_", "-stability_", "-scaling_", "-merge_", "-sweep_", "-kcorr_", "-cont_", "-nnm_", "-floquet", "-lattice_",
                        "-force_", "-sim_", "-linear_"}) {
    INFO(p);
    CHECK(std::count(ComponentPrefixes().begin(), ComponentPrefixes().end(), std::string(p)) == 1);
  }
}

TEST_CASE("the forced scene computes the linear modes exactly when the tone burst needs them", "[contract]")
{
  LatticeParams lp;
  lp.cells = 6;
  Lattice lat;
  REQUIRE(lat.Setup(PETSC_COMM_WORLD, lp) == 0);
  PetscPushErrorHandler(PetscReturnErrorHandler, NULL); // the expected errors are not printed
  size_t needed = 0;
  for (ForceProfile profile : {ForceProfile::None, ForceProfile::Site, ForceProfile::Mode, ForceProfile::Exponential})
    for (PetscReal amplitude : {-1.0, 0.01}) {
      ToneBurstOptions fo;
      fo.profile = profile;
      fo.amplitude = amplitude;
      fo.omega = 1.7;
      fo.energy = 1;
      fo.mode = 3;
      fo.site = lp.InterfaceSite();
      ToneBurst burst;
      const bool without_modes = burst.Setup(lat, fo, NULL) == 0;
      INFO("profile " << (int)profile << ", amplitude " << amplitude);
      CHECK(ForcedScene::NeedsLinearModes(fo) == !without_modes);
      needed += ForcedScene::NeedsLinearModes(fo);
    }
  PetscPopErrorHandler();
  CHECK(needed == 5); // mode and exponential at either amplitude, the site profile under the amplitude rule
}

TEST_CASE("a resume or an overwrite compares effective values: a changed code default is caught, the same value given or defaulted is not a change",
          "[contract][serial]")
{
  RegisterStudyContracts(); // the compared option prefixes
  const std::string given = "-study continuation -lattice_cells 5";
  // written when the shooting integrator's default was rk; this run's default is symsplit
  const RunRecord old_file{given, "-lattice_k 1\n-nnm_ts_type rk\n"}, now{given, "-lattice_k 1\n-nnm_ts_type symsplit\n"};
  CHECK(FirstOptionDifference(old_file, now, OptionRule::Resume) == "with -nnm_ts_type rk, the default then (now symsplit)");
  CHECK(FirstOptionDifference(old_file, now, OptionRule::Overwrite) == "with -nnm_ts_type rk, the default then (now symsplit)");
  CHECK(FirstOptionDifference(now, now, OptionRule::Resume).empty());
  // given on one side, the same value by default on the other: the same run
  const RunRecord explicit_now{given + " -nnm_ts_type symsplit", "-lattice_k 1\n-nnm_ts_type symsplit\n"};
  CHECK(FirstOptionDifference(explicit_now, now, OptionRule::Resume).empty());
  CHECK(FirstOptionDifference(now, explicit_now, OptionRule::Resume).empty());
  // given on one side, another default on the other: named as before
  const RunRecord explicit_rk{given + " -nnm_ts_type rk", "-lattice_k 1\n-nnm_ts_type rk\n"};
  CHECK(FirstOptionDifference(explicit_rk, now, OptionRule::Resume) == "with -nnm_ts_type rk (now not given)");
  CHECK(FirstOptionDifference(now, explicit_rk, OptionRule::Resume) == "without -nnm_ts_type (now rk)");
  // a file of before effective_options existed: only what was given is compared
  const RunRecord legacy{given, ""};
  CHECK(FirstOptionDifference(legacy, now, OptionRule::Resume).empty());
  // bookkeeping is never compared, whatever its effective value
  const RunRecord verbose0{given, "-cont_verbose 0\n"}, verbose1{given, "-cont_verbose 1\n"};
  CHECK(FirstOptionDifference(verbose0, verbose1, OptionRule::Overwrite).empty());
}

TEST_CASE("the output records the effective value of every option the run read, defaults included", "[contract]")
{
  // -lattice_k's table read with its default: its note is the default, and the TS prefix declared is its code default
  ClearEffectiveOptions();
  LatticeParams p;
  PCHK(LatticeModelFromOptions(PETSC_COMM_WORLD, &p));
  PCHK(DeclareTS(PETSC_COMM_WORLD, "nnm_"));
  const std::string text = EffectiveOptionsText();
  INFO(text);
  CHECK(text.find("-lattice_k 1\n") != std::string::npos);
  CHECK(text.find(std::string("-nnm_ts_type ") + TSDefaultType("nnm_") + "\n") != std::string::npos);
  {
    test::ScopedOptions o{{"-lattice_k", "2.5"}};
    PCHK(LatticeModelFromOptions(PETSC_COMM_WORLD, &p));
  }
  CHECK(EffectiveOptionsText().find("-lattice_k 2.5\n") != std::string::npos);
  {
    EffectiveOptionsPause pause; // the audit's reads of other studies' options are not this run's
    test::ScopedOptions o{{"-lattice_k", "3"}};
    PCHK(LatticeModelFromOptions(PETSC_COMM_WORLD, &p));
  }
  CHECK(EffectiveOptionsText().find("-lattice_k 2.5\n") != std::string::npos);
}
