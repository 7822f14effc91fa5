// The output schemas (io/schema.cpp) against the frozen contract names
// (tests/contract_names.txt): every name users' scripts read is in its
// group's schema, of that kind, shape and type; the continuation record and the sweep's fields bind the schema
// exactly; the writers refuse a name the schema lacks.
#include "helpers.hpp"
#include "io/input.hpp"
#include "io/output.hpp"
#include "io/schema.hpp"
#include "studies/continuation_record.hpp"
#include "studies/sweep_store.hpp"
#include <fstream>
#include <hdf5.h>
#include <sys/stat.h>
#include <cstring>
#include <regex>
#include <set>
#include <sstream>

using namespace nltopo;

namespace {

struct ContractName {
  std::string group, kind, name, type, shape;
};

// tests/contract_names.txt: the frozen names and the format version they belong to.
std::vector<ContractName> ReadContract(const std::string &path, long *version)
{
  std::ifstream in(path);
  std::vector<ContractName> names;
  std::string line;
  *version = -1;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::vector<std::string> cols;
    std::stringstream ss(line);
    for (std::string c; std::getline(ss, c, '\t');) cols.push_back(c);
    if (cols.size() == 2 && cols[0] == "format_version") *version = std::stol(cols[1]);
    else if (cols.size() == 5) names.push_back({cols[0], cols[1], cols[2], cols[3], cols[4]});
  }
  return names;
}

} // namespace

