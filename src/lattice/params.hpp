#pragma once
// Parameters of the SSH interface lattice and the bond rule of model.md.
// Sites and bonds are 0-based here: bond b joins sites b and b+1 (model.md's
// bond i = b+1 joins sites i and i+1, 1-based).
#include <petscsys.h>
#include <vector>

namespace nltopo {

enum class Layout { Interface = 0, Left = 1, Right = 2 };
// Random stiffness perturbations (paper, "Robustness to perturbations"):
// chiral: every bond k_b -> k_b + k delta_b with the grounding adjusted so that
// the diagonal of K stays k_hat (K - k_hat I keeps its chiral, bipartite form);
// achiral: every bond and every grounding spring g_i -> g_i + k delta_i, the
// diagonal following. delta uniform in (-2 delta, 2 delta): mean |delta| = delta.
enum class Perturbation { None = 0, Chiral = 1, Achiral = 2 };

struct LatticeParams {
  PetscReal k = 1.0;      // base coupling
  PetscReal gamma = 0.4;  // dimerisation: k1 = k(1+gamma) stiff, k2 = k(1-gamma) soft
  PetscReal gamma0 = 1.0; // grounding stiffness
  PetscReal Gamma = 0.5;  // cubic coefficient on every stiff bond
  PetscInt cells = 25;    // Nc, unit cells per side
  Layout layout = Layout::Interface;
  Perturbation perturbation = Perturbation::None;
  PetscReal delta = 0; // mean |relative perturbation| of the springs
  PetscInt seed = 1;   // realisation of the perturbation (the same on any number of ranks)

  PetscReal K1() const { return k * (1 + gamma); }
  PetscReal K2() const { return k * (1 - gamma); }
  // Uniform diagonal of K (model.md: k_hat for EVERY site, ends and interface included).
  PetscReal KHat() const { return K1() + K2() + gamma0; }
  PetscInt N() const { return layout == Layout::Interface ? 4 * cells + 2 : 2 * cells; }
  // 0-based index of the interface site m (model.md: m = 2 Nc + 1, 1-based).
  PetscInt InterfaceSite() const { return 2 * cells; }

  // Whether bond b (0-based) is a stiff (k1) bond, by position (model.md "Bonds").
  bool Stiff(PetscInt b) const
  {
    const PetscInt i = b + 1; // model.md's 1-based bond index
    const bool odd = (i % 2) == 1;
    switch (layout) {
    case Layout::Left: return !odd; // 1-2 soft, then alternating
    case Layout::Right: return odd; // 1-2 stiff, then alternating
    case Layout::Interface:
    default: return i <= 2 * cells ? !odd : odd;
    }
  }
  PetscReal Bond(PetscInt b) const { return Stiff(b) ? K1() : K2(); }
};

const char *LayoutName(Layout l);
const char *PerturbationName(Perturbation p);

// The springs of the (possibly perturbed) lattice: bonds[b] for b = 0..N-2 and
// the diagonal of K, diag[i] = sum of the bonds at i + grounding g_i, for
// i = 0..N-1. Deterministic in (params, seed): every rank builds the same.
void LatticeSprings(const LatticeParams &p, std::vector<PetscReal> *bonds, std::vector<PetscReal> *diag);

// Reads the -lattice_* options of the geometry and the springs and validates
// them (errors name the option); the studies read the whole lattice model,
// effects included, with LatticeModelFromOptions (effects/effect.hpp).
PetscErrorCode LatticeParamsFromOptions(MPI_Comm comm, LatticeParams *p);

} // namespace nltopo
