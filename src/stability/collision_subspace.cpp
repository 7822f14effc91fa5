#include "stability/collision_subspace.hpp"
#include "core/lapack.hpp"
#include "core/log.hpp"
#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <utility>

namespace nltopo {

namespace {

constexpr int kCandidates = 8;         // upper members nearest b* (a step off the curve splits the pair's b by +-sqrt(g)/2)
constexpr int kPairsOf = 3;            // of these, the best by their own overlap with the last subspace: 3 pairs to compare
constexpr PetscReal kMinOverlap = 0.5; // a choice that overlaps less with the last point's subspace is another collision

// The real Schur form T = Z^T M Z of a (n x n): T into t, Z into z, the eigenvalues into wr, wi.
PetscErrorCode RealSchur(int n, PetscReal *a, std::vector<PetscReal> &t, std::vector<PetscReal> &z, std::vector<PetscReal> &wr, std::vector<PetscReal> &wi)
{
  const int one = 1;
  int info = 0, lwork = -1;
  PetscReal wq;
  PetscFunctionBeginUser;
  std::vector<PetscReal> tau(std::max(1, n - 1)), work;
  wr.assign(n, 0), wi.assign(n, 0);
  dgehrd_(&n, &one, &n, a, &n, tau.data(), &wq, &lwork, &info);
  work.assign((size_t)wq + 1, 0);
  lwork = (int)work.size();
  dgehrd_(&n, &one, &n, a, &n, tau.data(), work.data(), &lwork, &info);
  PetscCheck(info == 0, PETSC_COMM_SELF, PETSC_ERR_LIB, "collision subspace: LAPACK dgehrd failed, info %d", info);
  t.assign((size_t)n * n, 0.0);
  for (int c = 0; c < n; c++)
    for (int i = 0; i <= std::min(c + 1, n - 1); i++) t[(size_t)c * n + i] = a[(size_t)c * n + i];
  z.assign(a, a + (size_t)n * n);
  lwork = -1;
  dorghr_(&n, &one, &n, z.data(), &n, tau.data(), &wq, &lwork, &info);
  work.assign(std::max(work.size(), (size_t)wq + 1), 0);
  lwork = (int)work.size();
  dorghr_(&n, &one, &n, z.data(), &n, tau.data(), work.data(), &lwork, &info);
  PetscCheck(info == 0, PETSC_COMM_SELF, PETSC_ERR_LIB, "collision subspace: LAPACK dorghr failed, info %d", info);
  lwork = -1;
  dhseqr_("S", "V", &n, &one, &n, t.data(), &n, wr.data(), wi.data(), z.data(), &n, &wq, &lwork, &info, 1, 1);
  work.assign(std::max(work.size(), (size_t)wq + 1), 0);
  lwork = (int)work.size();
  dhseqr_("S", "V", &n, &one, &n, t.data(), &n, wr.data(), wi.data(), z.data(), &n, work.data(), &lwork, &info, 1, 1);
  PetscCheck(info == 0, PETSC_COMM_SELF, PETSC_ERR_LIB, "collision subspace: LAPACK dhseqr failed, info %d", info);
  PetscFunctionReturn(0);
}

// The orthonormal basis (n x 2 per complex pair) of the invariant subspace of the complex pairs at Schur
// positions idx; empty where the reordering fails (a block too close to another to be swapped past it:
// LAPACK's info 1).
PetscErrorCode Basis(int n, const std::vector<PetscReal> &t, const std::vector<PetscReal> &z, std::initializer_list<int> idx, std::vector<PetscReal> *basis)
{
  int m = 0, info = 0, liwork = 1, iwork = 0;
  PetscReal s, sep;
  PetscFunctionBeginUser;
  std::vector<int> select(n, 0);
  for (int i : idx) select[i] = 1; // (a complex pair's two positions move together)
  std::vector<PetscReal> tt = t, zz = z, wr(n), wi(n), work(n);
  const int lwork = n, want = 2 * (int)idx.size();
  dtrsen_("N", "V", select.data(), &n, tt.data(), &n, zz.data(), &n, wr.data(), wi.data(), &m, &s, &sep, work.data(), &lwork, &iwork, &liwork, &info, 1, 1);
  basis->clear();
  if (info == 1) PetscFunctionReturn(0);
  PetscCheck(info == 0 && m == want, PETSC_COMM_SELF, PETSC_ERR_LIB, "collision subspace: LAPACK dtrsen failed, info %d, m %d", info, m);
  basis->assign(zz.begin(), zz.begin() + (size_t)want * n);
  PetscFunctionReturn(0);
}

// ||u^T v||_F^2 / k for u (n x 4) and v (n x k), orthonormal columns: 1 when v lies in u's span.
PetscReal Overlap(int n, const std::vector<PetscReal> &u, const std::vector<PetscReal> &v)
{
  const int k = (int)(v.size() / n);
  PetscReal f = 0;
  for (int a = 0; a < 4; a++)
    for (int b = 0; b < k; b++) {
      PetscReal d = 0;
      for (int i = 0; i < n; i++) d += u[(size_t)a * n + i] * v[(size_t)b * n + i];
      f += d * d;
    }
  return f / k;
}

} // namespace

PetscErrorCode TrackCollision(int n, PetscReal *a, PetscReal tol, PetscReal bstar, const std::vector<PetscReal> &prev, CollisionChoice *out)
{
  using C = std::complex<PetscReal>;
  std::vector<PetscReal> t, z, wr, wi;
  static PetscLogEvent ev = 0;
  PetscFunctionBeginUser;
  if (!ev) PetscCall(NamedLogEvent("CollisionTrack", &ev));
  PetscCall(PetscLogEventBegin(ev, 0, 0, 0, 0));
  *out = CollisionChoice();
  PetscCall(RealSchur(n, a, t, z, wr, wi));
  for (int k = 0; k < n; k++) out->mu.emplace_back(wr[k], wi[k]);
  std::vector<int> up; // upper members (a real pair: a branch point or period doubling, not these)
  for (int k = 0; k < n; k++)
    if (wi[k] > tol * std::abs(out->mu[k])) up.push_back(k);
  auto b = [&](int k) { return 0.5 * (out->mu[k] + 1.0 / out->mu[k]); };
  std::sort(up.begin(), up.end(), [&](int p, int q) { return std::abs(b(p) - bstar) < std::abs(b(q) - bstar); });
  if (up.size() > (size_t)kCandidates) up.resize(kCandidates);
  if (!prev.empty()) { // the candidates whose own subspace lies most in the last point's (a failed reordering: 0.5, undecided)
    std::vector<std::pair<PetscReal, int>> own;
    for (int k : up) {
      std::vector<PetscReal> u;
      PetscCall(Basis(n, t, z, {k}, &u));
      own.emplace_back(u.empty() ? 0.5 : Overlap(n, prev, u), k);
    }
    std::stable_sort(own.begin(), own.end(), [](const auto &x, const auto &y) { return x.first > y.first; });
    up.clear();
    for (size_t k = 0; k < own.size() && k < (size_t)kPairsOf; k++) up.push_back(own[k].second);
  }
  PetscReal best = -1;
  const size_t last = prev.empty() ? std::min<size_t>(up.size(), 2) : up.size(); // without prev: the two nearest b* alone
  for (size_t p = 0; p < last; p++)
    for (size_t q = p + 1; q < last; q++) {
      const C s = b(up[p]) + b(up[q]);
      if (std::abs(s.imag()) > 2 * tol) continue; // not both real nor conjugate: no collision
      std::vector<PetscReal> basis;
      PetscCall(Basis(n, t, z, {up[p], up[q]}, &basis));
      if (basis.empty() && !prev.empty()) continue;
      const PetscReal ov = prev.empty() || basis.empty() ? 0 : Overlap(n, prev, basis);
      if (!prev.empty() && ov < kMinOverlap) continue;
      if (ov > best) {
        best = ov, out->ok = true, out->overlap = ov;
        out->g = std::real((b(up[p]) - b(up[q])) * (b(up[p]) - b(up[q])));
        out->bmid = 0.5 * s.real();
        out->basis = std::move(basis);
      }
    }
  PetscCall(PetscLogEventEnd(ev, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

} // namespace nltopo
