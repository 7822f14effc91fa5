#pragma once
// Linear normal modes of K with SLEPc (EPS behind this small interface), and
// the rule that names the modes the paper uses (docs/studies/linear.md, "Mode identification").
#include "bands/bloch.hpp"
#include "lattice/lattice.hpp"
#include <string>
#include <vector>

namespace nltopo {

struct LinearModesOptions {
  PetscInt dense_max = 2000; // N above this: shift-invert around the band edges instead of all pairs
  PetscInt nev = 4;          // shift-invert: eigenpairs per target
  PetscReal offset = 1e-6;   // shift-invert: targets sit this far (relative) outside each band edge
};
PetscErrorCode LinearModesOptionsFromOptions(MPI_Comm comm, LinearModesOptions *o);
// Refuses the dense path (N <= o.dense_max: all N eigenpairs on every rank)
// where it would not fit in memory; Compute checks it, a study before any set-up.
PetscErrorCode CheckLinearModesMemory(MPI_Comm comm, PetscInt N, const LinearModesOptions &o);

// Indices (into Omega()) of the named modes; -1 when the layout has none.
struct NamedModes {
  PetscInt interface = -1, acoustic_top = -1, optical_bottom = -1, optical_top = -1;
  PetscReal insulated_omega = NAN;    // sqrt of the Rayleigh quotient of the projected insulated mode
  PetscInt insulated_cluster = 0;     // eigenpairs in the k_hat cluster it was projected from
  PetscReal insulated_residual = NAN; // ||K x - omega^2 x|| of the projected mode
};

class LinearModes {
public:
  PetscErrorCode Compute(const Lattice &lat, const LinearModesOptions &o);

  bool Complete() const { return complete_; }                    // all N eigenpairs
  const std::vector<PetscReal> &Omega() const { return omega_; } // ascending
  Vec Mode(PetscInt j) const { return modes_[j]; }               // unit 2-norm, largest entry positive
  PetscErrorCode CopyMode(PetscInt j, Vec x) const;
  // (phi_j . eta)^2 for every stored mode.
  PetscErrorCode Projections(Vec eta, std::vector<PetscReal> *proj2) const;

  const NamedModes &Named() const { return named_; }
  // The insulated mode: even-sublattice projection of the k_hat eigenspace
  // (model.md "Trap"); NULL if the layout has none.
  Vec Insulated() const { return insulated_; }

private:
  PetscErrorCode SolveAll(const Lattice &lat);
  PetscErrorCode SolveNear(const Lattice &lat, const LinearModesOptions &o);
  PetscErrorCode AppendPairs(const Lattice &lat, EPS eps, PetscInt nmax);
  PetscErrorCode SortAndNormalise();
  PetscErrorCode Identify(const Lattice &lat);

  bool complete_ = false;
  std::vector<PetscReal> omega_;
  std::vector<OwnedVec> modes_;
  OwnedVec insulated_;
  NamedModes named_;
};

// Why a lattice of these parameters has no insulated mode (Insulated() NULL),
// naming the option that decides it: a layout without an interface, gamma = 0
// (no gap), too few cells for the mode's decay length, or a perturbation that
// moved it; one sentence for an error message (issue 34, 13c).
std::string NoInsulatedModeReason(const LatticeParams &p);

} // namespace nltopo
