#include "io/schema.hpp"
#include <cstdlib>
#include <cstring>

namespace nltopo {

namespace {

using namespace schema_names;

std::vector<Schema> &Registry()
{
  static std::vector<Schema> s = {{"/",
                                   "",
                                   {{"study", A, S, "scalar", "1", "the -study that wrote the file"},
                                    {"version", A, S, "scalar", "1", "git describe or project version"},
                                    {"options", A, S, "scalar", "1", "the full options database, to repeat the run"},
                                    {"effective_options", A, S, "scalar", "1", "each option the run read and its value, defaults included, one per line"},
                                    {"wall_seconds", A, R, "scalar", "s", "wall time of the run"},
                                    {"complete", A, I, "scalar", "1", "1; 0 for a checkpoint, a running sweep or an interrupted run", codes::kYesNo},
                                    {"options_table", A, S, "nopt", "1", "the given options as a table of (key without its -, value; empty for a flag)"},
                                    {"format_version", A, I, "scalar", "1", "the output format's version (docs/outputs.md); a file without it is version 0"}}},
                                  {"/cost",
                                   "",
                                   {{"wall_seconds", A, R, "scalar", "s", "wall time of the run"},
                                    {"<prefix>integrator", A, S, "scalar", "1", "sim_ (forced/free runs) or nnm_ (shooting): TS type and scheme"},
                                    {"<prefix>accuracy", A, S, "scalar", "1", "fixed step, or rtol and atol"},
                                    {"<prefix>solves", A, I, "scalar", "1", "time integrations"},
                                    {"<prefix>steps", A, I, "scalar", "1", "accepted steps"},
                                    {"<prefix>rejected_steps", A, I, "scalar", "1", "rejected steps"},
                                    {"<prefix>force_evaluations", A, I, "scalar", "1", "force evaluations over every rank"},
                                    {"<prefix>dt_min", A, R, "scalar", "time", "smallest fixed step"},
                                    {"<prefix>dt_max", A, R, "scalar", "time", "largest fixed step"},
                                    {"error_estimate", A, R, "scalar", "1", "the study's own error estimate, NaN if none"},
                                    {"error_estimate_of", A, S, "scalar", "1", "what error_estimate measures, none if none"}}}};
  return s;
}

// -1: not decided yet; NLTOPO_SCHEMA_CHECK or SetSchemaCheck decide (a debug build: on).
int g_check = -1;

bool CheckOn()
{
  if (g_check < 0) {
#if defined(NDEBUG)
    const char *e = std::getenv("NLTOPO_SCHEMA_CHECK");
    g_check = e && *e && std::strcmp(e, "0");
#else
    g_check = 1;
#endif
  }
  return g_check;
}

} // namespace

const std::vector<Schema> &Schemas() { return Registry(); }

void RegisterSchemas(const std::vector<Schema> &schemas, const char *writer)
{
  for (const Schema &s : schemas)
    if (!FindSchema(s.group, s.variant)) {
      Registry().push_back(s);
      if (!*Registry().back().writer) Registry().back().writer = writer;
    }
}

const Schema *FindSchema(const char *group, const char *variant)
{
  for (const Schema &s : Schemas())
    if (!std::strcmp(s.group, group) && !std::strcmp(s.variant, variant)) return &s;
  return nullptr;
}

bool NameMatches(const std::string &pattern, const std::string &name)
{
  const size_t lt = pattern.find('<'), gt = pattern.find('>');
  if (lt == std::string::npos || gt == std::string::npos || gt < lt) return pattern == name;
  const std::string pre = pattern.substr(0, lt), post = pattern.substr(gt + 1);
  return name.size() > pre.size() + post.size() && !name.compare(0, pre.size(), pre) && !name.compare(name.size() - post.size(), post.size(), post);
}

bool GroupMatches(const std::string &pattern, const std::string &path)
{
  size_t p = 0, q = 0;
  while (true) {
    const size_t pe = pattern.find('/', p), qe = path.find('/', q);
    if (!NameMatches(pattern.substr(p, pe - p), path.substr(q, qe - q))) return false;
    if (pe == std::string::npos || qe == std::string::npos) return pe == qe;
    p = pe + 1, q = qe + 1;
  }
}

const Field *FindField(const std::string &group_path, const std::string &name, FieldKind kind)
{
  std::string path = group_path;
  if (path.size() > 1 && path.back() == '/') path.pop_back();
  for (int exact = 1; exact >= 0; exact--) // a name itself before a pattern (reference_converged before reference_<observable>)
    for (const Schema &s : Schemas()) {
      if (!GroupMatches(s.group, path)) continue;
      for (const Field &f : s.fields)
        if (f.kind == kind && (exact ? name == f.name : NameMatches(f.name, name))) return &f;
    }
  return nullptr;
}

const char *KindName(FieldKind k) { return k == FieldKind::Dataset ? "dataset" : "attribute"; }

const char *TypeName(FieldType t) { return t == FieldType::Real ? "real" : t == FieldType::Int ? "int" : "string"; }

void SetSchemaCheck(bool on) { g_check = on; }

bool SchemaCheckOn() { return CheckOn(); }

PetscErrorCode SchemaCheckWrite(MPI_Comm comm, const char *group, const char *name, FieldKind kind, FieldType type)
{
  PetscFunctionBeginUser;
  if (!CheckOn()) PetscFunctionReturn(0);
  const Field *f = FindField(group, name, kind);
  PetscCheck(f, comm, PETSC_ERR_PLIB, "output schema has no %s %s in group %s: add it to the schema its study registers (studies/registry.hpp)", KindName(kind),
             name, group);
  PetscCheck(f->type == type, comm, PETSC_ERR_PLIB, "output schema: %s %s/%s is %s there, written as %s", KindName(kind), group, name, TypeName(f->type),
             TypeName(type));
  PetscFunctionReturn(0);
}

} // namespace nltopo
