#pragma once
// /continuation/<branch> of outputs.md: what the continuation study keeps per
// branch, written and read back (-cont_resume) by one table of columns bound
// to the fields of the group's schema (io/schema.cpp).
#include "orbits/continuation.hpp"
#include "stability/bifurcations.hpp"
#include "stability/codim2.hpp"
#include "stability/floquet_hooks.hpp" // FloquetColumns
#include "stability/krein_map.hpp"
#include "io/schema.hpp"
#include <string>
#include <vector>

namespace nltopo {

// Everything /continuation/<label> holds: the branch, its Floquet data (dense
// or matrix-free hook) and its cost.
struct BranchRecord {
  std::string label;
  std::string parent;           // -cont_switch: the branch point or period doubling it starts from, "<branch>:<event>"; empty for a linear mode's
  PetscInt period_multiple = 1; // its orbits last this many periods of the parent's orbit at the event (2: born at a period doubling)
  PetscReal omega = 0, seconds = 0;
  Branch b;
  FloquetColumns f;
  PetscInt jac = 0, res = 0, tan = 0, kry = 0;
  // -cont_bifurcations: the located events (written when located is set)
  bool located = false;
  std::vector<BifurcationEvent> events;
  PetscReal bif_tol = 0, bif_seconds = 0;
  PetscInt bif_probes = 0;
  // -cont_codim2: the curves of its events in (E, p) (/continuation/<branch>/codim2/<curve>)
  std::vector<Codim2Curve> codim2;
  // the linear frequencies of the Krein resonance map (written with -floquet when set; the study's, outlives the record)
  const KreinSpectrum *krein = nullptr;
};

enum class FloquetKind { None, Dense, MatrixFree };

// The schema variants of a route: "" and, with Floquet, "floquet" or "floquet_mf".
std::vector<const char *> ContinuationVariants(FloquetKind fk);
// The names the column table binds (tests: it covers the schema exactly).
std::vector<std::string> ContinuationColumnNames();

// One curve of -cont_codim2 into group g, by the fields of the schema at
// schema_path (a Codim2Schema: /continuation/<branch>/codim2/<curve>, or
// the stability map's copy of it).
PetscErrorCode WriteCodim2CurveAt(PetscViewer v, const std::string &g, const char *schema_path, const Codim2Curve &c);
// The schema of one such curve, at path (studies/continuation_contract.cpp).
Schema Codim2Schema(const char *path);

// n2 = 2N, nev = -floquet_mf_nev.
PetscErrorCode WriteRecord(PetscViewer v, const BranchRecord &r, FloquetKind fk, PetscInt n2, PetscInt nev);

// -cont_resume: /continuation/<label> of an earlier output (complete or a
// checkpoint) as a Branch (z0 rows on rank 0, the rest on every rank) and its
// Floquet columns; found is false when the file has no such branch. Floquet
// data the file lacks (it was written without -floquet) become NaN / 0 (-1 for
// -floquet_mf's stable and instability: not decided, not computed). mf_route:
// the route this run's -floquet_mf takes ("dense" or "matrix-free"); a file
// whose multipliers another route computed is refused.
PetscErrorCode ReadResume(MPI_Comm comm, const std::string &file, const std::string &label, FloquetKind fk, PetscInt n2, PetscInt nev, Branch *b,
                          FloquetColumns *f, bool *found, const std::string &mf_route = "");

} // namespace nltopo
