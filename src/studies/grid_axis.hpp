#pragma once
// A grid axis from options: -<prefix><name>_min/_max/_n/_spacing (linear or
// log, ends included), or an explicit -<prefix><name>_list, which replaces
// them. Its rows go into the caller's option table (core/option_table.hpp),
// bound to fields of the caller's options struct (their initializers are the
// axis's defaults); GridAxisFromTable makes the values after the table's Read.
#include "core/option_table.hpp"
#include <string>
#include <vector>

namespace nltopo {

enum class AxisSpacing { Linear, Log };
inline constexpr const char *kAxisSpacingNames[2] = {"linear", "log"};

// Axis values are frequencies or energies: a sane physical range. The size
// bound keeps a grid (and its output) to what a run can hold.
constexpr PetscReal kAxisMin = 1e-12, kAxisMax = 1e12;
constexpr PetscInt kAxisMaxPoints = 100000, kAxisMaxList = 4096;

// The fields of one axis in the options struct S; name: "omega" (-<prefix>omega_min, ...).
template <class S> struct GridAxisFields {
  const char *name;
  PetscReal S::*min, S::*max;
  PetscInt S::*n;
  AxisSpacing S::*spacing;
  std::vector<PetscReal> S::*list;
};

// The axis's five rows (class Physics: a grid is what a run computes).
template <class S> OptionTable<S> &GridAxisRows(OptionTable<S> &t, const GridAxisFields<S> &f)
{
  const std::string a = f.name;
  t.Real((a + "_min").c_str(), f.min, Closed(kAxisMin, kAxisMax), ("Lower end of the " + a + " axis").c_str())
      .Real((a + "_max").c_str(), f.max, Closed(kAxisMin, kAxisMax), ("Upper end of the " + a + " axis").c_str())
      .Int((a + "_n").c_str(), f.n, Closed(1, kAxisMaxPoints), ("Number of " + a + " values (ends included)").c_str())
      .Why("the grid and its output are held in memory")
      .Enum((a + "_spacing").c_str(), f.spacing, kAxisSpacingNames, 2, ("Spacing of the " + a + " axis").c_str())
      .RealList((a + "_list").c_str(), f.list, kAxisMaxList, Closed(kAxisMin, kAxisMax), ("Explicit " + a + " values (replaces min/max/n)").c_str())
      .Default("none (min/max/n)");
  return t;
}

// The values of the axis -<prefix><name>: the list when given (list_given), else min..max in n points.
PetscErrorCode GridAxis(MPI_Comm comm, const std::string &option, PetscReal min, PetscReal max, PetscInt n, AxisSpacing spacing,
                        const std::vector<PetscReal> &list, bool list_given, std::vector<PetscReal> *axis);

// The same from the struct s that table t (prefix: its prefix, "sweep_") read, with Read's set.
template <class S>
PetscErrorCode GridAxisFromTable(MPI_Comm comm, const char *prefix, const OptionTable<S> &t, const std::vector<PetscBool> &set, const S &s,
                                 const GridAxisFields<S> &f, std::vector<PetscReal> *axis)
{
  const bool list_given = t.Given(set, (std::string(f.name) + "_list").c_str());
  return GridAxis(comm, std::string("-") + prefix + f.name, s.*f.min, s.*f.max, s.*f.n, s.*f.spacing, s.*f.list, list_given, axis);
}

} // namespace nltopo
