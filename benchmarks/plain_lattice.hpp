#pragma once
// The lattice of model.md in plain C++ (standard library only), shared by the
// plain baselines plain_dopri5.cpp and plain_splitting.cpp. Sites are 0-based
// here (model.md is 1-based). Fixed: k=1, gamma=0.4, gamma0=1, layout=interface,
// forcing profile eta=`site` (model.md "Forcing").
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <string>
#include <vector>

struct Params {
  int Nc = 25;
  double omega = std::sqrt(3.0), Estar = 1.0, S = NAN, t_final = 1000.0;
  double rtol = 1e-8, atol = 1e-8, Gamma = 0.5;
  int repeat = 5;
  double dt = 0.05;                 // plain_splitting: the fixed step
};

// Lattice + forcing (model.md "Bonds", "Linear stiffness K", "Equations of motion").
struct Lattice {
  int N, fsite;                 // number of sites; forced site (0-based 2Nc+1 = 1-based m+1)
  double khat;                  // uniform diagonal k1+k2+gamma0 (every site)
  std::vector<double> kb, gb;   // per bond b (joins b, b+1): linear k_b, cubic coeff (Gamma or 0)
  double S, w, tau, t0;         // F(t) = S cos(w t) exp(-((t-t0)/tau)^2) on fsite
  bool forcing_on = true;

  Lattice(const Params& p) {
    const double k = 1.0, gamma = 0.4, gamma0 = 1.0;
    const double k1 = k * (1 + gamma), k2 = k * (1 - gamma);
    N = 4 * p.Nc + 2; fsite = 2 * p.Nc + 1; khat = k1 + k2 + gamma0;
    kb.resize(N - 1); gb.resize(N - 1);
    for (int b = 0; b < N - 1; ++b) {
      const int i = b + 1;      // 1-based bond index of model.md
      const bool stiff = (i <= 2 * p.Nc) ? (i % 2 == 0) : (i % 2 == 1);
      kb[b] = stiff ? k1 : k2;
      gb[b] = stiff ? p.Gamma : 0.0;  // cubic force only on stiff (k1) bonds
    }
    S = p.S; w = p.omega; tau = 25.0 * 2.0 * M_PI / w; t0 = 5.0 * tau;
  }
  double force(double t) const {
    if (!forcing_on) return 0.0;
    const double s = (t - t0) / tau;
    return S * std::cos(w * t) * std::exp(-s * s);
  }
  // a = -K u - f_NL(u) + F(t) eta for the displacements u (length N).
  void accel(double t, const double* u, double* a) const {
    for (int i = 0; i < N; ++i) a[i] = -khat * u[i];
    for (int b = 0; b < N - 1; ++b) {      // off-diagonal -k_b, plus cubic bond force
      const double d = u[b] - u[b + 1];
      const double nl = gb[b] * d * d * d; // f_NL,b += Gamma d^3; f_NL,b+1 -= Gamma d^3
      a[b]     += kb[b] * u[b + 1] - nl;
      a[b + 1] += kb[b] * u[b] + nl;
    }
    a[fsite] += force(t);
  }
  // z = [u, v] (length 2N); dz = [v, -K u - f_NL(u) + F(t) eta]. No allocation.
  void rhs(double t, const double* z, double* dz) const {
    for (int i = 0; i < N; ++i) dz[i] = z[N + i];
    accel(t, z, dz + N);
  }
  // E = 1/2 v.v + 1/2 u.K u + sum_stiff Gamma d^4/4  (model.md "Equations of motion")
  double energy(const double* z) const {
    const double* u = z; const double* v = z + N;
    double e = 0.0;
    for (int i = 0; i < N; ++i) e += 0.5 * (v[i] * v[i] + khat * u[i] * u[i]);
    for (int b = 0; b < N - 1; ++b) {
      const double d = u[b] - u[b + 1];
      e += -kb[b] * u[b] * u[b + 1] + 0.25 * gb[b] * d * d * d * d;
    }
    return e;
  }
  // The parts of E: kinetic, linear (1/2 u.K u) and quartic (the RMS window's nonlinear/linear ratio).
  void energy_parts(const double* z, double* kin, double* lin, double* quart) const {
    const double* u = z; const double* v = z + N;
    double k = 0.0, l = 0.0, q = 0.0;
    for (int i = 0; i < N; ++i) { k += 0.5 * v[i] * v[i]; l += 0.5 * khat * u[i] * u[i]; }
    for (int b = 0; b < N - 1; ++b) {
      const double d = u[b] - u[b + 1];
      l -= kb[b] * u[b] * u[b + 1];
      q += 0.25 * gb[b] * d * d * d * d;
    }
    *kin = k; *lin = l; *quart = q;
  }
};


// Runs solve() `repeat` times; returns the last result, and the median and
// minimum wall time in ms.
template <class Solve>
auto TimeRepeats(int repeat, Solve solve, double* median_ms, double* min_ms) {
  std::vector<double> ms;
  decltype(solve()) R{};
  for (int r = 0; r < repeat; ++r) {
    const auto t0 = std::chrono::steady_clock::now();
    R = solve();
    const auto t1 = std::chrono::steady_clock::now();
    ms.push_back(std::chrono::duration<double, std::milli>(t1 - t0).count());
  }
  std::sort(ms.begin(), ms.end());
  const size_t m = ms.size();
  *median_ms = m % 2 ? ms[m / 2] : 0.5 * (ms[m / 2 - 1] + ms[m / 2]);
  *min_ms = ms[0];
  return R;
}

// The command-line options both baselines share; false if o is not one of them.
inline bool ParseCommon(const std::string& o, const char* v, Params& p) {
  if (o == "--cells") p.Nc = std::atoi(v);
  else if (o == "--omega") p.omega = std::atof(v);
  else if (o == "--energy") p.Estar = std::atof(v);
  else if (o == "--amplitude") p.S = std::atof(v);
  else if (o == "--t_final") p.t_final = std::atof(v);
  else if (o == "--repeat") p.repeat = std::max(1, std::atoi(v));
  else return false;
  return true;
}

// MCR = sum rms^4 / (sum rms^2)^2 with rms_i^2 = usq_i / T (usq: int u_i^2 dt over the window of length T).
inline double WindowMcr(const double* usq, int N, double T) {
  double s2 = 0.0, s4 = 0.0;
  for (int i = 0; i < N; ++i) { const double r2 = usq[i] / T; s2 += r2; s4 += r2 * r2; }
  return T > 0 ? s4 / (s2 * s2) : NAN;
}
