// plain_splitting.cpp -- plain C++17 baseline (no PETSc) for nltopo's symsplit TS
// type: the same splitting schemes (src/timeint/symsplit_schemes.hpp) on the same
// lattice (plain_lattice.hpp), doing per step what nltopo's forced run does: the
// kick-drift loops with the last acceleration reused (FSAL), the energy parts
// (the cut-off test, and the window's nonlinear/linear potential ratio), and the
// trapezoid sums of u^2 (RMS) and of the potential parts over the window. The cut-off is
// taken at the first step end with E >= E* (nltopo locates it inside the step,
// once per run).
//
// Run:  ./plain_splitting --amplitude S --scheme bm6 --dt 0.2 [--cells 25]
//         [--omega 1.7320508] [--energy 1] [--t_final 1000] [--repeat 5]
#include "plain_lattice.hpp"
#include "timeint/symsplit_schemes.hpp"
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

struct Result {
  long steps = 0, accels = 0;
  double t_off = NAN, E_final = NAN, mcr = NAN, nl_ratio = NAN;
};

static Result solve(Lattice& L, const Params& p, const nltopo::symsplit::Scheme& s, std::vector<double>& work) {
  const int N = L.N, stages = (int)s.drift.size();
  Result R;
  L.forcing_on = true;
  double *u = work.data(), *v = u + N, *a = v + N, *usq = a + N;
  std::fill(work.begin(), work.end(), 0.0);
  const long nsteps = (long)std::ceil(p.t_final / p.dt - 1e-9);
  const double h = p.t_final / nsteps;
  double t = 0, t_start = 0, kin, lin, quart, acc_lin = 0, acc_nl = 0;
  L.energy_parts(u, &kin, &lin, &quart);
  L.accel(t, u, a); ++R.accels;
  for (long n = 0; n < nsteps; ++n) {
    const double lin0 = lin, quart0 = quart;
    for (int i = 0; i < N; ++i) usq[i] += 0.5 * h * u[i] * u[i];
    double c = 0;
    for (int k = 0; k < stages; ++k) {
      const double bh = s.kick[k] * h, ch = s.drift[k] * h;
      for (int i = 0; i < N; ++i) { v[i] += bh * a[i]; u[i] += ch * v[i]; }
      c += s.drift[k];
      L.accel(k + 1 == stages ? t + h : t + c * h, u, a); ++R.accels;
    }
    const double bh = s.kick[stages] * h;
    for (int i = 0; i < N; ++i) v[i] += bh * a[i];
    t = (n + 1) * h;
    ++R.steps;
    for (int i = 0; i < N; ++i) usq[i] += 0.5 * h * u[i] * u[i];
    L.energy_parts(u, &kin, &lin, &quart);  // reads u = z[0..N), v = z[N..2N)
    acc_lin += 0.5 * h * (lin + lin0);
    acc_nl += 0.5 * h * (quart + quart0);
    if (L.forcing_on && kin + lin + quart >= p.Estar) {
      L.forcing_on = false; R.t_off = t; t_start = t;
      std::fill(usq, usq + N, 0.0);
      acc_lin = acc_nl = 0;
      L.accel(t, u, a); ++R.accels;
    }
  }
  R.nl_ratio = acc_lin > 0 ? acc_nl / acc_lin : NAN;
  R.E_final = L.energy(u);
  R.mcr = WindowMcr(usq, N, p.t_final - t_start);
  return R;
}

int main(int argc, char** argv) {
  Params p;
  std::string scheme = "verlet";
  for (int i = 1; i < argc; ++i) {
    std::string o = argv[i];
    if (i + 1 >= argc) { std::fprintf(stderr, "missing value for %s\n", o.c_str()); return 1; }
    const char* val = argv[++i];
    if (ParseCommon(o, val, p)) continue;
    if (o == "--dt") p.dt = std::atof(val);
    else if (o == "--scheme") scheme = val;
    else { std::fprintf(stderr, "unknown option %s\n", o.c_str()); return 1; }
  }
  if (std::isnan(p.S)) { std::fprintf(stderr, "--amplitude S is required\n"); return 1; }
  const nltopo::symsplit::Scheme* s = nullptr;
  for (const auto& x : nltopo::symsplit::Schemes()) if (scheme == x.name) s = &x;
  if (!s) { std::fprintf(stderr, "unknown --scheme %s\n", scheme.c_str()); return 1; }
  Lattice L(p);
  std::vector<double> work(4 * L.N);
  double med, min_ms;
  const Result R = TimeRepeats(p.repeat, [&] { return solve(L, p, *s, work); }, &med, &min_ms);
  std::printf("N=%d S=%.6g scheme=%s steps=%ld rhs_evals=%ld cutoff=%s t_off=%.10g energy_final=%.12g mcr=%.10g nl_ratio=%.8g median_ms=%.3f "
              "us_per_step=%.4f\n",
              L.N, p.S, s->name, R.steps, R.accels, std::isnan(R.t_off) ? "no" : "yes", R.t_off, R.E_final, R.mcr, R.nl_ratio, med,
              1e3 * med / R.steps);
  return 0;
}
