#include "io/output_reference.hpp"
#include "io/schema.hpp"

namespace nltopo {

namespace {

std::string Cell(std::string s)
{
  for (size_t i = 0; (i = s.find('|', i)) != std::string::npos; i += 2) s.replace(i, 1, "\\|");
  return s;
}

const char *kIntroduction = "# Outputs: what every study writes\n\n"
                            "Generated from the output schemas in the code (`nltopo -output_schema md > docs/outputs.md`); a test\n"
                            "checks that this page is what the binary writes, so it cannot drift from what the files hold.\n\n"
                            "Every run writes one HDF5 file: `-output <file.h5>`, default `<study>.h5`. It is written under a\n"
                            "temporary name and renamed when complete, so the path holds either nothing or a whole file\n"
                            "(a checkpoint is a whole file with `complete = 0`). Arrays are float64 unless the type says int or\n"
                            "string; a complex quantity is two datasets `*_re`, `*_im`. Names in angle brackets stand for any\n"
                            "name: `<branch>` a branch, `<observable>` an observable, `<prefix>` an integrator's prefix (`sim_`, `nnm_`).\n\n"
                            "## Reading a file\n\n"
                            "The file describes itself (format version 1 on):\n\n"
                            "- every dataset carries the string attributes `description` and `units`, and an integer code also\n"
                            "  `codes`: `\"v meaning; v meaning; ...\"`, e.g. `\"1 stable; 0 unstable; -1 not decided\"`;\n"
                            "- every group with attributes (the root included) has an attribute `fields`, a table with one record\n"
                            "  (name, units, description, codes) per other attribute, since HDF5 attributes cannot carry\n"
                            "  attributes (a table attribute, not a dataset, so that listing a group lists only its data);\n"
                            "- the root attribute `options_table` holds one record (key, value) per given option, exactly as\n"
                            "  PETSc holds it (so a value that itself holds options, as `-wp_configs` does, reads back exactly),\n"
                            "  beside the attribute `options`, the same as one line of text;\n"
                            "- the root attribute `format_version` says which version of this page the file follows.\n\n"
                            "Units are the model's scaled units (docs/model.md: unit masses, base coupling k = 1): `time`,\n"
                            "`rad/time` (frequencies), `energy`, `displacement`, `displacement/time`, `force`, `rad`; `s` is\n"
                            "wall-clock seconds and `1` a pure number, a count, an index or a string. The Python reader\n"
                            "(docs/python.md) reads all of this for you.\n\n"
                            "## Format versions and migration\n\n"
                            "The names below are an interface: scripts read them. A rename, a removal or a change of meaning of\n"
                            "any of them bumps `format_version` and adds a note here; tests/contract_names.txt freezes the names\n"
                            "and a unit test checks that every one of them is still written with its type and shape. Resume\n"
                            "refuses a file of another format version in one line.\n\n"
                            "- **0**: files without `format_version` (before it existed): the same names, without the\n"
                            "  descriptions, the codes, the `fields` tables and `options_table`.\n"
                            "- **1**: adds `format_version`, `options_table`, and `description`, `units`, `codes` and\n"
                            "  `fields`; nothing renamed or removed.\n";

std::string Table(const Schema &s)
{
  std::string o = "| name | kind | type | shape | units | description |\n|---|---|---|---|---|---|\n";
  for (const Field &f : s.fields) {
    std::string d = f.meaning ? f.meaning : "";
    if (f.codes) d += ". Codes: " + std::string(f.codes);
    o += "| `" + Cell(f.name) + "` | " + KindName(f.kind) + " | " + TypeName(f.type) + " | " + Cell(f.shape) + " | " + Cell(f.units ? f.units : "") + " | " +
         Cell(d) + " |\n";
  }
  return o;
}

} // namespace

std::string OutputReferenceMarkdown()
{
  std::string o = kIntroduction;
  o += "\n## Groups\n";
  for (const Schema &s : Schemas()) {
    o += "\n### `" + std::string(s.group) + "`";
    if (*s.variant) o += ", fields added with `-" + std::string(s.variant) + "`";
    o += "\n\nWritten by " + (*s.writer ? "`-study " + std::string(s.writer) + "`" : std::string("every study")) + ".\n\n";
    o += Table(s);
  }
  return o;
}

} // namespace nltopo
