#pragma once
// What makes an output describe itself (docs/outputs.md, "Reading a file"):
// every dataset carries the attributes `description` and `units` from its
// schema row (io/schema.hpp), and `codes` when it holds an integer code;
// every group with attributes holds an attribute `fields`, a table of (name,
// units, description, codes) describing the others, since HDF5 attributes
// cannot carry attributes; the root holds `options_table`, the given options
// as (key, value). Tables are attributes, not datasets, so that a group's
// members stay its data (a script listing /continuation sees branches only).
#include <petscviewer.h>
#include <string>
#include <utility>
#include <vector>

namespace nltopo {

// The root attribute `options_table`: each given option as PETSc holds it (key without
// its "-", value "" for a bare flag), so a value that itself holds options
// (-wp_configs) reads back exactly. Collective.
PetscErrorCode WriteGivenOptions(PetscViewer v);
// Describes every dataset and every group's attributes from the schemas, just
// before the file is committed. A field without a schema row, a description or
// units is an error naming it when the schema check is on (io/schema.hpp), and
// is left undescribed otherwise. Collective.
PetscErrorCode DescribeFile(PetscViewer v);

// The given options as (key without "-", value), in the database's order.
std::vector<std::pair<std::string, std::string>> GivenOptionPairs();

} // namespace nltopo
