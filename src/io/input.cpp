#include "io/input.hpp"
#include <cstring>
#include <hdf5.h>

namespace nltopo {

namespace {
template <typename T> PetscErrorCode ReadDataset(const std::string &file, const char *dataset, hid_t type, std::vector<T> *out)
{
  PetscFunctionBeginUser;
  H5E_auto2_t func;
  void *data;
  H5Eget_auto2(H5E_DEFAULT, &func, &data);
  H5Eset_auto2(H5E_DEFAULT, NULL, NULL); // our message instead of HDF5's stack dump
  hid_t f = H5Fopen(file.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  hid_t d = f < 0 ? -1 : H5Dopen2(f, dataset, H5P_DEFAULT);
  hid_t s = d < 0 ? -1 : H5Dget_space(d);
  hssize_t n = s < 0 ? -1 : H5Sget_simple_extent_npoints(s);
  herr_t st = -1;
  if (n >= 0) {
    out->resize((size_t)n);
    st = n ? H5Dread(d, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, out->data()) : 0;
  }
  if (s >= 0) H5Sclose(s);
  if (d >= 0) H5Dclose(d);
  if (f >= 0) H5Fclose(f);
  H5Eset_auto2(H5E_DEFAULT, func, data);
  PetscCheck(f >= 0, PETSC_COMM_SELF, PETSC_ERR_FILE_OPEN, "cannot open HDF5 file %s", file.c_str());
  PetscCheck(st >= 0, PETSC_COMM_SELF, PETSC_ERR_FILE_READ, "cannot read dataset %s from %s", dataset, file.c_str());
  PetscFunctionReturn(0);
}
} // namespace

PetscErrorCode ReadDoubles(const std::string &file, const char *dataset, std::vector<PetscReal> *out)
{
  PetscFunctionBeginUser;
  PetscCall(ReadDataset(file, dataset, H5T_NATIVE_DOUBLE, out));
  PetscFunctionReturn(0);
}

PetscErrorCode ReadInts(const std::string &file, const char *dataset, std::vector<PetscInt> *out)
{
  std::vector<int> buf;
  PetscFunctionBeginUser;
  PetscCall(ReadDataset(file, dataset, H5T_NATIVE_INT, &buf));
  out->assign(buf.begin(), buf.end());
  PetscFunctionReturn(0);
}

PetscErrorCode ReadStrings(const std::string &file, const char *dataset, std::vector<std::string> *out)
{
  PetscFunctionBeginUser;
  H5E_auto2_t func;
  void *data;
  H5Eget_auto2(H5E_DEFAULT, &func, &data);
  H5Eset_auto2(H5E_DEFAULT, NULL, NULL);
  hid_t f = H5Fopen(file.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  hid_t d = f < 0 ? -1 : H5Dopen2(f, dataset, H5P_DEFAULT);
  hid_t t = d < 0 ? -1 : H5Dget_type(d);
  hid_t s = d < 0 ? -1 : H5Dget_space(d);
  const bool fixed = t >= 0 && H5Tget_class(t) == H5T_STRING && H5Tis_variable_str(t) == 0;
  const size_t width = fixed ? H5Tget_size(t) : 0;
  const hssize_t n = s < 0 ? -1 : H5Sget_simple_extent_npoints(s);
  herr_t st = -1;
  if (fixed && n >= 0) {
    std::vector<char> buf((size_t)n * width + 1, '\0');
    st = n ? H5Dread(d, t, H5S_ALL, H5S_ALL, H5P_DEFAULT, buf.data()) : 0;
    out->clear();
    for (hssize_t i = 0; st >= 0 && i < n; i++) {
      const char *c = buf.data() + (size_t)i * width;
      out->emplace_back(c, strnlen(c, width));
    }
  }
  if (s >= 0) H5Sclose(s);
  if (t >= 0) H5Tclose(t);
  if (d >= 0) H5Dclose(d);
  if (f >= 0) H5Fclose(f);
  H5Eset_auto2(H5E_DEFAULT, func, data);
  PetscCheck(f >= 0, PETSC_COMM_SELF, PETSC_ERR_FILE_OPEN, "cannot open HDF5 file %s", file.c_str());
  PetscCheck(st >= 0, PETSC_COMM_SELF, PETSC_ERR_FILE_READ, "cannot read dataset %s from %s as fixed-length strings", dataset, file.c_str());
  PetscFunctionReturn(0);
}

bool HasDataset(const std::string &file, const char *dataset)
{
  H5E_auto2_t func;
  void *data;
  H5Eget_auto2(H5E_DEFAULT, &func, &data);
  H5Eset_auto2(H5E_DEFAULT, NULL, NULL);
  hid_t f = H5Fopen(file.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  bool ok = f >= 0;
  const std::string path = dataset;
  for (size_t pos = path.find('/', 1); ok; pos = path.find('/', pos + 1)) { // every link along the path, then the dataset
    ok = H5Lexists(f, path.substr(0, pos).c_str(), H5P_DEFAULT) > 0;
    if (pos == std::string::npos) break;
  }
  if (f >= 0) H5Fclose(f);
  H5Eset_auto2(H5E_DEFAULT, func, data);
  return ok;
}

namespace {
// Opens the root attribute `name` of file (errors silenced); f, a < 0 on failure.
// name: an attribute of the root, or "<object path>/<attribute>" of a group or dataset.
void OpenRootAttribute(const std::string &file, const char *name, hid_t *f, hid_t *a)
{
  *f = H5Fopen(file.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  const std::string path(name);
  const size_t slash = path.rfind('/');
  const std::string obj = slash == std::string::npos ? "." : (slash == 0 ? "/" : path.substr(0, slash)),
                    attr = slash == std::string::npos ? path : path.substr(slash + 1);
  *a = -1;
  if (*f < 0) return;
  if (obj != "." && obj != "/" && H5Lexists(*f, obj.c_str(), H5P_DEFAULT) <= 0) return;
  if (H5Aexists_by_name(*f, obj.c_str(), attr.c_str(), H5P_DEFAULT) > 0) *a = H5Aopen_by_name(*f, obj.c_str(), attr.c_str(), H5P_DEFAULT, H5P_DEFAULT);
}
} // namespace

bool ReadRootAttribute(const std::string &file, const char *name, std::string *value)
{
  H5E_auto2_t func;
  void *data;
  H5Eget_auto2(H5E_DEFAULT, &func, &data);
  H5Eset_auto2(H5E_DEFAULT, NULL, NULL);
  hid_t f, a, t = -1;
  bool ok = false;
  OpenRootAttribute(file, name, &f, &a);
  if (a >= 0 && (t = H5Aget_type(a)) >= 0 && H5Tget_class(t) == H5T_STRING) {
    if (H5Tis_variable_str(t) > 0) {
      char *s = NULL;
      hid_t mt = H5Tcopy(H5T_C_S1);
      H5Tset_size(mt, H5T_VARIABLE);
      H5Tset_cset(mt, H5Tget_cset(t)); // h5py writes str as UTF-8, which HDF5 will not convert to ASCII
      if (H5Aread(a, mt, &s) >= 0 && s) {
        *value = s;
        ok = true;
        H5free_memory(s);
      }
      H5Tclose(mt);
    } else {
      std::string buf(H5Tget_size(t) + 1, '\0');
      if (H5Aread(a, t, &buf[0]) >= 0) {
        *value = buf.c_str();
        ok = true;
      }
    }
  }
  if (t >= 0) H5Tclose(t);
  if (a >= 0) H5Aclose(a);
  if (f >= 0) H5Fclose(f);
  H5Eset_auto2(H5E_DEFAULT, func, data);
  return ok;
}

namespace {
// A root attribute read as the HDF5 native type `type` into *value, HDF5's own error printing off.
bool ReadRootAttributeAs(const std::string &file, const char *name, hid_t type, void *value)
{
  H5E_auto2_t func;
  void *data;
  H5Eget_auto2(H5E_DEFAULT, &func, &data);
  H5Eset_auto2(H5E_DEFAULT, NULL, NULL);
  hid_t f, a;
  bool ok = false;
  OpenRootAttribute(file, name, &f, &a);
  if (a >= 0) ok = H5Aread(a, type, value) >= 0;
  if (a >= 0) H5Aclose(a);
  if (f >= 0) H5Fclose(f);
  H5Eset_auto2(H5E_DEFAULT, func, data);
  return ok;
}
} // namespace

bool ReadRootAttribute(const std::string &file, const char *name, long *value) { return ReadRootAttributeAs(file, name, H5T_NATIVE_LONG, value); }

bool ReadRootAttribute(const std::string &file, const char *name, double *value) { return ReadRootAttributeAs(file, name, H5T_NATIVE_DOUBLE, value); }

} // namespace nltopo
