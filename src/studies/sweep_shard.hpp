#pragma once
// Shards of a sweep (-sweep_shard i/n, docs/studies/sweep.md "Shards and
// merge"): share i of n of the grid, so that n independent runs (a job array,
// a shell loop) compute one map that -study merge joins.
//
// The split is deterministic: every shard computes the whole assignment from
// the grid and the scene, and keeps its own part. It balances a cost model,
// not measured times: a point at E* costs
//     c(E*) = max(1, (E* / E_q)^(1/4)),
// the number of steps of its run relative to a run below E_q. Above E_q the
// quartic energy dominates, the lattice's frequencies grow as E*^(1/4), and so
// does the number of steps a run needs: exactly so for the fixed-step
// splittings with -sim_dt_quartic_energy E_q (timeint/simulation.cpp
// SetFixedStep), approximately for adaptive integrators. Without
// -sim_dt_quartic_energy, E_q = k1^2 / (2 |Gamma|), the energy of a stiff
// bond at which its cubic force equals its linear one (uniform cost for a
// linear lattice). Within an energy row every point costs the same: what
// depends on omega (the amplitude rule's repeats, the 0-1 test's continued
// record, -sweep_mcr_tol's extra runs at chaotic points) is not known before
// the run. The points, most expensive first (highest E*, then highest omega:
// the order in which a sweep hands them out), each go to the shard with the
// least cost so far (the lowest index among equals): the longest-processing-
// time rule, so the shards' costs differ by at most one point's cost. Costs
// are rounded to integers (thousandths) and summed exactly, so the last bits
// of pow on another machine do not change the split (short of a cost at
// exactly half a thousandth); shards of different splits would be refused by
// -study merge (a point in two shards, or in none).
#include "lattice/params.hpp"
#include <petscsys.h>
#include <string>
#include <vector>

namespace nltopo {

struct SweepShard {
  PetscInt index = 0, count = 0; // count 0: the whole grid (no -sweep_shard)
  bool On() const { return count > 0; }
};

// -sweep_shard's text "i/n" (0 <= i < n <= points, the grid's size); "" is the
// whole grid. One line naming the option and the value otherwise.
PetscErrorCode ParseSweepShard(MPI_Comm comm, const std::string &text, size_t points, SweepShard *shard);

// E_q of the cost model: -sim_dt_quartic_energy when positive, else k1^2 / (2 |Gamma|) (0: Gamma = 0, uniform cost).
PetscReal SweepCostEnergy(const LatticeParams &lp, PetscReal dt_quartic_energy);
// The integer cost (thousandths) of a point at E*.
long SweepPointCost(PetscReal energy, PetscReal e_q);

// The grid indices (row-major: energy row e, omega column w -> e * no + w) of
// shard s of the grid energy x omega, ascending; *share = its part of the
// total cost (0..1).
std::vector<size_t> SweepShardPoints(const std::vector<PetscReal> &energy, size_t no, PetscReal e_q, const SweepShard &s, double *share = nullptr);

} // namespace nltopo
