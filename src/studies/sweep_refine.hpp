#pragma once
// Adaptive refinement of a sweep (-sweep_refine_from, docs/studies/sweep.md
// "Adaptive refinement"): one level of an (omega, log E*) quadtree per run.
//
// The points of every level lie on a fine lattice: the base grid's axes with
// the midpoints of their intervals inserted `depth` times (omega's linear
// midpoint; E*'s geometric one on a log axis, else its linear one). A point of
// depth d has lattice coordinates that are multiples of 2^(depth - d). A cell
// of depth d is a square of side 2^(depth - d) whose four corners are sampled
// (the base grid's cells at depth 0, quarter cells below); it is a leaf while
// its centre is not sampled. A level refines the leaves whose corners' scores
// differ by more than the thresholds: it adds their missing edge midpoints and
// their centre, at depth d + 1. The fine lattice of the new level is one depth
// deeper than the previous file's; earlier points keep their values (the
// previous file's, bit for bit).
#include "studies/grid_axis.hpp"
#include "studies/sweep_store.hpp"
#include <petscsys.h>
#include <petscviewer.h>
#include <string>
#include <vector>

namespace nltopo {

struct SweepRefineOptions {
  std::string from;        // -sweep_refine_from: the previous level's (or the base grid's) complete sweep file; "": no refinement
  PetscReal mcr = 0.02;    // -sweep_refine_mcr: absolute MCR difference
  PetscReal kcorr = 0.3;   // -sweep_refine_kcorr: K difference (with -sweep_kcorr)
  PetscReal ratio = 1.0;   // -sweep_refine_ratio: difference of ln(nl_ratio)
  PetscInt max_points = 0; // -sweep_refine_max_points: at most this many new points (0: no cap)
  bool On() const { return !from.empty(); }
};

// The base axis x with the midpoints of its intervals inserted depth times.
std::vector<PetscReal> RefinedAxis(const std::vector<PetscReal> &x, bool log_midpoints, PetscInt depth);

// The refinement's picture of a fine lattice (no x ne points at depth `depth`,
// row-major like a sweep grid: energy row e, omega column w -> e * no + w).
struct RefineLattice {
  size_t no = 0, ne = 0;
  PetscInt depth = 0;
  size_t Index(size_t e, size_t w) const { return e * no + w; }
  // the depth at which the point of lattice index i was introduced
  PetscInt LevelOf(size_t i) const;
};

// What SelectRefinement found: the leaves over a threshold, those refined
// (the budget may stop short) and the new points, as lattice indices, ascending.
struct RefineSelection {
  size_t leaves = 0, over = 0, refined = 0;
  PetscInt by_mcr = 0, by_kcorr = 0, by_ratio = 0, by_predictable = 0; // refined cells per reason (a cell may count for several)
  std::vector<size_t> points;
};

// The leaves of the lattice g (sampled points: done = 1, the others absent,
// at depth lat.depth whose deepest points have depth lat.depth - 1) whose
// corners' scores differ by more than the thresholds, refined largest
// difference first up to the budget (docs/studies/sweep.md). kcorr_on: the
// file holds K.
RefineSelection SelectRefinement(const SweepGrid &g, const RefineLattice &lat, const SweepRefineOptions &o, bool kcorr_on);

} // namespace nltopo

namespace nltopo {

// Rank 0: "" if path may seed a refinement level of this run, else one line
// naming -sweep_refine_from, the file and why not: missing, not an nltopo
// sweep (or merged sweep) output, partial (complete = 0), another format
// version, or another scene (the first option that differs by the resume rule).
std::string RefineSourceProblem(const std::string &path);

// Rank 0: loads the complete sweep file path (a grid, a merged shard set, or
// a refinement level's output, /sweep/refined) of the base axes omega x
// energy into *g, the fine lattice one depth below the file's (*lat): its
// samples done = 1 with the file's values, every other point absent (done 0).
PetscErrorCode LoadRefineSource(const std::string &path, const std::vector<PetscReal> &omega, const std::vector<PetscReal> &energy, bool log_energy,
                                SweepGrid *g, RefineLattice *lat);

// Rank 0, -sweep_resume of a level: the points of the partial output path
// (its /sweep/refined samples done, on the lattice lat) that are among g's points.
PetscErrorCode LoadRefinedPartial(const std::string &path, const RefineLattice &lat, SweepGrid *g);

// Writes /sweep/refined: every point of g (g.points) as scattered samples.
PetscErrorCode WriteRefinedSamples(PetscViewer w, const SweepGrid &g, const RefineLattice &lat);

} // namespace nltopo
