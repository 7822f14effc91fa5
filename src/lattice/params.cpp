#include "lattice/params.hpp"
#include "core/option_table.hpp"
#include <cmath>
#include <random>

namespace nltopo {

static const PetscInt kMaxCells = 2500000;

static const char *const kLayoutNames[] = {"interface", "left", "right"};

static const char *const kPerturbationNames[] = {"none", "chiral", "achiral"};

const char *LayoutName(Layout l) { return kLayoutNames[static_cast<int>(l)]; }
const char *PerturbationName(Perturbation p) { return kPerturbationNames[static_cast<int>(p)]; }

void LatticeSprings(const LatticeParams &p, std::vector<PetscReal> *bonds, std::vector<PetscReal> *diag)
{
  const PetscInt N = p.N();
  bonds->assign(N > 1 ? N - 1 : 0, 0.0);
  diag->assign(N, p.KHat());
  for (PetscInt b = 0; b < N - 1; b++) (*bonds)[b] = p.Bond(b);
  if (p.perturbation == Perturbation::None || p.delta == 0) return;
  // One stream: the bond draws first, then (achiral) the grounding draws.
  std::mt19937_64 gen((unsigned long long)p.seed);
  std::uniform_real_distribution<double> d(-2 * p.delta, 2 * p.delta);
  std::vector<PetscReal> ground(N);
  for (PetscInt i = 0; i < N; i++) // unperturbed grounding: k_hat minus the bonds at i
    ground[i] = p.KHat() - (i > 0 ? (*bonds)[i - 1] : 0) - (i < N - 1 ? (*bonds)[i] : 0);
  for (PetscInt b = 0; b < N - 1; b++) (*bonds)[b] += p.k * d(gen);
  if (p.perturbation == Perturbation::Chiral) return; // diagonal stays k_hat: the grounding absorbs the change
  for (PetscInt i = 0; i < N; i++) {
    ground[i] += p.k * d(gen);
    (*diag)[i] = ground[i] + (i > 0 ? (*bonds)[i - 1] : 0) + (i < N - 1 ? (*bonds)[i] : 0);
  }
}

// The -lattice_* block of the geometry and the springs (model.md's parameters);
// the cubic bonds read -lattice_cubic themselves (effects/lattice_effects.cpp).
static const auto &kLatticeTable = DeclareOptionTable<LatticeParams>("lattice_", "Lattice model", [](OptionTable<LatticeParams> &t) {
  t.Real("k", &LatticeParams::k, Closed(1e-6, 1e6), "Base coupling k")
      .Why("a positive stiffness")
      .Real("gamma", &LatticeParams::gamma, Open(-1, 1), "Dimerisation gamma: k1 = k(1+gamma) stiff, k2 = k(1-gamma) soft")
      .Why("so that k1 = k(1+gamma) and k2 = k(1-gamma) are positive stiffnesses")
      .Real("gamma0", &LatticeParams::gamma0, Closed(0, 1e6), "Grounding stiffness gamma0")
      .Why("a non-negative stiffness")
      // 2.5e6 cells: N ~ 10^7 sites, a few GB for a forced run (the state, TS stages, K and L); more would exhaust memory
      .Int("cells", &LatticeParams::cells, Closed(1, kMaxCells), "Unit cells per side Nc, at most 2.5e6 (interface: N = 4 Nc + 2; left/right: N = 2 Nc)")
      .Enum("layout", &LatticeParams::layout, kLayoutNames, 3, "Lattice layout")
      .Enum("perturbation", &LatticeParams::perturbation, kPerturbationNames, 3,
            "Random spring perturbation (docs/model.md): chiral keeps diag(K) = k_hat, achiral varies every spring")
      .Real("delta", &LatticeParams::delta, RightOpen(0, 0.5),
            "Perturbation level: springs change by k delta_b, delta_b uniform in (-2 delta, 2 delta) (mean |delta_b| = delta)")
      .Int("seed", &LatticeParams::seed, Closed(PETSC_MIN_INT, PETSC_MAX_INT), "Seed of the perturbation's realisation");
});

PetscErrorCode LatticeParamsFromOptions(MPI_Comm comm, LatticeParams *p)
{
  PetscFunctionBeginUser;
  PetscCall(kLatticeTable.Read(comm, p));
  PetscFunctionReturn(0);
}

} // namespace nltopo
