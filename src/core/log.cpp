#include "core/log.hpp"
#include <map>
#include <string>

namespace nltopo {

static LogEvents g_log;
static bool g_registered = false;

PetscErrorCode LogRegister()
{
  PetscFunctionBeginUser;
  if (g_registered) PetscFunctionReturn(0);
  PetscCall(PetscClassIdRegister("nltopo", &g_log.classid));
  const PetscClassId cid = g_log.classid;
  PetscCall(PetscLogEventRegister("Energy", cid, &g_log.energy));
  PetscCall(PetscLogEventRegister("StateJacobian", cid, &g_log.jacobian));
  PetscCall(PetscLogEventRegister("LinearModes", cid, &g_log.eigen));
  PetscCall(PetscLogEventRegister("BlochZak", cid, &g_log.bloch));
  PetscCall(PetscLogEventRegister("OutputHDF5", cid, &g_log.output));
  PetscCall(PetscLogEventRegister("Diagnostics", cid, &g_log.diagnostics));
  PetscCall(PetscLogEventRegister("VariationalRhs", cid, &g_log.variational));
  PetscCall(PetscLogEventRegister("Floquet", cid, &g_log.floquet));
  PetscCall(PetscLogEventRegister("FloquetEigvals", cid, &g_log.floquet_eigenvalues));
  PetscCall(PetscLogEventRegister("Bifurcations", cid, &g_log.bifurcations));
  PetscCall(PetscLogEventRegister("ShootLinPC", cid, &g_log.mf_pc));
  PetscCall(PetscLogEventRegister("LinearTransition", cid, &g_log.transition));
  PetscCall(PetscLogStageRegister("Setup", &g_log.setup));
  PetscCall(PetscLogStageRegister("Solve", &g_log.solve));
  PetscCall(PetscLogStageRegister("Write", &g_log.write));
  g_registered = true;
  PetscFunctionReturn(0);
}

const LogEvents &Log() { return g_log; }

PetscErrorCode NamedLogEvent(const char *name, PetscLogEvent *ev)
{
  static std::map<std::string, PetscLogEvent> events;
  PetscFunctionBeginUser;
  auto it = events.find(name);
  if (it == events.end()) {
    PetscLogEvent e;
    PetscCall(PetscLogEventRegister(name, Log().classid, &e));
    it = events.emplace(name, e).first;
  }
  *ev = it->second;
  PetscFunctionReturn(0);
}

} // namespace nltopo
