#include "io/cost_card.hpp"
#include "core/cost.hpp"
#include "io/output.hpp"

namespace nltopo {

PetscErrorCode WriteCostCard(PetscViewer v, PetscReal wall_seconds)
{
  CostCard card;
  PetscFunctionBeginUser;
  PetscCall(CostCardOn(PetscObjectComm((PetscObject)v), &card));
  const char *grp = "/cost";
  PetscCall(WriteAttr(v, grp, "wall_seconds", wall_seconds));
  for (const CostEntry &e : card.entries) {
    if (!e.solves) continue;
    const std::string &p = e.prefix; // sim_..., nnm_...
    // the first solve's integrator (rank 0 of the output's communicator)
    PetscCall(WriteAttr(v, grp, (p + "integrator").c_str(), e.integrator.c_str()));
    PetscCall(WriteAttr(v, grp, (p + "accuracy").c_str(), e.accuracy.c_str()));
    PetscCall(WriteAttr(v, grp, (p + "solves").c_str(), e.solves));
    PetscCall(WriteAttr(v, grp, (p + "steps").c_str(), e.steps));
    PetscCall(WriteAttr(v, grp, (p + "rejected_steps").c_str(), e.rejected));
    PetscCall(WriteAttr(v, grp, (p + "force_evaluations").c_str(), e.evals));
    if (e.dt_max > 0) {
      PetscCall(WriteAttr(v, grp, (p + "dt_min").c_str(), e.dt_min));
      PetscCall(WriteAttr(v, grp, (p + "dt_max").c_str(), e.dt_max));
    }
  }
  PetscCall(WriteAttr(v, grp, "error_estimate", card.error));
  PetscCall(WriteAttr(v, grp, "error_estimate_of", card.error_what.c_str()));
  PetscFunctionReturn(0);
}

} // namespace nltopo
