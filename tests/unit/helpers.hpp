#pragma once
// Shared helpers for the unit tests (every test runs on 1 and 2 ranks, but
// those tagged [serial]: tests/CMakeLists.txt).
#include "effects/effect.hpp"
#include "lattice/lattice.hpp"
#include <catch2/catch.hpp>
#include <petscsys.h>
#include <initializer_list>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#define PCHK(...) REQUIRE((__VA_ARGS__) == 0)

namespace nltopo::test {

// The scene's effects on lat (effects/effect.hpp): the lattice's own, the
// burst's forcing if given, and the optional effects the options enable.
inline std::unique_ptr<EffectList> Effects(const Lattice &lat, ToneBurst *burst = nullptr)
{
  auto fx = std::make_unique<EffectList>(lat);
  PCHK(BuildEffects(lat, burst, fx.get()));
  return fx;
}

inline int Rank()
{
  int r;
  MPI_Comm_rank(PETSC_COMM_WORLD, &r);
  return r;
}

// A global vector as a std::vector on every rank.
inline std::vector<PetscReal> Gather(Vec x)
{
  Vec s;
  VecScatter sc;
  const PetscScalar *a;
  PetscInt n;
  VecScatterCreateToAll(x, &sc, &s);
  VecScatterBegin(sc, x, s, INSERT_VALUES, SCATTER_FORWARD);
  VecScatterEnd(sc, x, s, INSERT_VALUES, SCATTER_FORWARD);
  VecGetSize(s, &n);
  VecGetArrayRead(s, &a);
  std::vector<PetscReal> v(a, a + n);
  VecRestoreArrayRead(s, &a);
  VecScatterDestroy(&sc);
  VecDestroy(&s);
  return v;
}

// Sets x from a full std::vector (same on every rank).
inline void Scatter(const std::vector<PetscReal> &v, Vec x)
{
  PetscInt lo, hi;
  PetscScalar *a;
  VecGetOwnershipRange(x, &lo, &hi);
  VecGetArray(x, &a);
  for (PetscInt i = lo; i < hi; i++) a[i - lo] = v[i];
  VecRestoreArray(x, &a);
}

// Fills the state vector z from full u and v (same on every rank).
inline void SetState(const Lattice &lat, const std::vector<PetscReal> &u, const std::vector<PetscReal> &v, Vec z)
{
  for (PetscInt i = lat.OwnedStart(); i < lat.OwnedStart() + lat.OwnedCount(); i++) {
    VecSetValue(z, lat.StateIndexU(i), u[i], INSERT_VALUES);
    VecSetValue(z, lat.StateIndexV(i), v[i], INSERT_VALUES);
  }
  VecAssemblyBegin(z);
  VecAssemblyEnd(z);
}

// Splits a state vector into full u and v on every rank.
inline void GetState(const Lattice &lat, Vec z, std::vector<PetscReal> *u, std::vector<PetscReal> *v)
{
  const auto all = Gather(z);
  const PetscInt N = lat.N();
  u->resize(N);
  v->resize(N);
  for (PetscInt i = 0; i < N; i++) {
    (*u)[i] = all[lat.StateIndexU(i)];
    (*v)[i] = all[lat.StateIndexV(i)];
  }
}

// Deterministic pseudo-random numbers in (-1, 1), identical on all ranks.
inline std::vector<PetscReal> Pseudo(size_t n, unsigned seed)
{
  std::vector<PetscReal> v(n);
  unsigned s = seed * 2654435761u + 12345u;
  for (auto &x : v) {
    s = s * 1664525u + 1013904223u;
    x = 2.0 * (s >> 8) / double(1u << 24) - 1.0;
  }
  return v;
}

// Sets PETSc options for the duration of a scope.
struct ScopedOptions {
  std::vector<std::string> names;
  ScopedOptions(std::initializer_list<std::pair<const char *, const char *>> kv)
  {
    for (auto &p : kv) {
      PetscOptionsSetValue(NULL, p.first, p.second);
      names.push_back(p.first);
    }
  }
  ~ScopedOptions()
  {
    for (auto &n : names) PetscOptionsClearValue(NULL, n.c_str());
  }
};

} // namespace nltopo::test
