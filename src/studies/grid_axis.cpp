#include "studies/grid_axis.hpp"
#include <cmath>

namespace nltopo {

// Axis values are frequencies or energies: a sane physical range. The size
// bound keeps a grid (and its output) to what a run can hold.
static const PetscReal kAxisMin = 1e-12, kAxisMax = 1e12;
static const PetscInt kAxisMaxPoints = 100000;

// An axis from -<name>_min/_max/_n/_spacing, or an explicit -<name>_list.
PetscErrorCode ReadAxis(PetscOptionItems *PetscOptionsObject, MPI_Comm comm, const char *prefix, const char *name, PetscReal lo, PetscReal hi, PetscInt n,
                        bool log_default, std::vector<PetscReal> *axis)
{
  char opt[64], help[128];
  PetscReal list[4096];
  PetscInt nlist = 4096;
  PetscBool set;
  const char *spacings[] = {"linear", "log"};
  PetscInt spacing = log_default ? 1 : 0;
  PetscFunctionBeginUser;
  PetscCall(PetscSNPrintf(opt, sizeof(opt), "-%s_min", name));
  PetscCall(PetscSNPrintf(help, sizeof(help), "Lower end of the %s axis", name));
  PetscCall(PetscOptionsReal(opt, help, NULL, lo, &lo, NULL));
  PetscCall(PetscSNPrintf(opt, sizeof(opt), "-%s_max", name));
  PetscCall(PetscSNPrintf(help, sizeof(help), "Upper end of the %s axis", name));
  PetscCall(PetscOptionsReal(opt, help, NULL, hi, &hi, NULL));
  PetscCall(PetscSNPrintf(opt, sizeof(opt), "-%s_n", name));
  PetscCall(PetscSNPrintf(help, sizeof(help), "Number of %s values (ends included)", name));
  PetscCall(PetscOptionsInt(opt, help, NULL, n, &n, NULL));
  PetscCall(PetscSNPrintf(opt, sizeof(opt), "-%s_spacing", name));
  PetscCall(PetscSNPrintf(help, sizeof(help), "Spacing of the %s axis", name));
  PetscCall(PetscOptionsEList(opt, help, NULL, spacings, 2, spacings[spacing], &spacing, NULL));
  PetscCall(PetscSNPrintf(opt, sizeof(opt), "-%s_list", name));
  PetscCall(PetscSNPrintf(help, sizeof(help), "Explicit %s values (replaces min/max/n)", name));
  PetscCall(PetscOptionsRealArray(opt, help, NULL, list, &nlist, &set));
  axis->clear();
  if (set) {
    PetscCheck(nlist > 0, comm, PETSC_ERR_USER, "-%s%s_list is empty", prefix, name);
    axis->assign(list, list + nlist);
    for (PetscReal v : *axis)
      PetscCheck(std::isfinite(v) && v >= kAxisMin && v <= kAxisMax, comm, PETSC_ERR_USER, "-%s%s_list: values must lie in [%g, %g], got %g", prefix, name,
                 (double)kAxisMin, (double)kAxisMax, (double)v);
    PetscFunctionReturn(0);
  }
  PetscCheck(n >= 1 && n <= kAxisMaxPoints, comm, PETSC_ERR_USER, "-%s%s_n must lie in [1, %d], got %" PetscInt_FMT, prefix, name, (int)kAxisMaxPoints, n);
  PetscCheck(lo >= kAxisMin && hi <= kAxisMax && lo <= hi, comm, PETSC_ERR_USER, "-%s%s_min/_max must satisfy %g <= min <= max <= %g, got %g, %g", prefix, name,
             (double)kAxisMin, (double)kAxisMax, (double)lo, (double)hi); // false for nan
  for (PetscInt i = 0; i < n; i++) {
    const PetscReal s = n > 1 ? (PetscReal)i / (n - 1) : 0;
    axis->push_back(spacing ? lo * std::pow(hi / lo, s) : lo + s * (hi - lo));
  }
  PetscFunctionReturn(0);
}

} // namespace nltopo
