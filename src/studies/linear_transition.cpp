#include "studies/linear_transition.hpp"
#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace nltopo {

namespace {

const PetscInt kGammaListMaxPoints = 100000; // as the grid axes of the other studies (grid_axis.cpp)

// Describes how a Zak phase column (stride 2, band b) changes along gamma: its
// values and where it jumps, the points where it is undefined (NaN: gap closed).
std::string ZakSummary(const TransitionResult &t, const std::vector<PetscReal> &zak, int band)
{
  std::string s, undefined;
  char buf[160];
  PetscReal last = NAN, last_g = NAN;
  for (size_t i = 0; i < t.gamma.size(); i++) {
    const PetscReal z = zak[2 * i + band], g = t.gamma[i];
    if (std::isnan(z)) {
      std::snprintf(buf, sizeof(buf), "%s%g", undefined.empty() ? "" : ", ", (double)g);
      undefined += buf;
      continue;
    }
    if (std::isnan(last)) std::snprintf(buf, sizeof(buf), "%.6f from gamma = %g", (double)z, (double)g);
    else if (std::abs(z - last) > PETSC_PI / 2)
      std::snprintf(buf, sizeof(buf), "; jumps to %.6f between gamma = %g and %g", (double)z, (double)last_g, (double)g);
    else buf[0] = 0;
    s += buf;
    last = z, last_g = g;
  }
  if (!undefined.empty()) s += "; NaN (gap closed, k1 = k2) at gamma = " + undefined;
  return s;
}

// Frequencies of row i outside the infinite bands (with relative slack 1e-9):
// in the gap, and below / above both bands: the localised (edge, interface) modes.
void LocalisedModes(const TransitionResult &t, size_t i, std::vector<PetscReal> *in_gap, std::vector<PetscReal> *outside)
{
  const PetscReal *b = &t.bands_inf[4 * i], *w = &t.omega[i * (size_t)t.N], tol = 1e-9 * b[3];
  in_gap->clear(), outside->clear();
  for (PetscInt j = 0; j < t.N; j++) {
    if (w[j] > b[1] + tol && w[j] < b[2] - tol) in_gap->push_back(w[j]);
    else if (w[j] < b[0] - tol || w[j] > b[3] + tol) outside->push_back(w[j]);
  }
}

std::string List(const std::vector<PetscReal> &v)
{
  std::string s;
  char buf[32];
  for (size_t j = 0; j < v.size() && j < 6; j++) {
    std::snprintf(buf, sizeof(buf), "%s%.7f", j ? ", " : "", (double)v[j]);
    s += buf;
  }
  return v.size() > 6 ? s + ", ..." : s;
}

} // namespace

PetscErrorCode ParseGammaList(MPI_Comm comm, const std::string &given, GammaList *g)
{
  const size_t a = given.find_first_not_of(" \t"), b = given.find_last_not_of(" \t");
  const std::string value = a == std::string::npos ? "" : given.substr(a, b - a + 1);
  const char *v = given.c_str();
  PetscFunctionBeginUser;
  g->text = value;
  const size_t c1 = value.find(':'), c2 = c1 == std::string::npos ? c1 : value.find(':', c1 + 1);
  bool ok = c2 != std::string::npos && value.find(':', c2 + 1) == std::string::npos;
  if (ok) { // each field a whole number: strtod/strtol must consume it exactly
    const std::string f[3] = {value.substr(0, c1), value.substr(c1 + 1, c2 - c1 - 1), value.substr(c2 + 1)};
    char *end;
    for (int k = 0; k < 2 && ok; k++) {
      const double x = std::strtod(f[k].c_str(), &end);
      ok = !f[k].empty() && *end == 0 && f[k].find_first_of(" \t") == std::string::npos;
      (k ? g->hi : g->lo) = (PetscReal)x;
    }
    errno = 0;
    const long long n = ok ? std::strtoll(f[2].c_str(), &end, 10) : 0;
    ok = ok && !f[2].empty() && *end == 0 && errno == 0 && f[2].find_first_of(" \t+") == std::string::npos;
    g->n = ok && n >= -1 && n <= kGammaListMaxPoints ? (PetscInt)n : -1; // -1: out of range, checked below
  }
  PetscCheck(ok, comm, PETSC_ERR_USER, "-linear_gamma_list %s: expected min:max:n, e.g. -1:1:201", v);
  PetscCheck(g->lo >= -1 && g->hi <= 1 && g->lo < g->hi, comm, PETSC_ERR_USER,
             "-linear_gamma_list %s: min and max must satisfy -1 <= min < max <= 1 (k1 = k(1+gamma), k2 = k(1-gamma) not negative)", v); // false for nan
  PetscCheck(g->n >= 2, comm, PETSC_ERR_USER, "-linear_gamma_list %s: n must lie in [2, %d]", v, (int)kGammaListMaxPoints);
  PetscFunctionReturn(0);
}

