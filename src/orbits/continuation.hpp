#pragma once
// Pseudo-arclength continuation of an NNM family in X = (z0, T, beta):
// tangent predictor X + ds t, Newton corrector with the arclength constraint
// t . (X - X_pred) = 0 and the Poincare phase condition through the previous
// orbit, tangent of the family from J t = e_last (oriented along the previous
// tangent, so folds in T or E are passed, not reversed), adaptive ds from the
// Newton iteration count and a maximum relative change of the orbit per step.
// Stops at -cont_energy_max, -cont_omega_max or -cont_mcr_min, after
// -cont_max_points, or when ds collapses (reported, never silent). A drop of the shape correlation between
// consecutive orbits flags a modal interaction.
#include "orbits/shooting.hpp"

namespace nltopo {

struct ContinuationOptions {
  PetscReal energy_min = 1e-5, energy_max = 1e3;
  PetscReal omega_max = 0; // stop once omega exceeds this (0: no limit)
  PetscReal mcr_min = 0;   // stop once the MCR falls below this: the mode has delocalized (0: no limit)
  PetscInt max_points = 1000;
  PetscReal max_change = 0.2;       // max ||z0_new - z0_old|| / ||z0_old|| per step
  PetscReal ds_min = 1e-9;          // relative to ||z0||: below it the branch stops
  PetscInt newton_target = 4;       // grow ds below, shrink above
  PetscReal interaction_corr = 0.9; // shape correlation below this flags a modal interaction
  PetscBool verbose = PETSC_TRUE;
  PetscReal progress = 10; // seconds between progress lines (core/progress.hpp; 0: none), also of the bifurcation location
};
PetscErrorCode ContinuationOptionsFromOptions(MPI_Comm comm, ContinuationOptions *o);

// One orbit of a branch: its value in each per-point column of Branch.
struct BranchPoint {
  PetscReal energy = 0, omega = 0, period = 0, mcr = 0, shape_corr = 1, beta = 0;
  PetscInt newton_its = 0, krylov_its = 0;
};

struct Branch {
  std::vector<PetscReal> energy, omega, period, mcr, shape_corr, beta; // kPointColumns
  std::vector<PetscInt> newton_its, krylov_its;                        // per point (krylov: the mf route's GMRES iterations, 0 for dense LU)
  std::vector<PetscReal> z0;                                           // rank 0: npts x 2N rows [u_1..u_N, v_1..v_N]
  std::vector<PetscInt> interactions;                                  // point indices flagged as modal interactions
  std::string stop_reason;
  bool reached_max = false;
  // Where the continuation stands after the last point: the family tangent
  // there (rank 0, natural order [du_1..du_N, dv_1..dv_N, dT, dbeta]) and the
  // next step length. A resume from them takes the steps an uninterrupted run
  // takes, bit for bit (docs/errors.md "Resume rules").
  std::vector<PetscReal> next_tangent;
  PetscReal next_ds = 0;

  // p and its z0 row (rank 0: 2N values, other ranks: none) as the last point;
  // DropLast removes the last point (n2 = 2N).
  void Append(const BranchPoint &p, const std::vector<PetscReal> &z0_row);
  void DropLast(PetscInt n2);
};

// The per-point columns of Branch besides z0, each once: its name (the
// /continuation/<branch> dataset, studies/continuation_record.cpp) and where a
// Branch and a BranchPoint keep it (reals or ints).
struct PointColumn {
  const char *name;
  std::vector<PetscReal> Branch::*reals;
  PetscReal BranchPoint::*real;
  std::vector<PetscInt> Branch::*ints;
  PetscInt BranchPoint::*integer;
};
// clang-format off
inline constexpr PointColumn kPointColumns[] = {
  {"energy", &Branch::energy, &BranchPoint::energy, nullptr, nullptr},
  {"omega", &Branch::omega, &BranchPoint::omega, nullptr, nullptr},
  {"period", &Branch::period, &BranchPoint::period, nullptr, nullptr},
  {"mcr", &Branch::mcr, &BranchPoint::mcr, nullptr, nullptr},
  {"shape_corr", &Branch::shape_corr, &BranchPoint::shape_corr, nullptr, nullptr},
  {"beta", &Branch::beta, &BranchPoint::beta, nullptr, nullptr},
  {"newton_its", nullptr, nullptr, &Branch::newton_its, &BranchPoint::newton_its},
  {"krylov_its", nullptr, nullptr, &Branch::krylov_its, &BranchPoint::krylov_its},
};
// clang-format on

// A state z in natural order [u_1..u_N, v_1..v_N]: appended to rank 0's row
// store (other ranks: unchanged), or set from a row every rank holds.
PetscErrorCode AppendStateRow(const Lattice &lat, Vec z, std::vector<PetscReal> *rows);
PetscErrorCode StateFromRow(const Lattice &lat, const PetscReal *row, Vec z);
// MCR of the displacement part of z (model.md's MCR on u0, as a branch records it).
PetscErrorCode DisplacementMcr(const Lattice &lat, Vec z, PetscReal *mcr);
// The point of orbit X = (z0, T, beta) (z <- z0): energy, period, omega, beta
// and MCR; shape_corr 1 and the iteration counts 0 (the caller's to set).
PetscErrorCode OrbitPoint(Shooting &shoot, Vec X, Vec z, BranchPoint *p);
// b->Append(p, the z0 row of z).
PetscErrorCode AppendPoint(const Lattice &lat, Vec z, const BranchPoint &p, Branch *b);

// Called at every accepted orbit (z0, T, beta), e.g. for its Floquet
// multipliers. dz0 is the state part of the family tangent there (the
// generalized eigenvector of the trivial Floquet pair: (M - I) dz0 = -dT f(z0)).
class PointHook {
public:
  virtual ~PointHook() = default;
  virtual PetscErrorCode Point(Vec z0, PetscReal T, PetscReal beta, Vec dz0) = 0;
};

// Continues the family through the orbit guess (u_guess, v = 0) of period T_guess,
// or, given a resume branch of at least 2 points (as written by a previous run,
// z0 rows on rank 0), from its last orbit on: its points are kept; with the
// stored next_tangent and next_ds the continuation goes on exactly where it
// stood, otherwise (files written before they were stored) the last orbit is
// re-solved at its energy and the first step has the length of the last one.
// A stop signal (core/signals.hpp) returns the silent PETSC_ERR_SIG from the
// solve in progress; *b then holds every point recorded so far.
PetscErrorCode ContinueBranch(Shooting &shoot, Vec u_guess, PetscReal T_guess, const ContinuationOptions &o, const char *name, Branch *b,
                              PointHook *hook = nullptr, const Branch *resume = nullptr);

} // namespace nltopo
