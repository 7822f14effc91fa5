#include "io/self_describe.hpp"
#include "io/output.hpp"
#include "io/schema.hpp"
#include <petscviewerhdf5.h>
#include <cctype>
#include <cstring>
#include <map>
#include <sstream>

namespace nltopo {

namespace {

struct Object {
  std::string path;
  bool dataset;
};

herr_t CollectObject(hid_t, const char *name, const H5O_info_t *info, void *ctx)
{
  auto *list = static_cast<std::vector<Object> *>(ctx);
  if (info->type == H5O_TYPE_GROUP) list->push_back({std::strcmp(name, ".") ? std::string("/") + name : std::string("/"), false});
  else if (info->type == H5O_TYPE_DATASET) list->push_back({std::string("/") + name, true});
  return 0;
}

herr_t CollectAttribute(hid_t, const char *name, const H5A_info_t *, void *ctx)
{
  static_cast<std::vector<std::string> *>(ctx)->push_back(name);
  return 0;
}

std::string Parent(const std::string &path)
{
  const size_t slash = path.rfind('/');
  return slash ? path.substr(0, slash) : "/";
}

std::string Base(const std::string &path) { return path.substr(path.rfind('/') + 1); }

// A variable-length UTF-8 string attribute on an open object (h5py reads a
// str); collective: every rank writes the same.
PetscErrorCode StringAttribute(MPI_Comm comm, hid_t obj, const char *name, const std::string &value)
{
  hid_t type, space, attr;
  const char *buf = value.c_str();
  PetscFunctionBeginUser;
  PetscCheck((type = H5Tcopy(H5T_C_S1)) >= 0 && H5Tset_size(type, H5T_VARIABLE) >= 0 && H5Tset_cset(type, H5T_CSET_UTF8) >= 0, comm, PETSC_ERR_LIB,
             "HDF5 string type for attribute %s failed", name);
  PetscCheck((space = H5Screate(H5S_SCALAR)) >= 0, comm, PETSC_ERR_LIB, "HDF5 dataspace for attribute %s failed", name);
  if (H5Aexists(obj, name) > 0) H5Adelete(obj, name);
  PetscCheck((attr = H5Acreate2(obj, name, type, space, H5P_DEFAULT, H5P_DEFAULT)) >= 0, comm, PETSC_ERR_LIB, "HDF5 attribute %s failed", name);
  PetscCheck(H5Awrite(attr, type, &buf) >= 0, comm, PETSC_ERR_LIB, "HDF5 attribute %s failed", name);
  H5Aclose(attr);
  H5Sclose(space);
  H5Tclose(type);
  PetscFunctionReturn(0);
}

// An attribute holding a table: one record of variable-length UTF-8 strings
// per row, one member per column (h5py reads a structured array).
PetscErrorCode TableAttribute(MPI_Comm comm, hid_t obj, const char *name, const std::vector<const char *> &columns,
                              const std::vector<std::vector<std::string>> &rows)
{
  hid_t str, type, space, attr;
  const size_t nc = columns.size();
  PetscFunctionBeginUser;
  PetscCheck((str = H5Tcopy(H5T_C_S1)) >= 0 && H5Tset_size(str, H5T_VARIABLE) >= 0 && H5Tset_cset(str, H5T_CSET_UTF8) >= 0, comm, PETSC_ERR_LIB,
             "HDF5 string type for attribute %s failed", name);
  PetscCheck((type = H5Tcreate(H5T_COMPOUND, nc * sizeof(char *))) >= 0, comm, PETSC_ERR_LIB, "HDF5 table type for attribute %s failed", name);
  for (size_t c = 0; c < nc; c++)
    PetscCheck(H5Tinsert(type, columns[c], c * sizeof(char *), str) >= 0, comm, PETSC_ERR_LIB, "HDF5 table column %s failed", columns[c]);
  std::vector<const char *> buf;
  for (const auto &r : rows)
    for (size_t c = 0; c < nc; c++) buf.push_back(r.at(c).c_str());
  const hsize_t n = rows.size();
  PetscCheck((space = H5Screate_simple(1, &n, NULL)) >= 0, comm, PETSC_ERR_LIB, "HDF5 dataspace for attribute %s failed", name);
  if (H5Aexists(obj, name) > 0) H5Adelete(obj, name);
  PetscCheck((attr = H5Acreate2(obj, name, type, space, H5P_DEFAULT, H5P_DEFAULT)) >= 0, comm, PETSC_ERR_LIB, "HDF5 attribute %s failed", name);
  PetscCheck(!n || H5Awrite(attr, type, buf.data()) >= 0, comm, PETSC_ERR_LIB, "HDF5 attribute %s failed", name);
  H5Aclose(attr);
  H5Sclose(space);
  H5Tclose(type);
  H5Tclose(str);
  PetscFunctionReturn(0);
}

// The schema row of a written field, checked for a description and units.
PetscErrorCode Describe(MPI_Comm comm, const std::string &group, const std::string &name, FieldKind kind, const Field **f)
{
  PetscFunctionBeginUser;
  *f = FindField(group, name, kind);
  if (!SchemaCheckOn()) {
    if (*f && (!(*f)->units || !(*f)->meaning)) *f = nullptr;
    PetscFunctionReturn(0);
  }
  PetscCheck(*f, comm, PETSC_ERR_PLIB, "output schema has no %s %s in group %s: add it to the schema its study registers (studies/registry.hpp)",
             KindName(kind), name.c_str(), group.c_str());
  PetscCheck((*f)->units && *(*f)->units && (*f)->meaning && *(*f)->meaning, comm, PETSC_ERR_PLIB,
             "output schema: %s %s/%s needs a description and units (io/schema.hpp)", KindName(kind), group.c_str(), name.c_str());
  PetscFunctionReturn(0);
}

const char *const kFieldsTable = "fields";

PetscErrorCode DescribeDataset(MPI_Comm comm, hid_t file, const std::string &path, const Field &f)
{
  hid_t d;
  PetscFunctionBeginUser;
  PetscCheck((d = H5Dopen2(file, path.c_str(), H5P_DEFAULT)) >= 0, comm, PETSC_ERR_LIB, "HDF5 cannot open dataset %s", path.c_str());
  PetscCall(StringAttribute(comm, d, "description", f.meaning));
  PetscCall(StringAttribute(comm, d, "units", f.units));
  if (f.codes) PetscCall(StringAttribute(comm, d, "codes", f.codes));
  H5Dclose(d);
  PetscFunctionReturn(0);
}

// The `fields` table of a group's attributes (none: no table).
PetscErrorCode DescribeAttributes(MPI_Comm comm, hid_t file, const std::string &group)
{
  std::vector<std::string> names;
  hid_t g;
  PetscFunctionBeginUser;
  PetscCheck((g = H5Gopen2(file, group.c_str(), H5P_DEFAULT)) >= 0, comm, PETSC_ERR_LIB, "HDF5 cannot open group %s", group.c_str());
  hsize_t idx = 0;
  H5Aiterate2(g, H5_INDEX_NAME, H5_ITER_INC, &idx, CollectAttribute, &names);
  std::vector<std::vector<std::string>> rows;
  for (const std::string &n : names) {
    if (n == kFieldsTable) continue;
    const Field *f;
    PetscCall(Describe(comm, group, n, FieldKind::Attribute, &f));
    if (f) rows.push_back({n, f->units, f->meaning, f->codes ? f->codes : ""});
  }
  if (!rows.empty()) PetscCall(TableAttribute(comm, g, kFieldsTable, {"name", "units", "description", "codes"}, rows));
  H5Gclose(g);
  PetscFunctionReturn(0);
}

} // namespace

std::vector<std::pair<std::string, std::string>> GivenOptionPairs()
{
  std::vector<std::pair<std::string, std::string>> pairs;
  PetscInt nleft = 0;
  char **lnames = nullptr, **lvalues = nullptr, *all = nullptr;
  std::map<std::string, std::string> unused; // read exactly without marking anything used
  if (!PetscOptionsLeftGet(NULL, &nleft, &lnames, &lvalues)) {
    for (PetscInt i = 0; i < nleft; i++) {
      std::string k = lnames[i];
      for (char &c : k) c = (char)std::tolower((unsigned char)c);
      unused[k] = lvalues[i] ? lvalues[i] : "";
    }
    PetscOptionsLeftRestore(NULL, &nleft, &lnames, &lvalues);
  }
  if (PetscOptionsGetAll(NULL, &all) || !all) return pairs;
  std::istringstream in(all);
  std::vector<std::string> tok;
  for (std::string t; in >> t;) tok.push_back(t);
  PetscFree(all);
  // GetAll writes "-key value" in the database's order; the exact value of each
  // key tells how many of the following tokens it spans (a value may hold options).
  for (size_t i = 0; i < tok.size();) {
    std::string key = tok[i++].substr(1);
    std::string lower = key;
    for (char &c : lower) c = (char)std::tolower((unsigned char)c);
    std::string value;
    if (unused.count(lower)) value = unused[lower];
    else {
      const char *val = nullptr;
      PetscBool set = PETSC_FALSE;
      if (!PetscOptionsFindPair(NULL, NULL, ("-" + key).c_str(), &val, &set) && set && val) value = val;
    }
    std::istringstream vs(value);
    for (std::string t; vs >> t && i < tok.size();) i++;
    pairs.push_back({key, value});
  }
  return pairs;
}

PetscErrorCode WriteGivenOptions(PetscViewer v)
{
  hid_t file, root;
  PetscFunctionBeginUser;
  std::vector<std::vector<std::string>> rows;
  for (const auto &kv : GivenOptionPairs()) rows.push_back({kv.first, kv.second});
  PetscCall(PetscViewerHDF5GetFileId(v, &file));
  PetscCheck((root = H5Gopen2(file, "/", H5P_DEFAULT)) >= 0, PetscObjectComm((PetscObject)v), PETSC_ERR_LIB, "HDF5 cannot open the root group");
  PetscCall(TableAttribute(PetscObjectComm((PetscObject)v), root, "options_table", {"key", "value"}, rows));
  H5Gclose(root);
  PetscFunctionReturn(0);
}

PetscErrorCode DescribeFile(PetscViewer v)
{
  MPI_Comm comm = PetscObjectComm((PetscObject)v);
  hid_t file;
  std::vector<Object> objects;
  PetscFunctionBeginUser;
  PetscCall(PetscViewerHDF5GetFileId(v, &file));
  PetscCheck(H5Ovisit(file, H5_INDEX_NAME, H5_ITER_INC, CollectObject, &objects) >= 0, comm, PETSC_ERR_LIB, "HDF5 cannot list the output's objects");
  for (const Object &o : objects) {
    if (!o.dataset) {
      PetscCall(DescribeAttributes(comm, file, o.path));
      continue;
    }
    const std::string group = Parent(o.path), name = Base(o.path);
    const Field *f;
    PetscCall(Describe(comm, group, name, FieldKind::Dataset, &f));
    if (f) PetscCall(DescribeDataset(comm, file, o.path, *f));
  }
  PetscFunctionReturn(0);
}

} // namespace nltopo
