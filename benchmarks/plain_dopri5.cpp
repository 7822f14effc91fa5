// plain_dopri5.cpp -- plain C++17 baseline (standard library only) for the
// nltopo PETSc TS benchmark. This integrates the strongly nonlinear SSH interface
// lattice of docs/model.md with a hand-written Dormand-Prince 5(4)
// (Hairer's classic dopri5) and reports step statistics, energy and the MCR.
//
// Build:  g++ -O3 -std=c++17 -o plain_dopri5 plain_dopri5.cpp
// Run:    ./plain_dopri5 --amplitude 0.05 [--cells 25] [--omega 1.7320508]
//           [--energy 1] [--t_final 1000] [--rtol 1e-8] [--atol 1e-8]
//           [--Gamma 0.5] [--repeat 5]
//
// Sites are 0-based here (model.md is 1-based). Fixed: k=1, gamma=0.4,
// gamma0=1, layout=interface, forcing profile eta=`site` (model.md "Forcing").
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>
#include "plain_lattice.hpp"

struct Result {
  long steps = 0, rejected = 0, rhs_evals = 0;
  double t_off = NAN, E_off = NAN, E_final = NAN, mcr = NAN, drift = NAN;
  bool cut = false;
};

// Dormand-Prince 5(4) tableau (Hairer, Norsett & Wanner I, Table 5.2; dopri5.f).
static const double c2 = 1.0/5, c3 = 3.0/10, c4 = 4.0/5, c5 = 8.0/9;
static const double a21 = 1.0/5, a31 = 3.0/40, a32 = 9.0/40;
static const double a41 = 44.0/45, a42 = -56.0/15, a43 = 32.0/9;
static const double a51 = 19372.0/6561, a52 = -25360.0/2187, a53 = 64448.0/6561,
                    a54 = -212.0/729;
static const double a61 = 9017.0/3168, a62 = -355.0/33, a63 = 46732.0/5247,
                    a64 = 49.0/176, a65 = -5103.0/18656;
static const double a71 = 35.0/384, a73 = 500.0/1113, a74 = 125.0/192,
                    a75 = -2187.0/6784, a76 = 11.0/84;         // 5th-order weights (FSAL)
static const double e1 = 71.0/57600, e3 = -71.0/16695, e4 = 71.0/1920,
                    e5 = -17253.0/339200, e6 = 22.0/525, e7 = -1.0/40;  // b - bhat

// Workspace allocated once, outside the timed solve.
struct Work {
  std::vector<double> y, yn, k1, k2, k3, k4, k5, k6, k7, tmp, usq;
  explicit Work(int n2) : y(n2), yn(n2), k1(n2), k2(n2), k3(n2), k4(n2), k5(n2),
                          k6(n2), k7(n2), tmp(n2), usq(n2 / 2) {}
};