TEST_CASE("the frozen contract names are written with their kind, type and shape", "[schema][serial]")
{
  long version;
  const std::vector<ContractName> names = ReadContract(NLTOPO_CONTRACT_NAMES, &version);
  REQUIRE(names.size() >= 200);
  // A rename or a removal edits the list and bumps the version together (docs/outputs.md).
  CHECK(version == kFormatVersion);
  for (const ContractName &n : names) {
    bool found = false;
    for (const Schema &s : Schemas())
      if (n.group == s.group)
        for (const Field &f : s.fields) found |= n.name == f.name && n.kind == KindName(f.kind) && n.type == TypeName(f.type) && n.shape == f.shape;
    INFO(n.group << " " << n.kind << " " << n.name << " (" << n.type << ", " << n.shape << "): renamed or removed? bump kFormatVersion (io/schema.hpp)");
    CHECK(found);
  }
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
      REQUIRE(f.units);
      CHECK(*f.units); // every field has a description and units (written into the file)
      if (f.codes) CHECK(f.type == FieldType::Int);
      if (f.kind == FieldKind::Attribute) CHECK((std::string(f.shape) == "scalar" || std::string(f.name) == "options_table"));
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
  CHECK(SweepRealFields().size() == 12); // with mcr_dt (-sweep_mcr_tol), lyapunov, lyapunov_half (-sweep_lyapunov)
  CHECK(SweepIntFields().size() == 8); // with regime
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

namespace {
std::string StringAttr(hid_t obj, const char *name)
{
  std::string v;
  if (H5Aexists(obj, name) <= 0) return "(absent)";
  const hid_t a = H5Aopen(obj, name, H5P_DEFAULT), t = H5Aget_type(a), m = H5Tget_native_type(t, H5T_DIR_ASCEND);
  if (H5Tis_variable_str(t) > 0) {
    char *p = nullptr;
    H5Aread(a, m, &p);
    v = p ? p : "";
    H5free_memory(p);
  }
  H5Tclose(m), H5Tclose(t), H5Aclose(a);
  return v;
}
// A table attribute (compound of variable-length strings) as rows of strings.
std::vector<std::vector<std::string>> TableAttr(hid_t obj, const char *name)
{
  std::vector<std::vector<std::string>> rows;
  if (H5Aexists(obj, name) <= 0) return rows;
  const hid_t a = H5Aopen(obj, name, H5P_DEFAULT), t = H5Aget_type(a), sp = H5Aget_space(a);
  const int nc = H5Tget_nmembers(t);
  hsize_t n = 0;
  H5Sget_simple_extent_dims(sp, &n, NULL);
  std::vector<char *> buf(n * nc);
  H5Aread(a, t, buf.data());
  for (hsize_t i = 0; i < n; i++) {
    rows.emplace_back();
    for (int c = 0; c < nc; c++) rows.back().push_back(buf[i * nc + c] ? buf[i * nc + c] : "");
  }
  H5Dvlen_reclaim(t, sp, H5P_DEFAULT, buf.data());
  H5Sclose(sp), H5Tclose(t), H5Aclose(a);
  return rows;
}
} // namespace

TEST_CASE("a committed file describes every field: description, units, codes, the fields table, options, format_version", "[schema]")
{
  SetSchemaCheck(true);
  PetscMPIInt rank;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  REQUIRE(PetscOptionsSetValue(NULL, "-describe_test_configs", "-sim_ts_type rk -sim_ts_dt 0.1;bm4") == 0);
  REQUIRE(PetscOptionsSetValue(NULL, "-describe_test_flag", NULL) == 0);
  {
    OutputFile out;
    REQUIRE(out.Open(PETSC_COMM_WORLD, "describe_test.h5") == 0);
    REQUIRE(WriteArray(out.Viewer(), "/zak", "energy", std::vector<PetscReal>{1, 2}) == 0);
    REQUIRE(WriteIntArray(out.Viewer(), "/zak", "done", std::vector<PetscInt>{1, 0, 1, 1}, 2) == 0);
    REQUIRE(WriteAttr(out.Viewer(), "/zak", "energy_threshold", (PetscReal)1) == 0);
    REQUIRE(out.Commit("zak", 0.5) == 0);
  }
  if (!rank) {
    const hid_t f = H5Fopen("describe_test.h5", H5F_ACC_RDONLY, H5P_DEFAULT);
    REQUIRE(f >= 0);
    const hid_t e = H5Dopen2(f, "/zak/energy", H5P_DEFAULT), d = H5Dopen2(f, "/zak/done", H5P_DEFAULT);
    CHECK(StringAttr(e, "description") == FindField("/zak", "energy", FieldKind::Dataset)->meaning);
    CHECK(StringAttr(e, "units") == "energy");
    CHECK(StringAttr(e, "codes") == "(absent)");
    CHECK(StringAttr(d, "codes") == codes::kDone);
    H5Dclose(e), H5Dclose(d);
    long version = -1;
    CHECK(ReadRootAttribute("describe_test.h5", "format_version", &version));
    CHECK(version == kFormatVersion);
    // /zak's attribute fields: one record per other attribute; / has its own; options_table holds the given options
    for (const char *group : {"/zak", "/"}) {
      INFO(group);
      const hid_t g = H5Gopen2(f, group, H5P_DEFAULT);
      std::vector<std::vector<std::string>> fields = TableAttr(g, "fields"), options = TableAttr(g, "options_table");
      if (!std::strcmp(group, "/zak")) {
        REQUIRE(fields.size() == 1);
        CHECK(fields[0] == std::vector<std::string>{"energy_threshold", "energy", FindField("/zak", "energy_threshold", FieldKind::Attribute)->meaning, ""});
      } else {
        CHECK(fields.size() == 8); // study, version, options, effective_options, wall_seconds, complete, format_version, options_table
        bool found = false, flag = false;
        for (const auto &r : options) { // a value that holds options reads back exactly; a flag has an empty value
          found |= r == std::vector<std::string>{"describe_test_configs", "-sim_ts_type rk -sim_ts_dt 0.1;bm4"};
          flag |= r == std::vector<std::string>{"describe_test_flag", ""};
        }
        CHECK(found);
        CHECK(flag);
      }
      H5Gclose(g);
    }
    H5Fclose(f);
    std::remove("describe_test.h5");
  }
  PetscOptionsClearValue(NULL, "-describe_test_configs");
  PetscOptionsClearValue(NULL, "-describe_test_flag");
  // a field without units is refused at the commit, naming it; the output is not written
  RegisterSchemas({{"/describe_selftest", "", {{"bare", FieldKind::Dataset, FieldType::Real, "n", "", "a field without units"}}}});
  PetscPushErrorHandler(PetscReturnErrorHandler, NULL);
  {
    OutputFile out;
    REQUIRE(out.Open(PETSC_COMM_WORLD, "describe_bad.h5") == 0);
    REQUIRE(WriteArray(out.Viewer(), "/describe_selftest", "bare", std::vector<PetscReal>{1}) == 0);
    CHECK(out.Commit("zak", 0.5) != 0);
  }
  PetscPopErrorHandler();
  struct stat st;
  CHECK(stat("describe_bad.h5", &st) != 0);
}
