// The output schemas (io/schema.cpp) against the outputs reference
// docs/outputs.md: every dataset and attribute named there for a
// group the code writes is in the group's schema, of that kind, shape and
// type; the continuation record and the sweep's fields bind the schema
// exactly; the writers refuse a name the schema lacks.
#include "helpers.hpp"
#include "io/output.hpp"
#include "io/schema.hpp"
#include "studies/continuation_record.hpp"
#include "studies/sweep_store.hpp"
#include <fstream>
#include <regex>
#include <set>
#include <sstream>

using namespace nltopo;

namespace {

struct SpecName {
  std::string group, name, shape; // shape "" when the spec gives none
  bool attribute = false;
  std::string type; // "int", "string" or "" (not said)
};

std::string Trim(const std::string &s)
{
  const size_t a = s.find_first_not_of(" \t\n"), b = s.find_last_not_of(" \t\n");
  return a == std::string::npos ? "" : s.substr(a, b - a + 1);
}

// "<anything>" -> "<>", so that /perturb/<chiral|achiral> and /perturb/<kind> compare equal.
std::string Normal(const std::string &s) { return std::regex_replace(s, std::regex("<[^>]*>"), "<>"); }

// A shape as outputs.md writes one ("npts x 2N", "scalar"), or "".
std::string ShapeOf(const std::string &piece)
{
  static const std::set<std::string> dims = {"scalar", "N", "2N", "nq", "nt", "npts", "no", "ne", "nd", "nens", "nc", "ng"};
  const std::string p = Trim(std::regex_replace(piece, std::regex("\\s+attribute$"), ""));
  std::stringstream ss(std::regex_replace(p, std::regex(" x "), "|"));
  std::string tok;
  int n = 0;
  while (std::getline(ss, tok, '|')) {
    if (!dims.count(Trim(tok))) return "";
    n++;
  }
  return n ? p : "";
}

// One "datasets (shape)" cell: backticked names, each followed (directly or
// after a comma-separated run of names) by a parenthesis whose first piece is
// their shape; "int"/"strings" there give the type; the word "attribute(s)"
// outside parentheses makes the names after it attributes, inside makes the
// parenthesis's names attributes; a backticked name inside a parenthesis is
// another name of the same kind (an alternative or an example).
void ParseCell(const std::string &group, const std::string &cell, bool attributes, std::vector<SpecName> *out)
{
  std::vector<size_t> pending;
  size_t i = 0;
  std::string outside;
  while (i < cell.size()) {
    if (cell[i] == '`') {
      const size_t e = cell.find('`', i + 1);
      if (std::regex_search(outside, std::regex("\\battributes?\\b"))) attributes = true;
      outside.clear();
      out->push_back({group, cell.substr(i + 1, e - i - 1), "", attributes, ""});
      pending.push_back(out->size() - 1);
      i = e + 1;
    } else if (cell[i] == '(') {
      size_t depth = 1, e = i + 1;
      for (; e < cell.size() && depth; e++) depth += cell[e] == '(' ? 1 : cell[e] == ')' ? -1 : 0;
      const std::string in = cell.substr(i + 1, e - i - 2);
      const std::string shape = ShapeOf(in.substr(0, in.find_first_of(",;:")));
      const bool attr = std::regex_search(in, std::regex("\\battribute\\b"));
      const std::string type = std::regex_search(in, std::regex("\\bint\\b")) ? "int" : std::regex_search(in, std::regex("\\bstrings?\\b")) ? "string" : "";
      for (size_t k : pending) {
        (*out)[k].shape = shape, (*out)[k].type = type;
        (*out)[k].attribute |= attr;
      }
      std::smatch m;
      for (std::string rest = in; std::regex_search(rest, m, std::regex("`([^`]+)`")); rest = m.suffix())
        if (!pending.empty()) out->push_back({group, m[1], "", (*out)[pending.back()].attribute, ""});
      pending.clear();
      i = e;
    } else outside += cell[i++];
  }
}

// Splits a table row on the | outside backticks.
std::vector<std::string> Cells(const std::string &line)
{
  std::vector<std::string> c(1);
  bool tick = false;
  for (char ch : line) {
    if (ch == '`') tick = !tick;
    if (ch == '|' && !tick) c.emplace_back();
    else c.back() += ch;
  }
  return c;
}

std::vector<SpecName> ParseSpec(const std::string &path)
{
  std::ifstream f(path);
  std::stringstream ss;
  ss << f.rdbuf();
  const std::string text = ss.str();
  std::vector<SpecName> names;
  const size_t root = text.find("as attributes of `/`:");
  if (root != std::string::npos) ParseCell("/", text.substr(root + 21, text.find("\n\n", root) - root - 21), true, &names);
  std::istringstream lines(text);
  for (std::string line; std::getline(lines, line);) {
    if (line.rfind("| ", 0) || line.find("| study |") == 0) continue;
    const std::vector<std::string> c = Cells(line);
    if (c.size() < 4) continue;
    std::smatch m;
    if (!std::regex_search(c[2], m, std::regex("`([^`]+)`"))) continue;
    ParseCell(m[1], c[3], false, &names);
  }
  return names;
}

// The schemas of a spec group (its "<...>" segments as any name), every variant.
std::vector<const Schema *> SchemasOf(const std::string &group)
{
  std::vector<const Schema *> v;
  for (const Schema &s : Schemas())
    if (Normal(s.group) == Normal(group)) v.push_back(&s);
  return v;
}

bool Compatible(const SpecName &n, const Field &f)
{
  const bool named = n.name.find('<') != std::string::npos ? Normal(n.name) == Normal(f.name) : NameMatches(f.name, n.name);
  if (!named || (f.kind == FieldKind::Attribute) != n.attribute) return false;
  const std::string shape = !n.shape.empty() ? n.shape : n.attribute ? "scalar" : "";
  if (!shape.empty() && shape != f.shape) return false;
  if (n.type == "int") return f.type == FieldType::Int;
  if (n.type == "string") return f.type == FieldType::String;
  return n.attribute || f.type != FieldType::String; // arrays are numbers unless said
}

} // namespace