static Result solve(Lattice& L, const Params& p, Work& W) {
  const int n = 2 * L.N, N = L.N;
  Result R;
  L.forcing_on = true;
  double *y = W.y.data(), *yn = W.yn.data(), *k1 = W.k1.data(), *k2 = W.k2.data(),
         *k3 = W.k3.data(), *k4 = W.k4.data(), *k5 = W.k5.data(), *k6 = W.k6.data(),
         *k7 = W.k7.data(), *tmp = W.tmp.data(), *usq = W.usq.data();
  std::fill(y, y + n, 0.0);            // start from rest
  std::fill(usq, usq + N, 0.0);
  double t = 0.0, t_start = 0.0;       // t_start: start of the RMS window
  const double tf = p.t_final, rtol = p.rtol, atol = p.atol;
  auto wnorm = [&](const double* e, const double* ya, const double* yb) {
    double s = 0.0;
    for (int i = 0; i < n; ++i) {
      const double sk = atol + rtol * std::max(std::fabs(ya[i]), std::fabs(yb[i]));
      const double q = e[i] / sk; s += q * q;
    }
    return std::sqrt(s / n);
  };
  // Initial step: Hairer's heuristic (dopri5.f HINIT), with y0 as both scale args.
  L.rhs(t, y, k1); ++R.rhs_evals;
  const double d0 = wnorm(y, y, y), d1 = wnorm(k1, y, y);
  double h = (d0 < 1e-5 || d1 < 1e-5) ? 1e-6 : 0.01 * d0 / d1;
  for (int i = 0; i < n; ++i) tmp[i] = y[i] + h * k1[i];
  L.rhs(t + h, tmp, k2); ++R.rhs_evals;
  for (int i = 0; i < n; ++i) k3[i] = (k2[i] - k1[i]) / h;
  const double d2 = wnorm(k3, y, y), dm = std::max(d1, d2);
  const double h1 = dm <= 1e-15 ? std::max(1e-6, h * 1e-3) : std::pow(0.01 / dm, 0.2);
  h = std::min({100 * h, h1, tf - t});

  const double safety = 0.9, facmin = 0.2, facmax = 10.0, expo = 0.2;
  while (t < tf) {
    bool last = false;
    if (t + 1.01 * h >= tf) { h = tf - t; last = true; }  // clip to hit t_final exactly
    // Stages 2..7 (stage 1 = k1, FSAL).
    for (int i = 0; i < n; ++i) tmp[i] = y[i] + h * a21 * k1[i];
    L.rhs(t + c2 * h, tmp, k2);
    for (int i = 0; i < n; ++i) tmp[i] = y[i] + h * (a31 * k1[i] + a32 * k2[i]);
    L.rhs(t + c3 * h, tmp, k3);
    for (int i = 0; i < n; ++i) tmp[i] = y[i] + h * (a41 * k1[i] + a42 * k2[i] + a43 * k3[i]);
    L.rhs(t + c4 * h, tmp, k4);
    for (int i = 0; i < n; ++i)
      tmp[i] = y[i] + h * (a51 * k1[i] + a52 * k2[i] + a53 * k3[i] + a54 * k4[i]);
    L.rhs(t + c5 * h, tmp, k5);
    for (int i = 0; i < n; ++i)
      tmp[i] = y[i] + h * (a61 * k1[i] + a62 * k2[i] + a63 * k3[i] + a64 * k4[i] + a65 * k5[i]);
    L.rhs(t + h, tmp, k6);
    for (int i = 0; i < n; ++i)
      yn[i] = y[i] + h * (a71 * k1[i] + a73 * k3[i] + a74 * k4[i] + a75 * k5[i] + a76 * k6[i]);
    L.rhs(t + h, yn, k7);
    R.rhs_evals += 6;
    for (int i = 0; i < n; ++i)
      tmp[i] = h * (e1 * k1[i] + e3 * k3[i] + e4 * k4[i] + e5 * k5[i] + e6 * k6[i] + e7 * k7[i]);
    const double err = wnorm(tmp, y, yn);
    if (!(err <= 1.0)) {                // reject (also catches NaN)
      ++R.rejected;
      h *= std::max(facmin, safety * std::pow(err, -expo));
      if (!(h > 1e-14 * std::max(1.0, t))) { std::fprintf(stderr, "step size underflow at t=%g\n", t); std::exit(2); }
      continue;
    }
    ++R.steps;
    const double tn = last ? tf : t + h;
    // Trapezoid accumulation of int u_i^2 dt over this step (RMS diagnostic).
    for (int i = 0; i < N; ++i) usq[i] += 0.5 * h * (y[i] * y[i] + yn[i] * yn[i]);
    std::swap(y, yn); std::swap(k1, k7);  // FSAL: k7 at (tn, ynew) is next k1
    t = tn;
    // Energy cut-off (model.md "Forcing"): first accepted step with E >= E* ends
    // the forcing for good; the RMS window restarts at t_off; FSAL re-evaluated.
    if (L.forcing_on) {
      const double E = L.energy(y);
      if (E >= p.Estar) {
        L.forcing_on = false; R.cut = true; R.t_off = t; R.E_off = E; t_start = t;
        std::fill(usq, usq + N, 0.0);
        L.rhs(t, y, k1); ++R.rhs_evals;
      }
    }
    const double fac = err > 0 ? std::min(facmax, std::max(facmin, safety * std::pow(err, -expo))) : facmax;
    h = std::min(h * fac, tf);
  }
  R.E_final = L.energy(y);
  if (R.cut) R.drift = (R.E_final - R.E_off) / R.E_off;
  // rms_i = sqrt(int u_i^2 / (t_final - t_start)); MCR = sum rms^4 / (sum rms^2)^2.
  R.mcr = WindowMcr(usq, N, tf - t_start);
  return R;
}

int main(int argc, char** argv) {
  Params p;
  for (int i = 1; i < argc; ++i) {
    std::string a = argv[i];
    if (i + 1 >= argc) { std::fprintf(stderr, "missing value for %s\n", a.c_str()); return 1; }
    const char* v = argv[++i];
    if (ParseCommon(a, v, p)) continue;
    if (a == "--rtol") p.rtol = std::atof(v);
    else if (a == "--atol") p.atol = std::atof(v);
    else if (a == "--Gamma") p.Gamma = std::atof(v);
    else { std::fprintf(stderr, "unknown option %s\n", a.c_str()); return 1; }
  }
  if (std::isnan(p.S)) {  // model.md: S is the user's to set; no default rule here
    std::fprintf(stderr, "--amplitude S is required (no default S rule)\n");
    return 1;
  }
  Lattice L(p);
  Work W(2 * L.N);
  double med, min_ms;
  const Result R = TimeRepeats(p.repeat, [&] { return solve(L, p, W); }, &med, &min_ms);
  // cutoff=no means the burst ended before E >= E* (model.md: must be said).
  std::printf("N=%d S=%.6g S_rule=user steps=%ld rejected=%ld rhs_evals=%ld cutoff=%s "
              "t_off=%.10g energy_final=%.12g drift=%.3e mcr=%.10g median_ms=%.3f min_ms=%.3f\n",
              L.N, p.S, R.steps, R.rejected, R.rhs_evals, R.cut ? "yes" : "no", R.t_off,
              R.E_final, R.drift, R.mcr, med, min_ms);
  return 0;
}
