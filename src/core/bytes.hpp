#pragma once
// Plain values, vectors of them and strings as bytes and back, in the order
// they were written: what one group of ranks computed, sent to the others
// (every rank runs the same build, so the bytes need not be portable).
#include <petscsys.h>
#include <algorithm>
#include <string>
#include <type_traits>
#include <vector>

namespace nltopo {

class Bytes {
public:
  // Field by field, in one order for writing (put) and reading.
  template <typename T> void Field(T &x, bool put) { put ? Put(x) : Get(&x); }
  // root's bytes to every rank of comm; reading starts at the beginning. Collective.
  PetscErrorCode Bcast(MPI_Comm comm, PetscMPIInt root)
  {
    unsigned long long n = b_.size();
    PetscFunctionBeginUser;
    PetscCallMPI(MPI_Bcast(&n, 1, MPI_UNSIGNED_LONG_LONG, root, comm));
    b_.resize(n);
    PetscCallMPI(MPI_Bcast(b_.data(), (PetscMPIInt)n, MPI_CHAR, root, comm));
    at_ = 0;
    PetscFunctionReturn(0);
  }

private:
  template <typename T> void Put(const T &v)
  {
    static_assert(std::is_trivially_copyable<T>::value, "Bytes: plain values only");
    b_.insert(b_.end(), (const char *)&v, (const char *)&v + sizeof v);
  }
  template <typename T> void Put(const std::vector<T> &v)
  {
    static_assert(std::is_trivially_copyable<T>::value, "Bytes: vectors of plain values only");
    Put(v.size());
    b_.insert(b_.end(), (const char *)v.data(), (const char *)(v.data() + v.size()));
  }
  void Put(const std::string &s) { Put(std::vector<char>(s.begin(), s.end())); }
  template <typename T> void Get(T *v)
  {
    std::copy(b_.begin() + at_, b_.begin() + at_ + sizeof *v, (char *)v);
    at_ += sizeof *v;
  }
  template <typename T> void Get(std::vector<T> *v)
  {
    size_t n;
    Get(&n);
    v->resize(n);
    std::copy(b_.begin() + at_, b_.begin() + at_ + n * sizeof(T), (char *)v->data());
    at_ += n * sizeof(T);
  }
  void Get(std::string *s)
  {
    std::vector<char> c;
    Get(&c);
    s->assign(c.begin(), c.end());
  }
  std::vector<char> b_;
  size_t at_ = 0;
};

} // namespace nltopo
