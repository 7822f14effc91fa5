#include "timeint/ts_acceleration.hpp"

namespace nltopo {

namespace {

struct Acceleration {
  AccelerationFn fn = nullptr;
  void *ctx = nullptr;
};

PetscErrorCode DestroyAcceleration(void *p)
{
  delete static_cast<Acceleration *>(p);
  return 0;
}

} // namespace

PetscErrorCode TSSetAcceleration(TS ts, AccelerationFn f, void *ctx)
{
  PetscContainer c;
  PetscFunctionBegin;
  PetscCall(PetscContainerCreate(PetscObjectComm((PetscObject)ts), &c));
  PetscCall(PetscContainerSetPointer(c, new Acceleration{f, ctx}));
  PetscCall(PetscContainerSetUserDestroy(c, DestroyAcceleration));
  PetscCall(PetscObjectCompose((PetscObject)ts, "nltopo_acceleration", (PetscObject)c));
  PetscCall(PetscContainerDestroy(&c));
  PetscFunctionReturn(0);
}

PetscErrorCode TSGetAcceleration(TS ts, AccelerationFn *f, void **ctx)
{
  PetscContainer c;
  PetscFunctionBegin;
  *f = nullptr;
  if (ctx) *ctx = nullptr;
  PetscCall(PetscObjectQuery((PetscObject)ts, "nltopo_acceleration", (PetscObject *)&c));
  if (c) {
    void *p;
    PetscCall(PetscContainerGetPointer(c, &p));
    *f = static_cast<Acceleration *>(p)->fn;
    if (ctx) *ctx = static_cast<Acceleration *>(p)->ctx;
  }
  PetscFunctionReturn(0);
}

} // namespace nltopo
