// MCR: 1/N for a uniform vector, 1 for a single excited site (paper's MCR definition).
#include "diagnostics/mcr.hpp"
#include "helpers.hpp"

using namespace nltopo;

TEST_CASE("MCR of a uniform vector is 1/N and of a single site is 1", "[diagnostics]")
{
  const PetscInt N = 102;
  OwnedVec u;
  PCHK(VecCreateMPI(PETSC_COMM_WORLD, PETSC_DECIDE, N, u.out()));
  PetscReal mcr;
  PCHK(VecSet(u, 0.7));
  PCHK(Mcr(u, &mcr));
  REQUIRE(mcr == Approx(1.0 / N).epsilon(1e-14));
  PCHK(VecSet(u, 0.0));
  PCHK(VecSetValue(u, 60, -2.5, INSERT_VALUES)); // owned by rank 1 at np 2
  PCHK(VecAssemblyBegin(u));
  PCHK(VecAssemblyEnd(u));
  PCHK(Mcr(u, &mcr));
  REQUIRE(mcr == Approx(1.0).epsilon(1e-14));
}
