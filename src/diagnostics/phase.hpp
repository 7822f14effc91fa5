#pragma once
// Phase of a sampled oscillation at a known frequency (model.md "Diagnostics"):
// the argument of its Fourier coefficient c = sum_k x(t_k) e^{-i omega t_k}
// over a window of whole periods sampled uniformly, where the coefficient of a
// pure tone at omega is exact (the other harmonics are orthogonal to it).
#include <petscsys.h>

namespace nltopo {

// x[k * stride] sampled at t_k = t0 + k dt, k = 0..n-1. Returns arg(c) in (-pi, pi].
PetscReal FourierPhase(const PetscReal *x, PetscInt n, PetscInt stride, PetscReal t0, PetscReal dt, PetscReal omega);

// The phase difference wrapped to [-pi/2, 3 pi/2): both 0 and pi lie inside,
// so values near either do not split across the cut (model.md).
PetscReal WrapDimerPhase(PetscReal phi);

} // namespace nltopo
