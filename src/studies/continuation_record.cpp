#include "studies/continuation_record.hpp"
#include "core/errors.hpp"
#include "core/gather.hpp"
#include "io/input.hpp"
#include "io/output.hpp"
#include "io/schema.hpp"
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>

namespace nltopo {

namespace {

const char *const kGroup = "/continuation/<branch>";

// Where a record keeps a dataset: one of the three.
struct Cells {
  std::vector<PetscReal> *reals = nullptr;
  std::vector<PetscInt> *ints = nullptr; // written as the schema's type (newton_its: real)
  PetscReal *scalar = nullptr;           // a one-value dataset
  std::vector<std::string> *strings = nullptr;
};
struct AttrValue {
  PetscReal r = 0;
  PetscInt i = 0;
  std::string s;
};

enum : unsigned {
  kRank0 = 1,     // resume: kept on rank 0 only (not broadcast)
  kStepState = 2, // written once there are points; resume: read if present (files of older versions lack it)
  kInfOk = 4,     // resume: +inf is a value a run writes (a verdict's bound or e-folding time)
};

// One field of the schema and where BranchRecord keeps it: a dataset (data,
// or point: a per-point column of the branch, orbits/continuation.hpp) or an
// attribute (attr; written only, a resume recounts them).
struct Column {
  const char *name;
  unsigned flags;
  Cells (*data)(BranchRecord &);
  void (*attr)(const BranchRecord &, AttrValue *);
  const PointColumn *point = nullptr;
};

// clang-format off
const Column kColumns[] = {
  {"z0", kRank0, [](BranchRecord &r) { return Cells{&r.b.z0}; }, nullptr},
  {"interactions", 0, [](BranchRecord &r) { return Cells{nullptr, &r.b.interactions}; }, nullptr},
  {"next_tangent", kRank0 | kStepState, [](BranchRecord &r) { return Cells{&r.b.next_tangent}; }, nullptr},
  {"next_ds", kRank0 | kStepState, [](BranchRecord &r) { return Cells{nullptr, nullptr, &r.b.next_ds}; }, nullptr},
  {"multipliers_re", 0, [](BranchRecord &r) { return Cells{&r.f.re}; }, nullptr},
  {"multipliers_im", 0, [](BranchRecord &r) { return Cells{&r.f.im}; }, nullptr},
  {"krein", 0, [](BranchRecord &r) { return Cells{nullptr, &r.f.krein}; }, nullptr},
  {"max_modulus", 0, [](BranchRecord &r) { return Cells{&r.f.max_modulus}; }, nullptr},
  {"det_error", 0, [](BranchRecord &r) { return Cells{&r.f.det_error}; }, nullptr},
  {"stable", 0, [](BranchRecord &r) { return Cells{nullptr, &r.f.stable}; }, nullptr},
  {"instability", 0, [](BranchRecord &r) { return Cells{nullptr, &r.f.instability}; }, nullptr},
  {"verdict", 0, [](BranchRecord &r) { return Cells{nullptr, &r.f.verdict}; }, nullptr},
  {"verdict_bound", kInfOk, [](BranchRecord &r) { return Cells{&r.f.verdict_bound}; }, nullptr},
  {"verdict_efold", kInfOk, [](BranchRecord &r) { return Cells{&r.f.verdict_efold}; }, nullptr},
  {"verdict_reason", 0, [](BranchRecord &r) { return Cells{nullptr, nullptr, nullptr, &r.f.verdict_reason}; }, nullptr},
  {"linear_omega", 0, nullptr, [](const BranchRecord &r, AttrValue *a) { a->r = r.omega; }},
  {"parent", 0, nullptr, [](const BranchRecord &r, AttrValue *a) { a->s = r.parent; }},
  {"period_multiple", 0, nullptr, [](const BranchRecord &r, AttrValue *a) { a->i = r.period_multiple; }},
  {"stop_reason", 0, nullptr, [](const BranchRecord &r, AttrValue *a) { a->s = r.b.stop_reason; }},
  {"reached_energy_max", 0, nullptr, [](const BranchRecord &r, AttrValue *a) { a->i = r.b.reached_max; }},
  {"points", 0, nullptr, [](const BranchRecord &r, AttrValue *a) { a->i = (PetscInt)r.b.energy.size(); }},
  {"jacobian_evaluations", 0, nullptr, [](const BranchRecord &r, AttrValue *a) { a->i = r.jac; }},
  {"residual_evaluations", 0, nullptr, [](const BranchRecord &r, AttrValue *a) { a->i = r.res; }},
  {"tangent_products", 0, nullptr, [](const BranchRecord &r, AttrValue *a) { a->i = r.tan; }},
  {"krylov_iterations", 0, nullptr, [](const BranchRecord &r, AttrValue *a) { a->i = r.kry; }},
  {"seconds", 0, nullptr, [](const BranchRecord &r, AttrValue *a) { a->r = r.seconds; }},
  {"floquet_products", 0, nullptr, [](const BranchRecord &r, AttrValue *a) { a->i = r.f.products; }},
  {"floquet_unconverged", 0, nullptr, [](const BranchRecord &r, AttrValue *a) { a->i = r.f.unconverged; }},
  {"floquet_undecided", 0, nullptr, [](const BranchRecord &r, AttrValue *a) { a->i = (PetscInt)std::count(r.f.stable.begin(), r.f.stable.end(), -1); }},
  {"floquet_route", 0, nullptr, [](const BranchRecord &r, AttrValue *a) { a->s = r.f.route; }},
  // issue 35: the leading eigenvector's extent (floquet_hooks.hpp)
  {"leading_participation", 0, [](BranchRecord &r) { return Cells{&r.f.leading_participation}; }, nullptr},
  {"leading_edge_share", 0, [](BranchRecord &r) { return Cells{&r.f.leading_edge}; }, nullptr},
};
// clang-format on

// The branch's per-point columns, then kColumns.
const std::vector<Column> &AllColumns()
{
  static const std::vector<Column> all = [] {
    std::vector<Column> v;
    for (const PointColumn &p : kPointColumns) v.push_back({p.name, 0, nullptr, nullptr, &p});
    v.insert(v.end(), std::begin(kColumns), std::end(kColumns));
    return v;
  }();
  return all;
}

const Column *FindColumn(const char *name)
{
  for (const Column &c : AllColumns())
    if (!std::strcmp(c.name, name)) return &c;
  return nullptr;
}

bool HasData(const Column &c) { return c.data || c.point; }

Cells DataOf(const Column &c, BranchRecord &r)
{
  if (!c.point) return c.data(r);
  return c.point->reals ? Cells{&(r.b.*c.point->reals)} : Cells{nullptr, &(r.b.*c.point->ints)};
}

struct Bound {
  const Field *fd;
  const Column *c;
  bool floquet; // of a Floquet variant
};

// The fields of a route, each with its column.
PetscErrorCode Fields(MPI_Comm comm, FloquetKind fk, std::vector<Bound> *out)
{
  PetscFunctionBeginUser;
  out->clear();
  for (const char *variant : ContinuationVariants(fk)) {
    const Schema *s = FindSchema(kGroup, variant);
    PetscCheck(s, comm, PETSC_ERR_PLIB, "output schema (src/io/schema.cpp) has no %s variant \"%s\"", kGroup, variant);
    for (const Field &fd : s->fields) {
      const Column *c = FindColumn(fd.name);
      PetscCheck(c && (fd.kind == FieldKind::Dataset ? HasData(*c) : c->attr != nullptr), comm, PETSC_ERR_PLIB,
                 "%s %s/%s of the output schema has no column in studies/continuation_record.cpp", KindName(fd.kind), kGroup, fd.name);
      out->push_back({&fd, c, *variant != 0});
    }
  }
  PetscFunctionReturn(0);
}

// Values per row of a per-point dataset ("npts x 2N", "npts x nev"); 0: one-dimensional.
PetscInt RowLength(const char *shape, PetscInt n2, PetscInt nev)
{
  if (!std::strcmp(shape, "npts x 2N")) return n2;
  if (!std::strcmp(shape, "npts x nev")) return nev;
  return 0;
}

// /continuation/<branch>/bifurcations: each field of its schema from the events.
struct EventColumn {
  const char *name;
  PetscInt width; // values per event: 1, 2 (krein) or 0 for 2N (vector)
  void (*get)(const BifurcationEvent &, const BranchRecord &, PetscReal *);
};

// clang-format off
const EventColumn kEventColumns[] = {
  {"kind", 1, [](const BifurcationEvent &e, const BranchRecord &, PetscReal *x) { x[0] = (PetscReal)e.kind; }},
  {"energy", 1, [](const BifurcationEvent &e, const BranchRecord &, PetscReal *x) { x[0] = e.energy; }},
  {"omega", 1, [](const BifurcationEvent &e, const BranchRecord &, PetscReal *x) { x[0] = e.omega; }},
  {"s", 1, [](const BifurcationEvent &e, const BranchRecord &, PetscReal *x) { x[0] = e.s; }},
  {"multiplier_re", 1, [](const BifurcationEvent &e, const BranchRecord &, PetscReal *x) { x[0] = e.mu_re; }},
  {"multiplier_im", 1, [](const BifurcationEvent &e, const BranchRecord &, PetscReal *x) { x[0] = e.mu_im; }},
  {"krein", 2, [](const BifurcationEvent &e, const BranchRecord &, PetscReal *x) { x[0] = e.krein[0], x[1] = e.krein[1]; }},
  {"vector", 0, [](const BifurcationEvent &e, const BranchRecord &, PetscReal *x) { std::copy(e.vector.begin(), e.vector.end(), x); }},
  {"direction", 1, [](const BifurcationEvent &e, const BranchRecord &, PetscReal *x) { x[0] = (PetscReal)e.direction; }},
  {"point", 1, [](const BifurcationEvent &e, const BranchRecord &, PetscReal *x) { x[0] = (PetscReal)e.point; }},
  {"instability", 1, [](const BifurcationEvent &e, const BranchRecord &, PetscReal *x) { x[0] = (PetscReal)e.instability; }},
  {"omega_bracket", 1, [](const BifurcationEvent &e, const BranchRecord &, PetscReal *x) { x[0] = e.omega_bracket; }},
  {"resonance", 2, [](const BifurcationEvent &e, const BranchRecord &, PetscReal *x) { x[0] = (PetscReal)e.resonance[0], x[1] = (PetscReal)e.resonance[1]; }},
};
// clang-format on

PetscErrorCode WriteEvents(PetscViewer v, const BranchRecord &r, PetscInt n2)
{
  MPI_Comm comm = PetscObjectComm((PetscObject)v);
  const std::string g = "/continuation/" + r.label + "/bifurcations";
  const Schema *s = FindSchema("/continuation/<branch>/bifurcations");
  const PetscInt ne = (PetscInt)r.events.size();
  PetscFunctionBeginUser;
  PetscCheck(s, comm, PETSC_ERR_PLIB, "output schema (src/io/schema.cpp) has no /continuation/<branch>/bifurcations");
  for (const Field &fd : s->fields) {
    if (fd.kind == FieldKind::Attribute) {
      if (!std::strcmp(fd.name, "tol")) PetscCall(WriteAttr(v, g.c_str(), fd.name, r.bif_tol));
      else if (!std::strcmp(fd.name, "probes")) PetscCall(WriteAttr(v, g.c_str(), fd.name, r.bif_probes));
      else if (!std::strcmp(fd.name, "seconds")) PetscCall(WriteAttr(v, g.c_str(), fd.name, r.bif_seconds));
      else SETERRQ(comm, PETSC_ERR_PLIB, "attribute %s/%s of the output schema has no value in studies/continuation_record.cpp", g.c_str(), fd.name);
      continue;
    }
    const EventColumn *c = nullptr;
    for (const EventColumn &k : kEventColumns)
      if (!std::strcmp(k.name, fd.name)) c = &k;
    PetscCheck(c, comm, PETSC_ERR_PLIB, "dataset %s/%s of the output schema has no column in studies/continuation_record.cpp", g.c_str(), fd.name);
    const PetscInt w = c->width ? c->width : n2;
    std::vector<PetscReal> x((size_t)ne * w, NAN);
    for (PetscInt k = 0; k < ne; k++)
      if (c->width || r.events[k].vector.size() == (size_t)n2) c->get(r.events[k], r, x.data() + (size_t)k * w); // a fold's tangent or a vector not found: NaN
    if (fd.type == FieldType::Int) PetscCall(WriteIntArray(v, g.c_str(), fd.name, std::vector<PetscInt>(x.begin(), x.end()), w));
    else PetscCall(WriteArrayND(v, g.c_str(), fd.name, x, w == 1 ? std::vector<PetscInt>{ne} : std::vector<PetscInt>{ne, w}));
  }
  PetscFunctionReturn(0);
}

// /continuation/<branch>/krein_map (stability/krein_map.hpp): computed from
// the branch's energies and periods and the run's linear frequencies, so a
// resumed branch's map is recomputed whole.
PetscErrorCode WriteKreinMap(PetscViewer v, const BranchRecord &r)
{
  const std::string g = "/continuation/" + r.label + "/krein_map";
  const KreinMap m = ComputeKreinMap(*r.krein, r.omega, r.b.energy, r.b.period);
  std::string classes;
  for (int c = 0; c < kKreinPairClasses; c++) classes += std::string(c ? "," : "") + kKreinPairNames[c];
  PetscFunctionBeginUser;
  PetscCall(WriteIntArray(v, g.c_str(), "open", m.open, m.kmax, true));
  PetscCall(WriteArray(v, g.c_str(), "edge_omega", m.edges));
  PetscCall(WriteIntArray(v, g.c_str(), "energy_criterion", m.criterion));
  PetscCall(WriteArray(v, g.c_str(), "dE_domega", m.slope));
  PetscCall(WriteAttr(v, g.c_str(), "kmax", m.kmax));
  PetscCall(WriteAttr(v, g.c_str(), "pair_classes", classes.c_str()));
  PetscFunctionReturn(0);
}

// The first value of x that a stored resume state may not hold (x.size() if
// none): anything not finite, except NaN in a Floquet column (nan_ok), where it
// means "not computed" (outputs.md). Counts (ints) must also fit an int.
size_t FirstInvalid(const std::vector<PetscReal> &x, bool nan_ok, bool count, bool inf_ok = false)
{
  for (size_t i = 0; i < x.size(); i++) {
    if (nan_ok && std::isnan(x[i])) continue;
    if (inf_ok && std::isinf(x[i]) && x[i] > 0) continue; // (+inf only: no run writes -inf)
    if (!std::isfinite(x[i]) || (count && std::abs(x[i]) > (PetscReal)PETSC_MAX_INT)) return i;
  }
  return x.size();
}

// -cont_resume, rank 0: every dataset of /continuation/<label>/ (g) that the
// schema's fields bind, into rec. The branch's columns must be there; the step
// state and Floquet columns may not (files of older versions, or written
// without -floquet). A stored value that no run writes is refused in one
// line: a non-finite orbit, energy, period or step would send the
// continuation round without end (docs/errors.md "Resume rules").
PetscErrorCode ReadBranchColumns(const std::string &file, const std::string &g, const std::vector<Bound> &fields, PetscInt n2, BranchRecord *rec)
{
  Branch &rb = rec->b;
  bool has_tangent = false, has_ds = false;
  PetscFunctionBeginUser;
  for (const auto &[fd, c, floquet] : fields) {
    if (fd->kind != FieldKind::Dataset) continue;
    const std::string path = g + fd->name;
    if ((floquet || (c->flags & kStepState)) && !HasDataset(file, path.c_str())) continue;
    const Cells d = DataOf(*c, *rec);
    if (d.ints && fd->type == FieldType::Int) {
      PetscCall(ReadInts(file, path.c_str(), d.ints));
      continue;
    }
    if (d.strings) {
      PetscCall(ReadStrings(file, path.c_str(), d.strings));
      continue;
    }
    std::vector<PetscReal> x;
    PetscCall(ReadDoubles(file, path.c_str(), &x));
    const size_t bad = FirstInvalid(x, floquet, d.ints != nullptr, (c->flags & kInfOk) != 0);
    char v[32];
    if (bad < x.size()) std::snprintf(v, sizeof v, "%g", (double)x[bad]); // (PETSc's %g would print "nan.")
    PetscCheck(bad == x.size(), PETSC_COMM_SELF, PETSC_ERR_USER,
               "-cont_resume %s: %s holds %s (value %zu of %zu), which no run writes: %s (a damaged file?)", file.c_str(), path.c_str(), v, bad + 1,
               x.size(), floquet ? "Floquet values are finite, or NaN where not computed" : "a resume state must be finite");
    has_tangent |= d.reals == &rb.next_tangent, has_ds |= d.scalar == &rb.next_ds;
    if (d.reals) *d.reals = std::move(x);
    else if (d.ints) d.ints->assign(x.begin(), x.end());
    else {
      PetscCheck(x.size() == 1 && x[0] > 0, PETSC_COMM_SELF, PETSC_ERR_USER,
                 "-cont_resume %s: %s must be one positive step length (a damaged file?)", file.c_str(), path.c_str());
      *d.scalar = x[0];
    }
  }
  for (size_t i = 0; i < rb.period.size(); i++) {
    char v[32];
    std::snprintf(v, sizeof v, "%g", (double)rb.period[i]);
    PetscCheck(rb.period[i] > 0, PETSC_COMM_SELF, PETSC_ERR_USER, "-cont_resume %s: %speriod holds %s at point %zu, not a period (a damaged file?)", file.c_str(),
               g.c_str(), v, i);
  }
  // The step state: both (the exact resume) or neither (files written before them: the re-solving resume).
  PetscCheck(has_tangent == has_ds, PETSC_COMM_SELF, PETSC_ERR_USER, "-cont_resume %s: %s has %s but not %s (a damaged file?)", file.c_str(),
             g.c_str(), has_tangent ? "next_tangent" : "next_ds", has_tangent ? "next_ds" : "next_tangent");
  // (orbits of another length: ReadResume names them)
  PetscCheck(!has_tangent || rb.next_tangent.size() == (size_t)n2 + 2 || rb.z0.size() != rb.energy.size() * n2, PETSC_COMM_SELF, PETSC_ERR_USER,
             "-cont_resume %s: %snext_tangent has %zu values, not 2N + 2 = %" PetscInt_FMT " (same -lattice_cells?)", file.c_str(), g.c_str(),
             rb.next_tangent.size(), n2 + 2);
  PetscFunctionReturn(0);
}

} // namespace

std::vector<const char *> ContinuationVariants(FloquetKind fk)
{
  if (fk == FloquetKind::Dense) return {"", "floquet"};
  if (fk == FloquetKind::MatrixFree) return {"", "floquet_mf"};
  return {""};
}

std::vector<std::string> ContinuationColumnNames()
{
  std::vector<std::string> n;
  for (const Column &c : AllColumns()) n.push_back(c.name);
  return n;
}

// /continuation/<branch>/codim2/<curve> (-cont_codim2): each field of its schema from the curve.
PetscErrorCode WriteCodim2Curve(PetscViewer v, const std::string &label, const Codim2Curve &c)
{
  return WriteCodim2CurveAt(v, "/continuation/" + label + "/codim2/" + c.name, "/continuation/<branch>/codim2/<curve>", c);
}

PetscErrorCode WriteCodim2CurveAt(PetscViewer v, const std::string &g, const char *schema_path, const Codim2Curve &c)
{
  MPI_Comm comm = PetscObjectComm((PetscObject)v);
  const char *gc = g.c_str();
  const Schema *s = FindSchema(schema_path);
  const PetscInt np = (PetscInt)c.p.size();
  PetscFunctionBeginUser;
  PetscCheck(s, comm, PETSC_ERR_PLIB, "output schema has no %s", schema_path);
  for (const Field &fd : s->fields) {
    const std::string n = fd.name;
    if (fd.kind == FieldKind::Attribute) {
      if (n == "parameter") PetscCall(WriteAttr(v, gc, fd.name, Codim2ParameterOption(c.parameter)));
      else if (n == "kind") PetscCall(WriteAttr(v, gc, fd.name, (PetscInt)c.kind));
      else if (n == "event") PetscCall(WriteAttr(v, gc, fd.name, c.event));
      else if (n == "event_point") PetscCall(WriteAttr(v, gc, fd.name, c.event_point));
      else if (n == "stop_reason") PetscCall(WriteAttr(v, gc, fd.name, c.stop_reason.c_str()));
      else if (n == "solves") PetscCall(WriteAttr(v, gc, fd.name, c.solves));
      else if (n == "seconds") PetscCall(WriteAttr(v, gc, fd.name, c.seconds));
      else SETERRQ(comm, PETSC_ERR_PLIB, "attribute %s/%s of the output schema has no value in studies/continuation_record.cpp", gc, fd.name);
      continue;
    }
    if (n == "point_kind") {
      PetscCall(WriteIntArray(v, gc, fd.name, c.point_kind));
      continue;
    }
    const std::vector<PetscReal> *x = n == "p"                ? &c.p
                                      : n == "energy"         ? &c.energy
                                      : n == "omega"          ? &c.omega
                                      : n == "period"         ? &c.period
                                      : n == "test"           ? &c.test
                                      : n == "max_modulus"    ? &c.max_modulus
                                      : n == "multipliers_re" ? &c.mu_re
                                      : n == "multipliers_im" ? &c.mu_im
                                      : n == "point_p"        ? &c.point_p
                                      : n == "point_energy"   ? &c.point_energy
                                      : n == "point_omega"    ? &c.point_omega
                                      : n == "point_arc"      ? &c.point_arc
                                                              : nullptr;
    PetscCheck(x, comm, PETSC_ERR_PLIB, "dataset %s/%s of the output schema has no column in studies/continuation_record.cpp", gc, fd.name);
    if (n.rfind("multipliers", 0) == 0) PetscCall(WriteArrayND(v, gc, fd.name, *x, {np, Codim2Curve::kMultipliers}));
    else PetscCall(WriteArray(v, gc, fd.name, *x));
  }
  PetscFunctionReturn(0);
}

PetscErrorCode WriteRecord(PetscViewer v, const BranchRecord &r, FloquetKind fk, PetscInt n2, PetscInt nev)
{
  const std::string g = "/continuation/" + r.label;
  const char *gc = g.c_str();
  const PetscInt np = (PetscInt)r.b.energy.size();
  std::vector<Bound> fields;
  PetscFunctionBeginUser;
  PetscCall(Fields(PetscObjectComm((PetscObject)v), fk, &fields));
  for (const auto &[fd, c, floquet] : fields) {
    if (fd->kind == FieldKind::Attribute) {
      AttrValue a;
      c->attr(r, &a);
      if (fd->type == FieldType::Real) PetscCall(WriteAttr(v, gc, fd->name, a.r));
      else if (fd->type == FieldType::Int) PetscCall(WriteAttr(v, gc, fd->name, a.i));
      else PetscCall(WriteAttr(v, gc, fd->name, a.s.c_str()));
      continue;
    }
    if ((c->flags & kStepState) && !np) continue;              // where the continuation stands: what -cont_resume needs to go on bit for bit
    const Cells d = DataOf(*c, const_cast<BranchRecord &>(r)); // the accessors only point, the record is not changed
    const PetscInt row = RowLength(fd->shape, n2, nev);
    if (d.strings) PetscCall(WriteStringArray(v, gc, fd->name, *d.strings));
    else if (d.scalar) PetscCall(WriteArray(v, gc, fd->name, std::vector<PetscReal>{*d.scalar}));
    else if (d.ints && fd->type == FieldType::Int) PetscCall(WriteIntArray(v, gc, fd->name, *d.ints, row ? row : 1, !std::strcmp(fd->shape, "npts x nev")));
    else {
      const std::vector<PetscReal> conv = d.ints ? std::vector<PetscReal>(d.ints->begin(), d.ints->end()) : std::vector<PetscReal>();
      const std::vector<PetscReal> &x = d.ints ? conv : *d.reals;
      if (!std::strcmp(fd->shape, "npts x nev")) PetscCall(WriteArrayND(v, gc, fd->name, x, {np, nev})); // 2-D also for nev = 1
      else PetscCall(WriteArray(v, gc, fd->name, x, row ? row : 1));
    }
  }
  if (r.located) PetscCall(WriteEvents(v, r, n2));
  for (const Codim2Curve &c : r.codim2) PetscCall(WriteCodim2Curve(v, r.label, c));
  if (r.krein && fk != FloquetKind::None && np > 0) PetscCall(WriteKreinMap(v, r));
  PetscFunctionReturn(0);
}

PetscErrorCode ReadResume(MPI_Comm comm, const std::string &file, const std::string &label, FloquetKind fk, PetscInt n2, PetscInt nev, Branch *b,
                          FloquetColumns *f, bool *found, const std::string &mf_route)
{
  PetscMPIInt rank;
  const std::string g = "/continuation/" + label + "/";
  auto has = [&](const char *d) { return HasDataset(file, (g + d).c_str()); };
  std::vector<Bound> fields;
  BranchRecord rec;
  PetscFunctionBeginUser;
  *b = Branch();
  *f = FloquetColumns();
  PetscCall(Fields(comm, fk, &fields));
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  int status[2] = {0, 0}; // rank 0 reads; every rank checks: [readable, branch present]
  if (rank == 0) {
    status[0] = HasDataset(file, "/continuation");
    status[1] = status[0] && has("energy");
  }
  PetscCallMPI(MPI_Bcast(status, 2, MPI_INT, 0, comm));
  PetscCheck(status[0], comm, PETSC_ERR_FILE_OPEN, "-cont_resume %s: cannot open it, or it is not a continuation output (no /continuation group)",
             file.c_str());
  *found = status[1];
  if (!*found) PetscFunctionReturn(0);
  PetscInt rowlen = 0;  // values per stored orbit
  int route_change = 0;                          // -floquet_mf: 1 the file's route (file_route) is not this run's
  std::vector<std::string> file_route{std::string()};
  Branch &rb = rec.b;
  FloquetColumns &rf = rec.f;
  // Rank 0 reads and checks; its error (a dataset missing or not finite) fails every rank with its line.
  PetscErrorCode rerr = 0;
  char rmsg[1024] = "";
  if (rank == 0) PetscCall(CaptureError([&]() { return ReadBranchColumns(file, g, fields, n2, &rec); }, &rerr, rmsg, sizeof(rmsg)));
  PetscCall(FailTogether(comm, rerr, rmsg));
  if (rank == 0) {
    const size_t np = rb.energy.size();
    rowlen = rb.z0.size() == np * (size_t)n2 ? n2 : np == 0 ? -1 : (PetscInt)(rb.z0.size() / np);
    // Floquet columns of another -floquet_mf_nev or route (or none) are not comparable: NaN / 0 for every stored orbit.
    const bool comparable = np > 0 && rf.re.size() == np * (size_t)(fk == FloquetKind::Dense ? n2 : nev);
    // -floquet_mf: the verdicts of one route only. A file written before the
    // verdicts (no floquet_route) is matrix-free, and its stable = 1 meant only
    // "max |mu| <= 1 + tol": not decided.
    std::string route;
    const bool routed = fk == FloquetKind::MatrixFree && ReadRootAttribute(file, (g + "floquet_route").c_str(), &route);
    if (fk == FloquetKind::MatrixFree && comparable) {
      if (!routed) {
        for (PetscInt &x : rf.stable) x = x == 1 ? -1 : x;
        rf.instability.assign(np, -1);
      }
      file_route[0] = routed ? route : std::string("matrix-free");
      route_change = file_route[0] != mf_route;
    }
    for (const auto &[fd, c, floquet] : fields) { // padded: files written before krein or det_error were stored
      if (!floquet || fd->kind != FieldKind::Dataset) continue;
      const Cells d = DataOf(*c, rec);
      const size_t n = np * (size_t)std::max<PetscInt>(1, RowLength(fd->shape, n2, nev));
      // a missing -floquet_mf verdict or class is "not decided" / "not computed", never 0 (unstable / stable)
      const PetscInt unknown = (fk == FloquetKind::MatrixFree && (!std::strcmp(fd->name, "stable") || !std::strcmp(fd->name, "instability"))) ||
                                       !std::strcmp(fd->name, "verdict")
                                   ? -1
                                   : 0;
      if (d.strings) {
        if (!comparable) d.strings->clear();
        d.strings->resize(n, "not computed (resumed from a file written before verdicts)");
      } else if (d.reals) {
        if (!comparable) d.reals->clear();
        d.reals->resize(n, NAN);
      } else {
        if (!comparable) d.ints->clear();
        d.ints->resize(n, unknown);
      }
    }
  }
  PetscCallMPI(MPI_Bcast(&route_change, 1, MPI_INT, 0, comm));
  PetscCall(BroadcastStrings(comm, &file_route));
  PetscCheck(route_change == 0, comm, PETSC_ERR_USER,
             "-cont_resume %s: branch %s's Floquet multipliers were computed by the %s route, this run would take the %s one "
             "(-floquet_mf_dense_max, -floquet_mf_which): its verdicts would mix",
             file.c_str(), label.c_str(), file_route[0].c_str(), mf_route.c_str());
  PetscCallMPI(MPI_Bcast(&rowlen, 1, MPIU_INT, 0, comm));
  PetscCheck(rowlen == n2, comm, PETSC_ERR_USER,
             "-cont_resume %s: branch %s has orbits of %" PetscInt_FMT " values, this lattice has 2N = %" PetscInt_FMT " (same -lattice_cells?)", file.c_str(),
             label.c_str(), rowlen, n2);
  for (const auto &[fd, c, floquet] : fields) {
    if (fd->kind != FieldKind::Dataset || (c->flags & kRank0)) continue;
    const Cells d = DataOf(*c, rec);
    if (d.reals) PetscCall(BroadcastFromRoot(comm, MPIU_REAL, d.reals));
    if (d.ints) PetscCall(BroadcastFromRoot(comm, MPIU_INT, d.ints));
    if (d.strings) PetscCall(BroadcastStrings(comm, d.strings));
  }
  *b = std::move(rb);
  *f = std::move(rf);
  PetscFunctionReturn(0);
}

} // namespace nltopo
