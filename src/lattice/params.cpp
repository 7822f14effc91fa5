#include "lattice/params.hpp"
#include "effects/effect.hpp"
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

PetscErrorCode LatticeParamsFromOptions(MPI_Comm comm, LatticeParams *p)
{
  PetscInt layout = static_cast<PetscInt>(p->layout), pert = static_cast<PetscInt>(p->perturbation);
  PetscFunctionBeginUser;
  PetscOptionsBegin(comm, "lattice_", "Lattice model (shared/spec/model.md)", NULL);
  PetscCall(PetscOptionsReal("-k", "Base coupling k", NULL, p->k, &p->k, NULL));
  PetscCall(PetscOptionsReal("-gamma", "Dimerisation gamma: k1 = k(1+gamma) stiff, k2 = k(1-gamma) soft", NULL, p->gamma, &p->gamma, NULL));
  PetscCall(PetscOptionsReal("-gamma0", "Grounding stiffness gamma0", NULL, p->gamma0, &p->gamma0, NULL));
  // model.md's Gamma. Not "-lattice_Gamma": PETSc option names are case-insensitive,
  // so that name IS -lattice_gamma (README.md, "Option names").
  PetscCall(PetscOptionsReal("-cubic", "Cubic coefficient Gamma on every stiff bond (0 = linear lattice)", NULL, p->Gamma, &p->Gamma, NULL));
  PetscCall(PetscOptionsInt("-cells", "Unit cells per side Nc, at most 2.5e6 (interface: N = 4 Nc + 2; left/right: N = 2 Nc)", NULL, p->cells, &p->cells, NULL));
  PetscCall(PetscOptionsEList("-layout", "Lattice layout", NULL, kLayoutNames, 3, kLayoutNames[layout], &layout, NULL));
  PetscCall(PetscOptionsEList("-perturbation", "Random spring perturbation (README.md): chiral keeps diag(K) = k_hat, achiral varies every spring", NULL,
                              kPerturbationNames, 3, kPerturbationNames[pert], &pert, NULL));
  PetscCall(PetscOptionsReal("-delta", "Perturbation level: springs change by k delta_b, delta_b uniform in (-2 delta, 2 delta) (mean |delta_b| = delta)", NULL,
                             p->delta, &p->delta, NULL));
  PetscCall(PetscOptionsInt("-seed", "Seed of the perturbation's realisation", NULL, p->seed, &p->seed, NULL));
  PetscOptionsEnd();
  p->layout = static_cast<Layout>(layout);
  p->perturbation = static_cast<Perturbation>(pert);
  PetscCheck(std::isfinite(p->delta) && p->delta >= 0 && p->delta < 0.5, comm, PETSC_ERR_USER, "-lattice_delta must lie in [0, 0.5), got %g", (double)p->delta);

  // 2.5e6 cells: N ~ 10^7 sites, a few GB for a forced run (the state, TS stages, K and L); more would exhaust memory
  PetscCheck(p->cells >= 1 && p->cells <= kMaxCells, comm, PETSC_ERR_USER, "-lattice_cells must lie in 1..%d, got %" PetscInt_FMT, (int)kMaxCells, p->cells);
  PetscCheck(std::isfinite(p->k) && p->k > 0, comm, PETSC_ERR_USER, "-lattice_k must be a positive stiffness, got %g", (double)p->k);
  PetscCheck(p->k >= 1e-6 && p->k <= 1e6, comm, PETSC_ERR_USER, "-lattice_k must lie in [1e-6, 1e6], got %g", (double)p->k);
  PetscCheck(std::isfinite(p->gamma) && p->gamma > -1 && p->gamma < 1, comm, PETSC_ERR_USER,
             "-lattice_gamma must lie in (-1, 1) so that k1 = k(1+gamma) and k2 = k(1-gamma) are positive stiffnesses, got %g", (double)p->gamma);
  PetscCheck(std::isfinite(p->gamma0) && p->gamma0 >= 0, comm, PETSC_ERR_USER, "-lattice_gamma0 must be a non-negative stiffness, got %g", (double)p->gamma0);
  PetscCheck(p->gamma0 <= 1e6, comm, PETSC_ERR_USER, "-lattice_gamma0 must lie in [0, 1e6], got %g", (double)p->gamma0);
  PetscCheck(std::isfinite(p->Gamma) && std::abs(p->Gamma) <= 1e6, comm, PETSC_ERR_USER, "-lattice_cubic must lie in [-1e6, 1e6], got %g", (double)p->Gamma);
  PetscCall(EffectOptionsFromOptions(comm)); // the optional effects' options (-lattice_damping, ...): every study reads them, so a conservative one can refuse them by name
  PetscFunctionReturn(0);
}

} // namespace nltopo
