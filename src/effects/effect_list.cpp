#include "effects/effect.hpp"
#include "core/log.hpp"
#include "effects/forcing.hpp"
#include <cstdio>
#include <cstring>

namespace nltopo {

std::string OptionText(const char *name, PetscReal value)
{
  char buf[64];
  std::snprintf(buf, sizeof(buf), "%s %g", name, (double)value);
  return buf;
}

PetscErrorCode EffectList::Add(std::unique_ptr<Effect> e)
{
  PetscLogEvent ev;
  PetscFunctionBeginUser;
  if (!e) PetscFunctionReturn(0);
  PetscCall(LogRegister());
  PetscCall(PetscLogEventRegister(e->LogName(), Log().classid, &ev)); // the same id for the same name
  if (auto *f = dynamic_cast<ForcingEffect *>(e.get())) burst_ = f->Burst();
  events_.push_back(ev);
  fx_.push_back(std::move(e));
  PetscFunctionReturn(0);
}

void EffectList::Remove(const char *name)
{
  for (size_t k = 0; k < fx_.size(); k++)
    if (!std::strcmp(fx_[k]->Name(), name)) {
      if (dynamic_cast<ForcingEffect *>(fx_[k].get())) burst_ = nullptr;
      fx_.erase(fx_.begin() + k);
      events_.erase(events_.begin() + k);
      return;
    }
}

const Effect *EffectList::Find(const char *name) const
{
  for (const auto &e : fx_)
    if (!std::strcmp(e->Name(), name)) return e.get();
  return nullptr;
}

bool EffectList::Conservative() const
{
  for (const auto &e : fx_)
    if (!e->Conservative()) return false;
  return true;
}

bool EffectList::VelocityDependent() const
{
  for (const auto &e : fx_)
    if (e->VelocityDependent()) return true;
  return false;
}

PetscErrorCode EffectList::RequireConservative(const char *who) const
{
  PetscFunctionBeginUser;
  for (const auto &e : fx_)
    PetscCheck(e->Conservative(), lat_->Comm(), PETSC_ERR_USER, "%s needs a conservative lattice; %s adds the non-conservative %s effect (remove it)", who,
               e->EnabledBy().c_str(), e->Name());
  PetscFunctionReturn(0);
}

PetscErrorCode EffectList::RequirePositionOnly(const char *who) const
{
  PetscFunctionBeginUser;
  for (const auto &e : fx_)
    PetscCheck(!e->VelocityDependent(), lat_->Comm(), PETSC_ERR_USER,
               "%s integrates u'' = a(t, u); %s makes the force depend on the velocity (use an rk or implicit -sim_ts_type)", who, e->EnabledBy().c_str());
  PetscFunctionReturn(0);
}

PetscErrorCode EffectList::Acceleration(PetscReal t, const PetscScalar *u, const PetscScalar *v, PetscScalar *a, EffectCalls *calls) const
{
  const PetscInt xs = lat_->OwnedStart(), xm = lat_->OwnedCount();
  bool set = false;
  PetscFunctionBeginUser;
  for (size_t k = 0; k < fx_.size(); k++) {
    if (calls && !calls->on[k]) continue;
    const Effect &e = *fx_[k];
    PetscCall(PetscLogEventBegin(events_[k], 0, 0, 0, 0));
    if (calls) calls->count[k]++;
    if (!set && !e.SetAcceleration(t, u, v, a)) {
      for (PetscInt i = xs; i < xs + xm; i++) a[i] = 0;
      e.AddAcceleration(t, u, v, a);
    } else if (set) e.AddAcceleration(t, u, v, a);
    set = true;
    PetscCall(PetscLogFlops(e.FlopsPerSite() * xm));
    PetscCall(PetscLogEventEnd(events_[k], 0, 0, 0, 0));
  }
  if (!set)
    for (PetscInt i = xs; i < xs + xm; i++) a[i] = 0;
  PetscFunctionReturn(0);
}

void EffectList::Stiffness(const PetscScalar *u, PetscScalar *kd, PetscScalar *kb) const
{
  const PetscInt xs = lat_->OwnedStart(), xm = lat_->OwnedCount();
  for (PetscInt i = xs; i < xs + xm; i++) kd[i] = 0;
  for (PetscInt b = xs - 1; b < xs + xm; b++) kb[b] = 0;
  for (const auto &e : fx_) e->AddStiffness(u, kd, kb);
}

void EffectList::Damping(PetscScalar *c) const
{
  const PetscInt xs = lat_->OwnedStart(), xm = lat_->OwnedCount();
  for (PetscInt i = xs; i < xs + xm; i++) c[i] = 0;
  for (const auto &e : fx_) e->AddDamping(c);
}

PetscErrorCode EffectList::Energy(Vec z, EnergyParts *e) const
{
  const PetscScalar *u, *zl;
  Vec ul;
  EnergyParts loc;
  const PetscInt xm = lat_->OwnedCount();
  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(Log().energy, 0, 0, 0, 0));
  PetscCall(lat_->GetGhostedU(z, &ul, &u));
  PetscCall(VecGetArrayRead(z, &zl));
  const PetscScalar *v = zl + xm;
  PetscReal kin = 0;
#pragma omp simd reduction(+ : kin)
  for (PetscInt k = 0; k < xm; k++) kin += v[k] * v[k];
  loc.kinetic = 0.5 * kin; // unit masses
  for (const auto &f : fx_) f->AddEnergy(u, &loc);
  PetscCall(VecRestoreArrayRead(z, &zl));
  PetscCall(lat_->RestoreGhostedU(z, &ul, &u));
  if (lat_->Serial()) *e = loc;
  else {
    PetscReal in[3] = {loc.kinetic, loc.linear, loc.quartic}, out[3];
    PetscCallMPI(MPIU_Allreduce(in, out, 3, MPIU_REAL, MPIU_SUM, lat_->Comm()));
    e->kinetic = out[0];
    e->linear = out[1];
    e->quartic = out[2];
  }
  PetscCall(PetscLogEventEnd(Log().energy, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

PetscErrorCode EffectList::Assemble(const PetscScalar *u, Mat M, bool state_form, PetscReal beta) const
{
  const PetscInt xs = lat_->OwnedStart(), xm = lat_->OwnedCount();
  std::vector<PetscScalar> kd(xm), kb(xm + 1), c(state_form ? xm : 0);
  PetscFunctionBeginUser;
  Stiffness(u, kd.data() - xs, kb.data() - xs + 1);
  if (state_form) Damping(c.data() - xs);
  PetscCall(lat_->AssembleNearestNeighbour(kd.data() - xs, kb.data() - xs + 1, state_form ? c.data() - xs : NULL, M, !state_form, beta));
  PetscFunctionReturn(0);
}

PetscErrorCode EffectList::AssembleTangentStiffness(Vec u, Mat KT) const
{
  PetscFunctionBeginUser;
  if (!u) {
    PetscCall(Assemble(NULL, KT, false, 0));
    PetscFunctionReturn(0);
  }
  const PetscScalar *a;
  Vec ul;
  PetscCall(lat_->GetGhostedU(u, &ul, &a));
  PetscCall(Assemble(a, KT, false, 0));
  PetscCall(lat_->RestoreGhostedU(u, &ul, &a));
  PetscFunctionReturn(0);
}

PetscErrorCode EffectList::AssembleStateJacobian(Vec z, Mat A, PetscReal beta) const
{
  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(Log().jacobian, 0, 0, 0, 0));
  if (!z) {
    PetscCall(Assemble(NULL, A, true, beta));
  } else {
    const PetscScalar *a;
    Vec ul;
    PetscCall(lat_->GetGhostedU(z, &ul, &a));
    PetscCall(Assemble(a, A, true, beta));
    PetscCall(lat_->RestoreGhostedU(z, &ul, &a));
  }
  PetscCall(PetscLogEventEnd(Log().jacobian, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

} // namespace nltopo
