#include "diagnostics/phase.hpp"
#include <cmath>

namespace nltopo {

PetscReal FourierPhase(const PetscReal *x, PetscInt n, PetscInt stride, PetscReal t0, PetscReal dt, PetscReal omega)
{
  PetscReal re = 0, im = 0;
  for (PetscInt k = 0; k < n; k++) {
    const PetscReal th = omega * (t0 + k * dt), v = x[k * stride];
    re += v * std::cos(th);
    im -= v * std::sin(th);
  }
  return std::atan2(im, re);
}

PetscReal WrapDimerPhase(PetscReal phi)
{
  const PetscReal two_pi = 2 * PETSC_PI;
  phi = std::fmod(phi + PETSC_PI / 2, two_pi);
  if (phi < 0) phi += two_pi;
  return phi - PETSC_PI / 2;
}

} // namespace nltopo
