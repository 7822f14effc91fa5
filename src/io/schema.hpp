#pragma once
// One declarative schema per output group (outputs.md of the output contract
// plus our additions): every dataset and attribute a study writes, with its
// type, shape and meaning. io holds the groups every output has (/ and /cost);
// each study registers its own groups' schemas in its own file (its contract,
// studies/registry.hpp). It drives the continuation record (studies/continuation_record)
// and the sweep's fields (studies/sweep_store); tests/unit/test_schema.cpp
// checks outputs.md against it, and the writers of io/output refuse a name the
// schema lacks when the check is on (NLTOPO_SCHEMA_CHECK=1, as ctest sets it,
// or a debug build).
#include <petscsys.h>
#include <string>
#include <vector>

namespace nltopo {

enum class FieldKind { Dataset, Attribute };
enum class FieldType { Real, Int, String };

// Units are the model's scaled units (docs/model.md: unit masses, k = 1):
// "time", "rad/time", "energy", "displacement", "displacement/time", "force",
// "rad", "1/time", "(rad/time)^2", "periods" (of the orbit); "s" is wall-clock seconds; "1" a pure
// number, count, index or string. A state vector names its parts' units.
struct Field {
  const char *name; // may hold one placeholder, e.g. "error_<observable>"
  FieldKind kind;
  FieldType type;
  const char *shape; // "scalar", or dimensions as outputs.md names them: "npts", "npts x 2N", "ne x no", ...
  const char *units;
  const char *meaning;
  const char *codes = nullptr; // an integer code's values: "v meaning; v meaning; ..." (written as the attribute `codes`)
};

// The meanings of the integer codes several groups share (written into the file).
namespace codes {
constexpr const char *kYesNo = "1 yes; 0 no";
constexpr const char *kDone = "1 computed; 0 not run (stop signal or not reached yet)";
constexpr const char *kStable = "1 stable; 0 unstable; -1 not decided";
constexpr const char *kKrein = "1 positive signature; -1 negative signature; 0 not defined (real multiplier or below -floquet_krein_tol)";
constexpr const char *kInstability =
    "0 none; 1 B-B (critical eigenvector in the bulk); 2 B-E (between bulk and edge); 3 E-E (at the interface edge); -1 not computed";
constexpr const char *kEventKind =
    "1 energy fold; 2 branch point (+1); 3 period doubling (-1); 4 Krein collision (pass); 5 Hamiltonian-Hopf; 6 internal resonance";
constexpr const char *kDirection = "1 an instability begins along the branch (fold: E maximum); -1 it ends (fold: E minimum); 0 neither (a Krein pass)";
constexpr const char *kVerdict = "-1 not computed (resumed from a file written before verdicts); 0 stable (dense route: every multiplier within 1 + tol); 1 unstable-localized (a multiplier beyond 1 + delta, "
                                  "eigenvector at the interface, confirmed by k-period integration); 2 unstable-extended (the same, extended eigenvector); "
                                  "3 stable-to (nothing beyond 1 + verdict_bound); 4 unresolved (verdict_reason says why)";
constexpr const char *kPredictable = "1 predictable; 0 unpredictable (twin statistics); -1 not checked (no -sweep_mcr_tol)";
constexpr const char *kRegime = "0 regular (lyapunov x window below -sweep_lyapunov_efolds); 1 chaotic, the MCR statistically predictable (an ergodic average; "
                                "or not checked without -sweep_mcr_tol); 2 unpredictable (the twins spread beyond -sweep_mcr_tol); -1 not computed "
                                "(no -sweep_lyapunov, E* not reached, or failed)";
// The Krein resonance map (stability/krein_map.hpp): bits of a mask, a value is the sum of its open classes' bits.
constexpr const char *kKreinPairs = "0 none; 1 AA (acoustic + acoustic); 2 AO (acoustic + optical); 4 OO (optical + optical); 8 EA (localised + acoustic); "
                                    "16 EO (localised + optical); 32 EE (localised + localised, crossed since the previous orbit)";
constexpr const char *kEnergyCriterion = "0 no sign change; 1 E extremum (dE/dOmega through 0: a real pair through +1); 2 Omega extremum (dE/dOmega through "
                                         "infinity); 3 both";
// The codim-2 points of a -cont_codim2 curve (stability/codim2.hpp Codim2PointKind).
constexpr const char *kCodim2Point =
    "0 end of the curve (a bound, -cont_codim2_max_points or step collapse: stop_reason); 1 turn in p (dp/ds = 0, the curve goes on); "
    "2 Hamiltonian-Hopf end at b = +1 (1:1 resonance); 3 Hamiltonian-Hopf end at b = -1 (1:2 resonance); 4 linear limit (E -> 0)";
} // namespace codes

struct Schema {
  const char *group;   // a path; a segment "<...>" (or "case<k>") stands for any name
  const char *variant; // "" the group's fields; else added fields, e.g. "floquet" (with -floquet)
  std::vector<Field> fields;
  const char *writer = ""; // the study that writes it ("" every study); set by RegisterSchemas
};

// The current output format (root attribute format_version; a file without it
// is version 0). A rename, a removal or a change of meaning of any name in
// tests/contract_names.txt bumps it, with a migration note in docs/outputs.md.
constexpr PetscInt kFormatVersion = 1;

// Short names for schema tables: `using namespace nltopo::schema_names;`.
namespace schema_names {
constexpr FieldKind D = FieldKind::Dataset, A = FieldKind::Attribute;
constexpr FieldType R = FieldType::Real, I = FieldType::Int, S = FieldType::String;
} // namespace schema_names

// Every schema: / and /cost, then those registered, in registration order.
const std::vector<Schema> &Schemas();
// Adds schemas (studies/registry.cpp, each study's own); a group and variant
// already registered is kept as it is.
void RegisterSchemas(const std::vector<Schema> &schemas, const char *writer = "");
// The schema of a group pattern and variant, exactly as written in Schemas(); nullptr if none.
const Schema *FindSchema(const char *group, const char *variant = "");
// The field of a written group path (e.g. "/continuation/insulated") by its
// written name, over every variant of every matching schema; nullptr if none.
const Field *FindField(const std::string &group_path, const std::string &name, FieldKind kind);
// Whether a written name (or path segment) matches a pattern with at most one "<...>".
bool NameMatches(const std::string &pattern, const std::string &name);
bool GroupMatches(const std::string &pattern, const std::string &path);
const char *KindName(FieldKind k);
const char *TypeName(FieldType t);

// The writers' check: an error naming the group and name unless the schema has
// such a field of that kind and type (no-op unless the check is on).
PetscErrorCode SchemaCheckWrite(MPI_Comm comm, const char *group, const char *name, FieldKind kind, FieldType type);
void SetSchemaCheck(bool on); // overrides NLTOPO_SCHEMA_CHECK (tests)
bool SchemaCheckOn();

} // namespace nltopo
