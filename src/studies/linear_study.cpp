// -study linear: eigenpairs of K, the named modes (README.md "Mode
// identification"), infinite-lattice Bloch bands and Zak phases; /linear of outputs.md.
#include "bands/linear_modes.hpp"
#include "effects/effect.hpp"
#include "core/log.hpp"
#include "core/options_audit.hpp"
#include "io/output.hpp"
#include "io/schema.hpp"
#include "studies/registry.hpp"
#include <petscviewerhdf5.h>
#include <cmath>

namespace nltopo {

static PetscReal OmegaOf(const LinearModes &m, PetscInt j) { return j >= 0 ? m.Omega()[j] : NAN; }

static const PetscInt kBlochDefaultNq = 201; // -linear_nq

static PetscErrorCode BlochOptionsFromOptions(MPI_Comm comm, PetscInt *nq)
{
  PetscFunctionBeginUser;
  PetscOptionsBegin(comm, "linear_", "Linear study", NULL);
  PetscCall(PetscOptionsInt("-nq", "Wavenumbers for the Bloch bands; the Zak loop uses 2 nq points", NULL, *nq, nq, NULL));
  PetscOptionsEnd();
  PetscCheck(*nq >= 4 && *nq <= 1000000, comm, PETSC_ERR_USER, "-linear_nq must lie in [4, 1e6], got %" PetscInt_FMT, *nq);
  PetscFunctionReturn(0);
}

PetscErrorCode LinearStudyOptions(MPI_Comm comm)
{
  LatticeParams lp;
  LinearModesOptions mo;
  PetscInt nq = kBlochDefaultNq;
  PetscFunctionBeginUser;
  PetscCall(LatticeParamsFromOptions(comm, &lp));
  PetscCall(LinearModesOptionsFromOptions(comm, &mo));
  PetscCall(BlochOptionsFromOptions(comm, &nq));
  PetscCall(DeclareEPS(comm, "linear_"));
  PetscCall(DeclareOutputOptions(comm, "linear"));
  PetscFunctionReturn(0);
}

PetscErrorCode LinearStudy(MPI_Comm comm)
{
  LatticeParams lp;
  LinearModesOptions mo;
  PetscInt nq = kBlochDefaultNq;
  std::string path;
  OutputFile out;
  Lattice lat;
  LinearModes modes;
  PetscLogDouble t_start, t_end;
  PetscFunctionBeginUser;
  PetscCall(PetscTime(&t_start));
  PetscCall(LogRegister());
  PetscCall(PetscLogStagePush(Log().setup));
  PetscCall(LatticeParamsFromOptions(comm, &lp));
  PetscCall(LinearModesOptionsFromOptions(comm, &mo));
  PetscCall(BlochOptionsFromOptions(comm, &nq));
  PetscCall(OutputPathFromOptions(comm, "linear", &path));
  PetscCall(out.Open(comm, path));
  PetscCall(lat.Setup(comm, lp));
  {
    EffectList fx(lat); // the undamped modes of K: no non-conservative effect belongs here
    PetscCall(BuildEffects(lat, nullptr, &fx));
    PetscCall(fx.RequireConservative("-study linear (the normal modes of K)"));
  }
  PetscCall(PetscLogStagePop());

  PetscCall(PetscLogStagePush(Log().solve));
  PetscCall(modes.Compute(lat, mo));
  PetscCall(PetscLogEventBegin(Log().bloch, 0, 0, 0, 0));
  const BlochResult bl = ComputeBloch(lp, nq);
  PetscCall(PetscLogEventEnd(Log().bloch, 0, 0, 0, 0));
  PetscCall(PetscLogStagePop());

  const NamedModes &nm = modes.Named();
  const BandEdges be = InfiniteBandEdges(lp);
  PetscCall(PetscPrintf(comm, "nltopo linear: N = %" PetscInt_FMT " (%s, Nc = %" PetscInt_FMT "), %zu eigenpairs (%s)\n", lat.N(), LayoutName(lp.layout),
                        lp.cells, modes.Omega().size(), modes.Complete() ? "all" : "shift-invert near the band edges"));
  PetscCall(PetscPrintf(comm, "  insulated omega      %.10f   (sqrt(k_hat) = %.10f)\n", (double)nm.insulated_omega, (double)std::sqrt(lp.KHat())));
  PetscCall(PetscPrintf(comm, "  interface omega      %.10f   (above the optical band)\n", (double)OmegaOf(modes, nm.interface)));
  PetscCall(PetscPrintf(comm, "  acoustic band        %.6f .. %.6f (finite top %.6f)\n", (double)be.acoustic_bottom, (double)be.acoustic_top,
                        (double)OmegaOf(modes, nm.acoustic_top)));
  PetscCall(PetscPrintf(comm, "  optical band         %.6f .. %.6f (finite %.6f .. %.6f)\n", (double)be.optical_bottom, (double)be.optical_top,
                        (double)OmegaOf(modes, nm.optical_bottom), (double)OmegaOf(modes, nm.optical_top)));
  PetscCall(PetscPrintf(comm, "  Zak phase  left cell: acoustic %.6f optical %.6f | right cell: acoustic %.6f optical %.6f\n", (double)bl.zak_left[0],
                        (double)bl.zak_left[1], (double)bl.zak_right[0], (double)bl.zak_right[1]));

  PetscCall(PetscLogStagePush(Log().write));
  PetscViewer v = out.Viewer();
  PetscCall(WriteArray(v, "/linear", "omega", modes.Omega()));
  // Mode j is row j of "modes" (or "modes_selected" when not all were computed).
  const char *mname = modes.Complete() ? "modes" : "modes_selected";
  PetscCall(PetscViewerHDF5PushTimestepping(v));
  for (size_t j = 0; j < modes.Omega().size(); j++) {
    PetscCall(PetscViewerHDF5SetTimestep(v, (PetscInt)j));
    PetscCall(WriteVec(v, "/linear", mname, modes.Mode(j)));
  }
  PetscCall(PetscViewerHDF5PopTimestepping(v));
  if (modes.Insulated()) PetscCall(WriteVec(v, "/linear", "insulated_mode", modes.Insulated()));
  PetscCall(WriteAttr(v, "/linear", "insulated_omega", nm.insulated_omega));
  PetscCall(WriteAttr(v, "/linear", "interface_omega", OmegaOf(modes, nm.interface)));
  PetscCall(WriteAttr(v, "/linear", "acoustic_top", OmegaOf(modes, nm.acoustic_top)));
  PetscCall(WriteAttr(v, "/linear", "optical_bottom", OmegaOf(modes, nm.optical_bottom)));
  PetscCall(WriteAttr(v, "/linear", "optical_top", OmegaOf(modes, nm.optical_top)));
  PetscCall(WriteAttr(v, "/linear", "interface_index", nm.interface));
  PetscCall(WriteAttr(v, "/linear", "acoustic_top_index", nm.acoustic_top));
  PetscCall(WriteAttr(v, "/linear", "optical_bottom_index", nm.optical_bottom));
  PetscCall(WriteAttr(v, "/linear", "optical_top_index", nm.optical_top));
  PetscCall(WriteAttr(v, "/linear", "insulated_cluster", nm.insulated_cluster));
  PetscCall(WriteAttr(v, "/linear", "insulated_residual", nm.insulated_residual));
  PetscCall(WriteAttr(v, "/linear", "layout", LayoutName(lp.layout)));
  PetscCall(WriteAttr(v, "/linear", "N", lat.N()));
  PetscCall(WriteArray(v, "/linear/bloch", "q", bl.q));
  PetscCall(WriteArray(v, "/linear/bloch", "omega_acoustic", bl.omega_acoustic));
  PetscCall(WriteArray(v, "/linear/bloch", "omega_optical", bl.omega_optical));
  PetscCall(WriteAttr(v, "/linear/bloch", "zak_left_acoustic", bl.zak_left[0]));
  PetscCall(WriteAttr(v, "/linear/bloch", "zak_left_optical", bl.zak_left[1]));
  PetscCall(WriteAttr(v, "/linear/bloch", "zak_right_acoustic", bl.zak_right[0]));
  PetscCall(WriteAttr(v, "/linear/bloch", "zak_right_optical", bl.zak_right[1]));
  PetscCall(WriteBandEdges(v, "/linear/bloch", be));
  PetscCall(PetscTime(&t_end));
  PetscCall(out.Commit("linear", t_end - t_start));
  PetscCall(PetscLogStagePop());
  PetscCall(PetscPrintf(comm, "  wrote %s\n", path.c_str()));
  PetscFunctionReturn(0);
}

} // namespace nltopo
