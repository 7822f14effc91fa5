// Linear viscous damping on every mass, a_i += -c v_i (-lattice_damping c):
// not conservative, velocity-dependent, absent when c = 0. Each normal mode
// of the linear lattice decays as exp(-c t / 2) in amplitude (uniform C = c I
// keeps the modes uncoupled).
#include "core/option_table.hpp"
#include "effects/effect.hpp"
#include <cmath>

namespace nltopo {

namespace {

class Damping : public Effect {
public:
  Damping(const Lattice &lat, PetscReal c) : c_(c), xs_(lat.OwnedStart()), xe_(lat.OwnedStart() + lat.OwnedCount()) {}
  const char *Name() const override { return "damping"; }
  const char *LogName() const override { return "RhsDamping"; }
  std::string EnabledBy() const override { return OptionText("-lattice_damping", c_); }
  bool Conservative() const override { return false; }
  bool VelocityDependent() const override { return true; }
  PetscLogDouble FlopsPerSite() const override { return 2; }
  void AddAcceleration(PetscReal, const PetscScalar *, const PetscScalar *v, PetscScalar *a) const override
  {
    for (PetscInt i = xs_; i < xe_; i++) a[i] -= c_ * v[i];
  }
  void AddDamping(PetscScalar *c) const override
  {
    for (PetscInt i = xs_; i < xe_; i++) c[i] += c_;
  }

private:
  PetscReal c_;
  PetscInt xs_, xe_;
};

} // namespace

struct DampingOptions {
  PetscReal c = 0;
};

static const auto &kDampingTable = DeclareOptionTable<DampingOptions>("lattice_", "Lattice damping", [](OptionTable<DampingOptions> &t) {
  t.Real("damping", &DampingOptions::c, Closed(0, 1e6), "Linear viscous damping c on every mass, a += -c v (0: none; refused by the conservative studies)");
});

PetscErrorCode DampingFromOptions(MPI_Comm comm, const Lattice *lat, std::unique_ptr<Effect> *e)
{
  DampingOptions o;
  PetscFunctionBeginUser;
  PetscCall(kDampingTable.Read(comm, &o));
  if (lat && o.c > 0) *e = std::make_unique<Damping>(*lat, o.c);
  PetscFunctionReturn(0);
}

} // namespace nltopo