PetscErrorCode PrintTransitionSummary(MPI_Comm comm, const LatticeParams &lp, const TransitionResult &t, PetscLogDouble seconds)
{
  const size_t ng = t.gamma.size();
  const char *cells[2] = {"left cell (intra k2, inter k1)", "right cell (intra k1, inter k2)"}, *bands[2] = {"acoustic", "optical"};
  PetscFunctionBeginUser;
  char line[256]; // std::snprintf: PETSc's own %g prints -1 as "-1."
  std::snprintf(line, sizeof(line), "  transition: %zu values of gamma in [%g, %g], N = %d, %.3f s\n", ng, (double)t.gamma.front(), (double)t.gamma.back(),
                (int)t.N, (double)seconds);
  PetscCall(PetscPrintf(comm, "%s", line));
  for (int c = 0; c < 2; c++)
    for (int b = 0; b < 2; b++)
      PetscCall(PetscPrintf(comm, "  Zak phase, %s, %s: %s\n", cells[c], bands[b], ZakSummary(t, c ? t.zak_right : t.zak_left, b).c_str()));
  // The grid point nearest gamma = 0 (the gap closes there) and nearest the study's -lattice_gamma.
  size_t i0 = 0, il = 0;
  for (size_t i = 0; i < ng; i++) {
    if (std::abs(t.gamma[i]) < std::abs(t.gamma[i0])) i0 = i;
    if (std::abs(t.gamma[i] - lp.gamma) < std::abs(t.gamma[il] - lp.gamma)) il = i;
  }
  const PetscReal root = std::sqrt(lp.KHat()), *w0 = &t.omega[i0 * (size_t)t.N];
  const PetscReal *above = std::upper_bound(w0, w0 + t.N, root), *below = above == w0 ? w0 : above - 1;
  if (above == w0 + t.N) above = below;
  std::snprintf(line, sizeof(line),
                "  gamma = %g: infinite-lattice gap %.6f .. %.6f; finite frequencies next to sqrt(k_hat) = %.7f: %.7f and %.7f (spacing %.3g)\n",
                (double)t.gamma[i0], (double)t.bands_inf[4 * i0 + 1], (double)t.bands_inf[4 * i0 + 2], (double)root, (double)*below, (double)*above,
                (double)(*above - *below));
  PetscCall(PetscPrintf(comm, "%s", line));
  size_t unstable = 0;
  for (size_t i = 0; i < ng; i++) unstable += t.lambda_min[i] < 0;
  if (unstable) {
    std::snprintf(line, sizeof(line),
                  "  warning: K is not positive definite at %zu of the gamma values (smallest eigenvalue %.4g; lambda_min < 0 there, its omega written as 0)\n",
                  unstable, (double)*std::min_element(t.lambda_min.begin(), t.lambda_min.end()));
    PetscCall(PetscPrintf(comm, "%s", line));
  }
  std::vector<PetscReal> gap, out;
  LocalisedModes(t, il, &gap, &out);
  std::snprintf(line, sizeof(line), "  gamma = %g: %zu modes in the gap, %zu outside the bands (localised: edge and interface modes)\n", (double)t.gamma[il],
                gap.size(), out.size());
  PetscCall(PetscPrintf(comm, "%s    in the gap: %s\n    outside:    %s\n", line, List(gap).c_str(), List(out).c_str()));
  PetscFunctionReturn(0);
}

} // namespace nltopo
