#pragma once
// Wall-clock seconds for the benchmark drivers (PETSc's timer), and the
// median they quote.
#include <petscsys.h>
#include <algorithm>
#include <vector>

inline double Now()
{
  PetscLogDouble t;
  PetscTime(&t);
  return t;
}

inline double Median(std::vector<double> x)
{
  std::sort(x.begin(), x.end());
  const size_t n = x.size();
  return n % 2 ? x[n / 2] : 0.5 * (x[n / 2 - 1] + x[n / 2]);
}