TEST_CASE("outputs.md: every name of every written group is in its schema, of that kind, shape and type", "[schema][serial]")
{
  const std::vector<SpecName> spec = ParseSpec(NLTOPO_OUTPUTS_SPEC);
  // The parse itself against what outputs.md says.
  REQUIRE(spec.size() >= 80);
  auto in_spec = [&](const char *g, const char *n, const char *shape, bool attr) {
    for (const SpecName &s : spec)
      if (s.group == g && s.name == n && s.shape == shape && s.attribute == attr) return true;
    return false;
  };
  CHECK(in_spec("/", "wall_seconds", "", true));
  CHECK(in_spec("/linear", "modes", "N x N", false));
  CHECK(in_spec("/linear", "optical_top", "", true));
  CHECK(in_spec("/continuation/<branch>", "z0", "npts x 2N", false));
  CHECK(in_spec("/sweep", "mcr_spread", "ne x no", false));
  CHECK(in_spec("/perturb/<chiral|achiral>", "mcr", "nd x ne x nens", false));
  CHECK(in_spec("/workprecision", "spread_<observable>", "scalar", true));
  CHECK(in_spec("/workprecision", "reference", "", true));

  std::set<std::string> unwritten;
  size_t checked = 0;
  for (const SpecName &n : spec) {
    const std::vector<const Schema *> ss = SchemasOf(n.group);
    if (ss.empty()) {
      unwritten.insert(Normal(n.group));
      continue;
    }
    bool ok = false;
    for (const Schema *s : ss)
      for (const Field &f : s->fields) ok |= Compatible(n, f);
    INFO(n.group << " " << (n.attribute ? "attribute " : "dataset ") << n.name << " (" << n.shape << (n.type.empty() ? "" : ", " + n.type) << ")");
    CHECK(ok);
    checked++;
  }
  CHECK(checked >= 65);
  // Groups of outputs.md no study writes yet: a schema for one must come with its writer.
  CHECK(unwritten.empty()); // every group of outputs.md has its schema and its writer
}

