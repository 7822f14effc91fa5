// -study linear: eigenpairs of K, the named modes (docs/studies/linear.md "Mode
// identification"), infinite-lattice Bloch bands and Zak phases; /linear of outputs.md.
// With -linear_gamma_list, also the topological transition over gamma
// (paper Fig. 2a, bands/transition.hpp): /linear/transition.
#include "bands/linear_modes.hpp"
#include "bands/transition.hpp"
#include "studies/linear_transition.hpp"
#include "core/memory_guard.hpp"
#include "effects/effect.hpp"
#include "core/log.hpp"
#include "core/option_table.hpp"
#include "core/options_audit.hpp"
#include "io/output.hpp"
#include "io/schema.hpp"
#include "studies/registry.hpp"
#include "studies/study.hpp"
#include <petscviewerhdf5.h>
#include <cmath>

namespace nltopo {

namespace {

PetscReal OmegaOf(const LinearModes &m, PetscInt j) { return j >= 0 ? m.Omega()[j] : NAN; }

// The linear study's own block: -linear_nq and -linear_gamma_list (off unless given).
struct LinearStudyOptions {
  PetscInt nq = 201;
  std::string gamma_list; // min:max:n, "" = off
};

const auto &kLinearStudyTable = DeclareOptionTable<LinearStudyOptions>("linear_", "Linear study", [](OptionTable<LinearStudyOptions> &t) {
  t.Int("nq", &LinearStudyOptions::nq, Closed(4, 1000000), "Wavenumbers for the Bloch bands; the Zak loop uses 2 nq points")
      .String("gamma_list", &LinearStudyOptions::gamma_list,
              "Topological transition (paper Fig. 2a): min:max:n values of gamma in [-1, 1], the finite spectrum and the Zak phases at each "
              "-> /linear/transition (default: none, off)")
      .Default("none (off)");
});

PetscErrorCode LinearStudyOptionsFromOptions(MPI_Comm comm, PetscInt *nq, GammaList *gl)
{
  LinearStudyOptions o;
  std::vector<PetscBool> set;
  PetscFunctionBeginUser;
  PetscCall(kLinearStudyTable.Read(comm, &o, &set));
  // the value is at most 255 characters, as it always was
  PetscCheck(o.gamma_list.size() < 255, comm, PETSC_ERR_USER, "-linear_gamma_list %.255s...: too long, expected min:max:n", o.gamma_list.c_str());
  *nq = o.nq;
  *gl = GammaList();
  if (kLinearStudyTable.Given(set, "gamma_list")) PetscCall(ParseGammaList(comm, o.gamma_list, gl));
  PetscFunctionReturn(0);
}

class LinearStudy : public Study {
protected:
  PetscErrorCode ReadOptions() override
  {
    PetscFunctionBeginUser;
    PetscCall(LatticeModelFromOptions(comm_, &lp_));
    PetscCall(LinearModesOptionsFromOptions(comm_, &mo_));
    PetscCall(LinearStudyOptionsFromOptions(comm_, &nq_, &gl_));
    // The transition needs all N eigenfrequencies (an O(N^2) tridiagonal solve per gamma): the dense path's N.
    if (!declaring_ && gl_.n)
      PetscCheck(lp_.N() <= mo_.dense_max, comm_, PETSC_ERR_USER,
                 "-linear_gamma_list %s needs all N eigenfrequencies: N = %" PetscInt_FMT " exceeds -linear_dense_max %" PetscInt_FMT, gl_.text.c_str(),
                 lp_.N(), mo_.dense_max);
    PetscFunctionReturn(0);
  }
  PetscErrorCode DeclareSolvers(MPI_Comm comm) override { return DeclareEPS(comm, "linear_"); }
  PetscErrorCode CheckResources() override
  {
    PetscFunctionBeginUser;
    PetscCall(CheckLatticeMemory(comm_, lp_.N()));
    PetscCall(CheckLinearModesMemory(comm_, lp_.N(), mo_));
    // The transition's arrays, held on every rank (each computes them all).
    if (gl_.n) PetscCall(CheckMemory(comm_, 8.0 * (double)gl_.n * (double)(lp_.N() + 12), "/linear/transition (-linear_gamma_list n x N sites)"));
    PetscFunctionReturn(0);
  }
  PetscErrorCode Build() override
  {
    PetscFunctionBeginUser;
    PetscCall(lat_.Setup(comm_, lp_));
    EffectList fx(lat_); // the undamped modes of K: no non-conservative effect belongs here
    PetscCall(BuildEffects(lat_, nullptr, &fx));
    PetscCall(fx.RequireConservative("-study linear (the normal modes of K)"));
    PetscFunctionReturn(0);
  }
  PetscErrorCode Solve() override
  {
    PetscFunctionBeginUser;
    PetscCall(modes_.Compute(lat_, mo_));
    PetscCall(PetscLogEventBegin(Log().bloch, 0, 0, 0, 0));
    bl_ = ComputeBloch(lp_, nq_);
    PetscCall(PetscLogEventEnd(Log().bloch, 0, 0, 0, 0));
    be_ = InfiniteBandEdges(lp_);
    const NamedModes &nm = modes_.Named();
    PetscCall(PetscPrintf(comm_, "nltopo linear: N = %" PetscInt_FMT " (%s, Nc = %" PetscInt_FMT "), %zu eigenpairs (%s)\n", lat_.N(), LayoutName(lp_.layout),
                          lp_.cells, modes_.Omega().size(), modes_.Complete() ? "all" : "shift-invert near the band edges"));
    PetscCall(PetscPrintf(comm_, "  insulated omega      %.10f   (sqrt(k_hat) = %.10f)\n", (double)nm.insulated_omega, (double)std::sqrt(lp_.KHat())));
    PetscCall(PetscPrintf(comm_, "  interface omega      %.10f   (above the optical band)\n", (double)OmegaOf(modes_, nm.interface)));
    PetscCall(PetscPrintf(comm_, "  acoustic band        %.6f .. %.6f (finite top %.6f)\n", (double)be_.acoustic_bottom, (double)be_.acoustic_top,
                          (double)OmegaOf(modes_, nm.acoustic_top)));
    PetscCall(PetscPrintf(comm_, "  optical band         %.6f .. %.6f (finite %.6f .. %.6f)\n", (double)be_.optical_bottom, (double)be_.optical_top,
                          (double)OmegaOf(modes_, nm.optical_bottom), (double)OmegaOf(modes_, nm.optical_top)));
    PetscCall(PetscPrintf(comm_, "  Zak phase  left cell: acoustic %.6f optical %.6f | right cell: acoustic %.6f optical %.6f\n", (double)bl_.zak_left[0],
                          (double)bl_.zak_left[1], (double)bl_.zak_right[0], (double)bl_.zak_right[1]));
    if (gl_.n) { // without -linear_gamma_list nothing of the transition is computed
      PetscLogDouble t0, t1;
      PetscCall(PetscTime(&t0));
      PetscCall(PetscLogEventBegin(Log().transition, 0, 0, 0, 0));
      PetscCall(ComputeTransition(lp_, GammaGrid(gl_.lo, gl_.hi, gl_.n), nq_, &tr_));
      PetscCall(PetscLogEventEnd(Log().transition, 0, 0, 0, 0));
      PetscCall(PetscTime(&t1));
      PetscCall(PrintTransitionSummary(comm_, lp_, tr_, t1 - t0));
    }
    PetscFunctionReturn(0);
  }
  PetscErrorCode Write(PetscViewer v) override
  {
    const NamedModes &nm = modes_.Named();
    PetscFunctionBeginUser;
    PetscCall(WriteArray(v, "/linear", "omega", modes_.Omega()));
    // Mode j is row j of "modes" (or "modes_selected" when not all were computed).
    const char *mname = modes_.Complete() ? "modes" : "modes_selected";
    PetscCall(PetscViewerHDF5PushTimestepping(v));
    for (size_t j = 0; j < modes_.Omega().size(); j++) {
      PetscCall(PetscViewerHDF5SetTimestep(v, (PetscInt)j));
      PetscCall(WriteVec(v, "/linear", mname, modes_.Mode(j)));
    }
    PetscCall(PetscViewerHDF5PopTimestepping(v));
    if (modes_.Insulated()) PetscCall(WriteVec(v, "/linear", "insulated_mode", modes_.Insulated()));
    PetscCall(WriteAttr(v, "/linear", "insulated_omega", nm.insulated_omega));
    PetscCall(WriteAttr(v, "/linear", "interface_omega", OmegaOf(modes_, nm.interface)));
    PetscCall(WriteAttr(v, "/linear", "acoustic_top", OmegaOf(modes_, nm.acoustic_top)));
    PetscCall(WriteAttr(v, "/linear", "optical_bottom", OmegaOf(modes_, nm.optical_bottom)));
    PetscCall(WriteAttr(v, "/linear", "optical_top", OmegaOf(modes_, nm.optical_top)));
    PetscCall(WriteAttr(v, "/linear", "interface_index", nm.interface));
    PetscCall(WriteAttr(v, "/linear", "acoustic_top_index", nm.acoustic_top));
    PetscCall(WriteAttr(v, "/linear", "optical_bottom_index", nm.optical_bottom));
    PetscCall(WriteAttr(v, "/linear", "optical_top_index", nm.optical_top));
    PetscCall(WriteAttr(v, "/linear", "insulated_cluster", nm.insulated_cluster));
    PetscCall(WriteAttr(v, "/linear", "insulated_residual", nm.insulated_residual));
    PetscCall(WriteAttr(v, "/linear", "layout", LayoutName(lp_.layout)));
    PetscCall(WriteAttr(v, "/linear", "N", lat_.N()));
    PetscCall(WriteArray(v, "/linear/bloch", "q", bl_.q));
    PetscCall(WriteArray(v, "/linear/bloch", "omega_acoustic", bl_.omega_acoustic));
    PetscCall(WriteArray(v, "/linear/bloch", "omega_optical", bl_.omega_optical));
    PetscCall(WriteAttr(v, "/linear/bloch", "zak_left_acoustic", bl_.zak_left[0]));
    PetscCall(WriteAttr(v, "/linear/bloch", "zak_left_optical", bl_.zak_left[1]));
    PetscCall(WriteAttr(v, "/linear/bloch", "zak_right_acoustic", bl_.zak_right[0]));
    PetscCall(WriteAttr(v, "/linear/bloch", "zak_right_optical", bl_.zak_right[1]));
    PetscCall(WriteBandEdges(v, "/linear/bloch", be_));
    if (gl_.n) {
      const char *g = "/linear/transition";
      PetscCall(WriteArray(v, g, "gamma", tr_.gamma));
      PetscCall(WriteArray(v, g, "omega", tr_.omega, tr_.N));
      PetscCall(WriteArray(v, g, "zak_left", tr_.zak_left, 2));
      PetscCall(WriteArray(v, g, "zak_right", tr_.zak_right, 2));
      PetscCall(WriteArray(v, g, "bands_inf", tr_.bands_inf, 4));
      PetscCall(WriteArray(v, g, "lambda_min", tr_.lambda_min));
      PetscCall(WriteAttr(v, g, "N", tr_.N));
      PetscCall(WriteAttr(v, g, "layout", LayoutName(lp_.layout)));
      PetscCall(WriteAttr(v, g, "nq", nq_));
      PetscCall(WriteAttr(
          v, g, "zak_rule",
          "Wilson loop over 2 nq points of the Brillouin zone, wrapped to [-pi/2, 3 pi/2); NaN where k1 = k2 (gamma = 0: the gap closes, the Zak phase is undefined)"));
    }
    PetscFunctionReturn(0);
  }

private:
  LatticeParams lp_;
  LinearModesOptions mo_;
  PetscInt nq_ = LinearStudyOptions().nq;
  GammaList gl_; // -linear_gamma_list (n = 0: off)
  TransitionResult tr_;
  Lattice lat_;
  LinearModes modes_;
  BlochResult bl_{};
  BandEdges be_{};
};

} // namespace

StudyContract LinearStudyContract()
{
  using namespace schema_names;
  return {{"-lattice_", "-linear_"},
          {{"/linear",
            "",
            {{"omega", D, R, "N", "rad/time", "finite-lattice frequencies, ascending"},
             {"modes", D, R, "N x N", "1", "row j: mode j"},
             {"modes_selected", D, R, "nsel x N", "1", "shift-invert path: the computed modes only"},
             {"insulated_mode", D, R, "N", "1", "the insulated mode"},
             {"insulated_omega", A, R, "scalar", "rad/time", "frequency of the insulated mode"},
             {"interface_omega", A, R, "scalar", "rad/time", "frequency of the interface mode"},
             {"acoustic_top", A, R, "scalar", "rad/time", "finite lattice: acoustic band top"},
             {"optical_bottom", A, R, "scalar", "rad/time", "finite lattice: optical band bottom"},
             {"optical_top", A, R, "scalar", "rad/time", "finite lattice: optical band top"},
             {"interface_index", A, I, "scalar", "1", "mode index of interface_omega (-1: none)"},
             {"acoustic_top_index", A, I, "scalar", "1", "mode index of acoustic_top"},
             {"optical_bottom_index", A, I, "scalar", "1", "mode index of optical_bottom"},
             {"optical_top_index", A, I, "scalar", "1", "mode index of optical_top"},
             {"insulated_cluster", A, I, "scalar", "1", "eigenpairs in the k_hat cluster"},
             {"insulated_residual", A, R, "scalar", "1", "||K x - omega^2 x|| of the insulated mode"},
             {"layout", A, S, "scalar", "1", "lattice layout"},
             {"N", A, I, "scalar", "1", "sites"}}},
           {"/linear/bloch", "",
            WithBandEdges({{"q", D, R, "nq", "rad", "Bloch wavenumbers"},
                           {"omega_acoustic", D, R, "nq", "rad/time", "acoustic band"},
                           {"omega_optical", D, R, "nq", "rad/time", "optical band"},
                           {"zak_left_acoustic", A, R, "scalar", "rad", "Zak phase, left cell, acoustic (wrapped to [-pi/2, 3 pi/2))"},
                           {"zak_left_optical", A, R, "scalar", "rad", "Zak phase, left cell, optical"},
                           {"zak_right_acoustic", A, R, "scalar", "rad", "Zak phase, right cell, acoustic"},
                           {"zak_right_optical", A, R, "scalar", "rad", "Zak phase, right cell, optical"}})},
           {"/linear/transition",
            "",
            {{"gamma", D, R, "ng", "1", "dimerisation values of -linear_gamma_list"},
             {"omega", D, R, "ng x N", "rad/time", "finite-lattice frequencies at each gamma, ascending"},
             {"zak_left", D, R, "ng x 2", "rad", "Zak phase of the left cell (intra k2, inter k1): acoustic, optical; NaN where k1 = k2"},
             {"zak_right", D, R, "ng x 2", "rad", "Zak phase of the right cell (intra k1, inter k2): acoustic, optical; NaN where k1 = k2"},
             {"bands_inf", D, R, "ng x 4", "rad/time", "infinite lattice at each gamma: acoustic bottom, top, optical bottom, top (rad/s)"},
             {"lambda_min", D, R, "ng", "(rad/time)^2", "smallest eigenvalue of K at each gamma (< 0: K not positive definite, omega clamped to 0 there)"},
             {"N", A, I, "scalar", "1", "sites"},
             {"layout", A, S, "scalar", "1", "lattice layout"},
             {"nq", A, I, "scalar", "1", "-linear_nq: the Zak loop uses 2 nq points"},
             {"zak_rule", A, S, "scalar", "1", "how the Zak phases were computed, and what NaN means"}}}}};
}

std::unique_ptr<Study> CreateLinearStudy() { return std::make_unique<LinearStudy>(); }

} // namespace nltopo
