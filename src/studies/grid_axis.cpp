#include "studies/grid_axis.hpp"
#include <cmath>

namespace nltopo {

// The rows checked each end, n and every list value (GridAxisRows); what is left is their order.
PetscErrorCode GridAxis(MPI_Comm comm, const std::string &option, PetscReal min, PetscReal max, PetscInt n, AxisSpacing spacing,
                        const std::vector<PetscReal> &list, bool list_given, std::vector<PetscReal> *axis)
{
  PetscFunctionBeginUser;
  axis->clear();
  if (list_given) {
    PetscCheck(!list.empty(), comm, PETSC_ERR_USER, "%s_list is empty", option.c_str());
    *axis = list;
    PetscFunctionReturn(0);
  }
  PetscCheck(min <= max, comm, PETSC_ERR_USER, "%s_min/_max must satisfy %g <= min <= max <= %g, got %g, %g", option.c_str(), (double)kAxisMin,
             (double)kAxisMax, (double)min, (double)max);
  for (PetscInt i = 0; i < n; i++) {
    const PetscReal s = n > 1 ? (PetscReal)i / (n - 1) : 0;
    axis->push_back(spacing == AxisSpacing::Log ? min * std::pow(max / min, s) : min + s * (max - min));
  }
  PetscFunctionReturn(0);
}

} // namespace nltopo
