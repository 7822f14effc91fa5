#pragma once
// Reading back our own HDF5 files (e.g. a sweep to resume), serially, with the
// HDF5 C API: one dataset at a time, flattened row-major.
#include <petscsys.h>
#include <string>
#include <vector>

namespace nltopo {

// Not collective: call on the rank that needs the data. Errors name the file and dataset.
PetscErrorCode ReadDoubles(const std::string &file, const char *dataset, std::vector<PetscReal> *out);
PetscErrorCode ReadInts(const std::string &file, const char *dataset, std::vector<PetscInt> *out);
// A one-dimensional dataset of fixed-length strings (as WriteStringArray writes them).
PetscErrorCode ReadStrings(const std::string &file, const char *dataset, std::vector<std::string> *out);
// Whether the file opens and holds the dataset (absolute path, e.g. "/continuation/insulated/energy").
bool HasDataset(const std::string &file, const char *dataset);
// A root attribute of the file (string, or integer), or with name
// "<path>/<attribute>" one of a group or dataset (e.g.
// "/continuation/insulated/floquet_route"): false when the file does not open
// as HDF5 or has no such attribute.
bool ReadRootAttribute(const std::string &file, const char *name, std::string *value);
bool ReadRootAttribute(const std::string &file, const char *name, long *value);
bool ReadRootAttribute(const std::string &file, const char *name, double *value);

} // namespace nltopo
