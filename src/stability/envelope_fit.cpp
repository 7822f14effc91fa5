#include "stability/envelope_fit.hpp"
#include <cmath>

namespace nltopo {

const char *const kScalingVerdictCodes = "0 stable (no orbit of the window unstable at any N); 1 persists (p < -scaling_persist_exponent); 2 finite-size "
                                          "(p >= it); 3 undetermined (fewer than two N with an unstable orbit, or the threshold within one standard error of p)";

const char *ScalingVerdictName(PetscInt v)
{
  switch (v) {
  case kScalingStable: return "stable";
  case kScalingPersists: return "persists";
  case kScalingFiniteSize: return "finite-size";
  default: return "undetermined";
  }
}

PetscInt WindowMaximum(const std::vector<PetscReal> &energy, const std::vector<PetscReal> &max_modulus, PetscReal lo, PetscReal hi, PetscReal *envelope)
{
  PetscInt best = -1;
  *envelope = NAN;
  for (size_t i = 0; i < energy.size() && i < max_modulus.size(); i++) {
    if (!(energy[i] >= lo && energy[i] < hi) || !std::isfinite(max_modulus[i])) continue;
    if (best < 0 || max_modulus[i] > max_modulus[best]) best = (PetscInt)i;
  }
  if (best >= 0) *envelope = max_modulus[best] - 1;
  return best;
}

EnvelopeFit FitEnvelope(const std::vector<PetscReal> &N, const std::vector<PetscReal> &envelope, PetscReal tol, PetscReal p_persist)
{
  EnvelopeFit f;
  std::vector<PetscReal> x, y;
  bool any_orbit = false;
  for (size_t k = 0; k < N.size() && k < envelope.size(); k++) {
    if (!std::isfinite(envelope[k])) continue;
    any_orbit = true;
    if (envelope[k] > tol) x.push_back(std::log(N[k])), y.push_back(std::log(envelope[k]));
  }
  f.npoints = (PetscInt)x.size();
  if (any_orbit && x.empty()) {
    f.verdict = kScalingStable;
    return f;
  }
  if (f.npoints < 2) return f; // undetermined
  const PetscReal n = (PetscReal)x.size();
  PetscReal mx = 0, my = 0;
  for (size_t i = 0; i < x.size(); i++) mx += x[i] / n, my += y[i] / n;
  PetscReal sxx = 0, sxy = 0, syy = 0;
  for (size_t i = 0; i < x.size(); i++) sxx += (x[i] - mx) * (x[i] - mx), sxy += (x[i] - mx) * (y[i] - my), syy += (y[i] - my) * (y[i] - my);
  if (!(sxx > 0)) return f; // every point at one N
  const PetscReal slope = sxy / sxx, icpt = my - slope * mx;
  PetscReal ssr = 0;
  for (size_t i = 0; i < x.size(); i++) ssr += std::pow(y[i] - (icpt + slope * x[i]), 2);
  f.p = -slope, f.C = std::exp(icpt);
  f.r2 = syy > 0 ? 1 - ssr / syy : 1;
  f.residual = std::sqrt(ssr / n);
  if (x.size() > 2) f.p_stderr = std::sqrt(ssr / (n - 2) / sxx);
  // decided when the threshold lies outside p +- its standard error (two points: no error estimate, decided by p)
  const bool decided = !(std::abs(f.p - p_persist) <= (std::isfinite(f.p_stderr) ? f.p_stderr : 0));
  f.verdict = !decided ? kScalingUndetermined : f.p < p_persist ? kScalingPersists : kScalingFiniteSize;
  return f;
}

} // namespace nltopo
