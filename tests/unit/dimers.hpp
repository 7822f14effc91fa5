#pragma once
// Two stiff dimers joined by a weak soft bond (layout right, Nc = 2, gamma =
// 0.9): two weakly coupled identical hardening oscillators, mirror-symmetric,
// whose upper optical NNM loses stability in a pitchfork that first-order
// averaging predicts (test_floquet.cpp, test_bifurcations.cpp).
#include "nnm_fixture.hpp"

namespace nltopo::test {

struct CoupledDimers : NnmFixture {
  PetscErrorCode Setup()
  {
    LatticeParams p;
    p.layout = Layout::Right;
    p.cells = 2;
    p.gamma = 0.9;
    return NnmFixture::Setup(p);
  }
  // The NNM family of linear mode j up to omega_max, in small steps (to resolve the onset).
  PetscErrorCode Continue(PetscInt j, PetscReal omega_max, PointHook *hook, Branch *out = nullptr)
  {
    ContinuationOptions co;
    Branch b;
    co.verbose = PETSC_FALSE;
    co.max_change = 0.05;
    co.omega_max = omega_max;
    return NnmFixture::Continue(j, co, out ? out : &b, hook);
  }
};

} // namespace nltopo::test
