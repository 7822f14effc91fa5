#pragma once
// RAII ownership of PETSc/SLEPc handles: the destructor calls the matching
// XDestroy, so no study needs a hand-written teardown list.
#include <petscdm.h>
#include <petscmat.h>
#include <petscsnes.h>
#include <petscts.h>
#include <petscviewer.h>
#include <slepceps.h>
#include <utility>

namespace nltopo {

template <typename T, PetscErrorCode (*Destroy)(T *)> class Owned {
public:
  Owned() = default;
  explicit Owned(T h) : h_(h) {}
  ~Owned() { reset(); }
  Owned(const Owned &) = delete;
  Owned &operator=(const Owned &) = delete;
  Owned(Owned &&o) noexcept : h_(std::exchange(o.h_, nullptr)) {}
  Owned &operator=(Owned &&o) noexcept
  {
    if (this != &o) {
      reset();
      h_ = std::exchange(o.h_, nullptr);
    }
    return *this;
  }
  operator T() const { return h_; }
  T get() const { return h_; }
  // Address for PETSc "create" calls; releases any handle held before.
  T *out()
  {
    reset();
    return &h_;
  }
  void reset()
  {
    if (h_) (void)Destroy(&h_);
    h_ = nullptr;
  }
  // Gives up ownership (the caller destroys it and checks the error).
  T release() { return std::exchange(h_, nullptr); }
  explicit operator bool() const { return h_ != nullptr; }

private:
  T h_ = nullptr;
};

using OwnedVec = Owned<Vec, VecDestroy>;
using OwnedMat = Owned<Mat, MatDestroy>;
using OwnedDM = Owned<DM, DMDestroy>;
using OwnedTS = Owned<TS, TSDestroy>;
using OwnedSNES = Owned<SNES, SNESDestroy>;
using OwnedEPS = Owned<EPS, EPSDestroy>;
using OwnedIS = Owned<IS, ISDestroy>;
using OwnedViewer = Owned<PetscViewer, PetscViewerDestroy>;
using OwnedVecScatter = Owned<VecScatter, VecScatterDestroy>;
using OwnedRandom = Owned<PetscRandom, PetscRandomDestroy>;

} // namespace nltopo
