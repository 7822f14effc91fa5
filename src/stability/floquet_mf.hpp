#pragma once
// Matrix-free Floquet multipliers for long lattices: SLEPc Krylov-Schur on a
// MATSHELL whose MatMult is the monodromy action M x = dz(T)/dz0 x, one
// tangent-linear integration of the orbit per product (PeriodicFlow::
// IntegrateWithTangent); the 2N x 2N monodromy is never formed. Options:
// -floquet_mf_nev (leading multipliers wanted), -floquet_mf_eps_* (the solver).
#include "orbits/flow.hpp"
#include <vector>

namespace nltopo {

// A shell for M at the orbit (z0, T, beta). The flow, z0 and the shell must
// outlive its use; products() counts the integrations.
class MonodromyShell {
public:
  PetscErrorCode Create(PeriodicFlow &flow, Vec z0, PetscReal T, PetscReal beta);
  Mat Get() const { return M_; }
  PetscInt Products() const { return products_; }
  PetscErrorCode Mult(Vec x, Vec y);

private:
  PeriodicFlow *flow_ = nullptr;
  Vec z0_ = nullptr;
  PetscReal T_ = 0, beta_ = 0;
  PetscInt products_ = 0;
  OwnedMat M_;
  OwnedVec zT_;
};

struct LeadingMultipliers {
  std::vector<PetscReal> re, im; // by decreasing modulus
  PetscInt products = 0;         // monodromy actions used
};

// The nev multipliers of largest modulus (EPS_LARGEST_MAGNITUDE, Krylov-Schur).
PetscErrorCode FloquetLeading(PeriodicFlow &flow, Vec z0, PetscReal T, PetscReal beta, PetscInt nev, LeadingMultipliers *r);

} // namespace nltopo