TEST_CASE("the output schemas are well formed", "[schema][serial]")
{
  for (const Schema &s : Schemas()) {
    std::set<std::pair<std::string, int>> seen;
    for (const Field &f : s.fields) {
      INFO(s.group << " " << s.variant << " " << f.name);
      CHECK(seen.insert({f.name, (int)f.kind}).second);
      CHECK(*f.meaning);
      CHECK(*f.shape);
      if (f.kind == FieldKind::Attribute) CHECK(std::string(f.shape) == "scalar");
    }
  }
  CHECK(GroupMatches("/continuation/<branch>", "/continuation/mode3"));
  CHECK_FALSE(GroupMatches("/continuation/<branch>", "/continuation"));
  CHECK(GroupMatches("/stability/case<k>", "/stability/case12"));
  CHECK(GroupMatches("/", "/"));
  CHECK_FALSE(GroupMatches("/linear", "/linear/bloch"));
  CHECK(FindField("/workprecision", "error_mcr", FieldKind::Dataset));
  CHECK_FALSE(FindField("/workprecision", "error_", FieldKind::Dataset));
  CHECK(FindField("/cost", "nnm_steps", FieldKind::Attribute));
  REQUIRE(FindField("/workprecision", "reference_converged", FieldKind::Attribute));
  CHECK(FindField("/workprecision", "reference_converged", FieldKind::Attribute)->type == FieldType::Int);
}

TEST_CASE("the continuation record and the sweep's fields bind their schemas exactly", "[schema][serial]")
{
  std::set<std::string> schema;
  for (const char *variant : {"", "floquet", "floquet_mf"}) {
    const Schema *s = FindSchema("/continuation/<branch>", variant);
    REQUIRE(s);
    for (const Field &f : s->fields) schema.insert(f.name);
  }
  const std::vector<std::string> cols = ContinuationColumnNames();
  CHECK(std::set<std::string>(cols.begin(), cols.end()) == schema);
  CHECK(cols.size() == schema.size());
  CHECK(ContinuationVariants(FloquetKind::MatrixFree).size() == 2);
  CHECK(SweepFieldsUnbound().empty());
  CHECK(SweepRealFields().size() == 9);
  CHECK(SweepIntFields().size() == 7);
  CHECK(std::string(SweepRealFields()[0].name) == "mcr"); // the journal's first value
}

TEST_CASE("the writers refuse a name or type the schema lacks", "[schema]")
{
  SetSchemaCheck(true);
  PetscPushErrorHandler(PetscReturnErrorHandler, NULL); // the expected errors are not printed
  CHECK(SchemaCheckWrite(PETSC_COMM_WORLD, "/continuation/optical_top", "z0", FieldKind::Dataset, FieldType::Real) == 0);
  CHECK(SchemaCheckWrite(PETSC_COMM_WORLD, "/sweep", "mcr_spread", FieldKind::Dataset, FieldType::Real) == 0);
  CHECK(SchemaCheckWrite(PETSC_COMM_WORLD, "/sweep", "mcr_spreed", FieldKind::Dataset, FieldType::Real) != 0);
  CHECK(SchemaCheckWrite(PETSC_COMM_WORLD, "/sweep", "done", FieldKind::Dataset, FieldType::Real) != 0); // it is int
  CHECK(SchemaCheckWrite(PETSC_COMM_WORLD, "/sweep", "done", FieldKind::Attribute, FieldType::Int) != 0);
  CHECK(SchemaCheckWrite(PETSC_COMM_WORLD, "/nowhere", "mcr", FieldKind::Dataset, FieldType::Real) != 0);
  {
    OutputFile out; // never committed: its temporary is removed
    REQUIRE(out.Open(PETSC_COMM_WORLD, "schema_test.h5") == 0);
    CHECK(WriteAttr(out.Viewer(), "/zak", "energy_threshold", (PetscReal)1) == 0);
    CHECK(WriteAttr(out.Viewer(), "/zak", "energy_treshold", (PetscReal)1) != 0);
    CHECK(WriteArray(out.Viewer(), "/zak", "phi1_mean", std::vector<PetscReal>{1, 2}) != 0);
    CHECK(WriteIntArray(out.Viewer(), "/zak", "energy", std::vector<PetscInt>{1, 2}) != 0);
  }
  PetscPopErrorHandler();
}
