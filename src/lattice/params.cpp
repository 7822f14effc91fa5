#include "lattice/params.hpp"
#include <cmath>

namespace nltopo {

static const char *const kLayoutNames[] = {"interface", "left", "right"};

const char *LayoutName(Layout l) { return kLayoutNames[static_cast<int>(l)]; }

PetscErrorCode LatticeParamsFromOptions(MPI_Comm comm, LatticeParams *p)
{
  PetscInt layout = static_cast<PetscInt>(p->layout);
  PetscFunctionBeginUser;
  PetscOptionsBegin(comm, "lattice_", "Lattice model (shared/spec/model.md)", NULL);
  PetscCall(PetscOptionsReal("-k", "Base coupling k", NULL, p->k, &p->k, NULL));
  PetscCall(PetscOptionsReal("-gamma", "Dimerisation gamma: k1 = k(1+gamma) stiff, k2 = k(1-gamma) soft", NULL, p->gamma, &p->gamma, NULL));
  PetscCall(PetscOptionsReal("-gamma0", "Grounding stiffness gamma0", NULL, p->gamma0, &p->gamma0, NULL));
  // model.md's Gamma. Not "-lattice_Gamma": PETSc option names are case-insensitive,
  // so that name IS -lattice_gamma (README.md, "Option names").
  PetscCall(PetscOptionsReal("-cubic", "Cubic coefficient Gamma on every stiff bond (0 = linear lattice)", NULL, p->Gamma, &p->Gamma, NULL));
  PetscCall(PetscOptionsInt("-cells", "Unit cells per side Nc (interface: N = 4 Nc + 2; left/right: N = 2 Nc)", NULL, p->cells, &p->cells, NULL));
  PetscCall(PetscOptionsEList("-layout", "Lattice layout", NULL, kLayoutNames, 3, kLayoutNames[layout], &layout, NULL));
  PetscOptionsEnd();
  p->layout = static_cast<Layout>(layout);

  PetscCheck(p->cells >= 1 && p->cells <= (PETSC_MAX_INT - 2) / 4, comm, PETSC_ERR_USER, "-lattice_cells must lie in 1..%d, got %" PetscInt_FMT,
             (int)((PETSC_MAX_INT - 2) / 4), p->cells);
  PetscCheck(std::isfinite(p->k) && p->k > 0, comm, PETSC_ERR_USER, "-lattice_k must be a positive stiffness, got %g", (double)p->k);
  PetscCheck(std::isfinite(p->gamma) && p->gamma > -1 && p->gamma < 1, comm, PETSC_ERR_USER,
             "-lattice_gamma must lie in (-1, 1) so that k1 = k(1+gamma) and k2 = k(1-gamma) are positive stiffnesses, got %g", (double)p->gamma);
  PetscCheck(std::isfinite(p->gamma0) && p->gamma0 >= 0, comm, PETSC_ERR_USER, "-lattice_gamma0 must be a non-negative stiffness, got %g", (double)p->gamma0);
  PetscCheck(std::isfinite(p->Gamma), comm, PETSC_ERR_USER, "-lattice_cubic must be finite, got %g", (double)p->Gamma);
  PetscFunctionReturn(0);
}

} // namespace nltopo
