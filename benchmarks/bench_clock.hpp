#pragma once
// Wall-clock seconds for the benchmark drivers (PETSc's timer).
#include <petscsys.h>

inline double Now()
{
  PetscLogDouble t;
  PetscTime(&t);
  return t;
}
