// plain_rkn.cpp -- plain C++17 baseline (no PETSc) for nltopo's rkn TS type:
// the same embedded Runge-Kutta-Nystrom pairs (src/timeint/rkn_schemes.hpp) on
// the same lattice (plain_lattice.hpp) and forced run, with the step-size
// controller of nltopo's rkn + TSAdapt basic (PETSc 3.18) written out:
//
//   enorm = sqrt(mean over u and v of (d_i / (atol + rtol max(|y_i|, |yhat_i|)))^2)
//           (TSErrorWeightedNorm, 2-norm; d = propagated - embedded),
//   accepted if enorm <= 1; h_next = h clip(safety enorm^(-1/(q+1)), 0.1, 10)
//   with q the embedded order, safety 0.9 (x 0.5 when the previous attempt of
//   the same step was rejected and this one is too); after an accepted step the
//   next step is stretched or halved to land on t_final (MATCHSTEP,
//   TSAdaptChoose's rule).
//
// Per step it does what nltopo's forced run needs for its outputs:
//  - the stages (positions only) and the four weighted sums (u1, v1 and the
//    differences to the embedded pair) in contiguous passes, the error norm;
//  - while the forcing is on: E at the step end (the cut-off test) and E on the
//    step's quintic Hermite interpolant every (pi / omega) / 8 inside the step
//    (nltopo's inner scan: a long step can hold a whole excursion above E*);
//  - the cut-off: a crossing at the step end (E >= E* there) is located by
//    regula falsi on true steps retaken from the step start, to a relative
//    1e-10 in E, from a first guess by bisection on the interpolant (nltopo's
//    TS event also retakes the step); a crossing inside the step (ends below
//    E*) is located on the interpolant by bisection and the run restarts from
//    the interpolated state (as nltopo does);
//  - E(t) samples every --sample_dt on the interpolant (nltopo's /simulate/energy);
//  - after the cut-off: the window integrals (u_i^2 for the RMS, the linear
//    and quartic potential for nl_ratio) by 3-point Gauss-Legendre on each
//    step's interpolant (nltopo's rule for rkn).
// What it leaves out, and nltopo does: the energy at every step end after the
// cut-off, the kinetic part and v at the Gauss nodes, the trapezoid values it
// keeps as a fallback.
//
// Run:  ./plain_rkn --amplitude S [--scheme dep86] [--rtol 1e-8] [--atol 1e-8]
//         [--dt 0.2 (first step)] [--sample_dt 1] [--cells 25]
//         [--omega 1.7320508] [--energy 1] [--t_final 1000] [--repeat 5]
#include "plain_lattice.hpp"
#include "timeint/rkn_schemes.hpp"
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <utility>
#include <vector>

using nltopo::rkn::Pair;

struct Result {
  long steps = 0, rejected = 0, accels = 0, samples = 0;
  double t_off = NAN, E_final = NAN, mcr = NAN, nl_ratio = NAN, E_sum = 0;
};

// Everything the solve touches, allocated once outside the timed part.
struct Work {
  int N, s;
  std::vector<double> z, z1, zi, y, usq, bsum, E;  // state [u|v], next state, interpolated state, stage, window, weighted sums
  std::vector<std::vector<double>> k;              // stage accelerations; k[s] = end acceleration (pairs without FSAL)
  std::vector<std::vector<std::pair<int, double>>> rows;  // nonzero A_ij of each stage row
  std::vector<double> dbar, db;                    // bbar - bhatbar, b - bhat
  Work(int n, const Pair& P)
      : N(n), s(P.stages), z(2 * n), z1(2 * n), zi(2 * n), y(n), usq(n), bsum(4 * n), k(P.stages + 1, std::vector<double>(n)),
        rows(P.stages), dbar(P.stages), db(P.stages) {
    for (int i = 0; i < s; ++i) {
      for (int j = 0; j < i; ++j)
        if (P.A[i * s + j] != 0) rows[i].push_back({j, P.A[i * s + j]});
      dbar[i] = P.bbar[i] - P.bhatbar[i];
      db[i] = P.b[i] - P.bhat[i];
    }
  }
};

// The quintic Hermite interpolant at t0 + s h from (u, v, a) at both ends; x = [u|v]
// (u only if !with_v).
static void Hermite(const double* z0, const double* z1, const double* a0, const double* a1, int N, double h, double s, double* x, bool with_v) {
  const double s2 = s * s, s3 = s2 * s, s4 = s3 * s, s5 = s4 * s;
  const double H0 = 1 - 10 * s3 + 15 * s4 - 6 * s5, H1 = h * (s - 6 * s3 + 8 * s4 - 3 * s5), H2 = h * h * 0.5 * (s2 - 3 * s3 + 3 * s4 - s5);
  const double H3 = 10 * s3 - 15 * s4 + 6 * s5, H4 = h * (-4 * s3 + 7 * s4 - 3 * s5), H5 = h * h * 0.5 * (s3 - 2 * s4 + s5);
  const double *u0 = z0, *v0 = z0 + N, *u1 = z1, *v1 = z1 + N;
  for (int i = 0; i < N; ++i) x[i] = H0 * u0[i] + H3 * u1[i] + H1 * v0[i] + H4 * v1[i] + H2 * a0[i] + H5 * a1[i];
  if (!with_v) return;
  const double D0 = (-30 * s2 + 60 * s3 - 30 * s4) / h, D1 = 1 - 18 * s2 + 32 * s3 - 15 * s4, D2 = h * 0.5 * (2 * s - 9 * s2 + 12 * s3 - 5 * s4);
  const double D4 = -12 * s2 + 28 * s3 - 15 * s4, D5 = h * 0.5 * (3 * s2 - 8 * s3 + 5 * s4);
  for (int i = 0; i < N; ++i) x[N + i] = D0 * (u0[i] - u1[i]) + D1 * v0[i] + D4 * v1[i] + D2 * a0[i] + D5 * a1[i];
}

// The linear and quartic potential of the displacements u.
static void Potential(const Lattice& L, const double* u, double* lin, double* quart) {
  double l = 0.0, q = 0.0;
  for (int i = 0; i < L.N; ++i) l += 0.5 * L.khat * u[i] * u[i];
  for (int b = 0; b < L.N - 1; ++b) {
    const double d = u[b] - u[b + 1];
    l -= L.kb[b] * u[b] * u[b + 1];
    q += 0.25 * L.gb[b] * d * d * d * d;
  }
  *lin = l; *quart = q;
}

// One attempt from (t, z) with step h: z1 <- (u1, v1); returns the weighted error norm.
// k[0] holds a(t, u) on entry.
static double Attempt(Lattice& L, const Pair& P, Work& W, const Params& p, double t, double h, Result& R) {
  const int N = W.N, s = W.s;
  const double h2 = h * h;
  const double *u = W.z.data(), *v = u + N;
  double* y = W.y.data();
  for (int i = 1; i < s; ++i) {
    const double ch = P.c[i] * h;
    for (int q = 0; q < N; ++q) y[q] = u[q] + ch * v[q];
    for (const auto& jw : W.rows[i]) {
      const double w = h2 * jw.second;
      const double* kj = W.k[jw.first].data();
      for (int q = 0; q < N; ++q) y[q] += w * kj[q];
    }
    L.accel(t + ch, y, W.k[i].data());
    ++R.accels;
  }
  double *su = W.bsum.data(), *sv = su + N, *eu = sv + N, *ev = eu + N;
  std::fill(W.bsum.begin(), W.bsum.end(), 0.0);
  for (int i = 0; i < s; ++i) {
    const double wb = P.bbar[i], wv = P.b[i], xb = W.dbar[i], xv = W.db[i];
    const double* a = W.k[i].data();
    for (int q = 0; q < N; ++q) {
      su[q] += wb * a[q];
      sv[q] += wv * a[q];
      eu[q] += xb * a[q];
      ev[q] += xv * a[q];
    }
  }
  double* u1 = W.z1.data();
  double* v1 = u1 + N;
  double sum = 0.0;
  const double rtol = p.rtol, atol = p.atol;
  for (int q = 0; q < N; ++q) {
    const double un = u[q] + h * v[q] + h2 * su[q], vn = v[q] + h * sv[q];
    const double ue = un - h2 * eu[q], ve = vn - h * ev[q];  // the embedded solution
    const double du = std::fabs(ue - un) / (atol + rtol * std::max(std::fabs(un), std::fabs(ue)));
    const double dv = std::fabs(ve - vn) / (atol + rtol * std::max(std::fabs(vn), std::fabs(ve)));
    sum += du * du + dv * dv;
    u1[q] = un;
    v1[q] = vn;
  }
  return std::sqrt(sum / (2 * N));
}

static Result solve(Lattice& L, const Params& p, const Pair& P, double sample_dt, Work& W) {
  const int N = L.N, s = P.stages;
  const double tf = p.t_final, safety = 0.9, reject_safety = 0.5, clip_lo = 0.1, clip_hi = 10.0;
  const double expo = -1.0 / (P.order_embedded + 1);
  const double spacing = M_PI / (8 * L.w);  // the inner scan's spacing while the forcing is on
  Result R;
  L.forcing_on = true;
  std::fill(W.z.begin(), W.z.end(), 0.0);
  std::fill(W.usq.begin(), W.usq.end(), 0.0);
  W.E.clear();
  double* a0 = W.k[0].data();
  double t = 0.0, h = std::min(p.dt, tf), acc_lin = 0, acc_nl = 0, t_start = 0;
  double E_start = 0;  // E at t (while the forcing is on)
  bool window = false;
  long next_sample = 0;
  L.accel(t, W.z.data(), a0); ++R.accels;
  // E samples at k sample_dt up to t_hi, on the interpolant of the step [t_lo, t_lo + hs]
  // (z -> z1, a0 -> a1); hs = 0: the initial state.
  auto samples = [&](double tlo, double hs, double thi, const double* a1) {
    if (sample_dt <= 0) return;
    for (;;) {
      const double tk = next_sample * sample_dt;
      if (tk > tf * (1 + 1e-12) || tk > thi + 1e-9 * sample_dt) break;
      double kin, lin, quart;
      if (hs == 0) L.energy_parts(W.z.data(), &kin, &lin, &quart);
      else if (std::fabs(tk - (tlo + hs)) <= 1e-12 * (1 + tk)) L.energy_parts(W.z1.data(), &kin, &lin, &quart);
      else {
        Hermite(W.z.data(), W.z1.data(), W.k[0].data(), a1, N, hs, (tk - tlo) / hs, W.zi.data(), true);
        L.energy_parts(W.zi.data(), &kin, &lin, &quart);
      }
      W.E.push_back(kin + lin + quart);
      ++next_sample;
    }
  };
  samples(0, 0, 0, nullptr);
  const int iend = P.fsal ? s - 1 : s;  // k[iend]: a(t + h, u1)
  while (t < tf) {
    bool prev_rejected = false;
    double err;
    for (;;) {  // attempts of one step
      err = Attempt(L, P, W, p, t, h, R);
      if (!(err <= 1.0)) {
        const double sf = prev_rejected ? safety * reject_safety : safety;
        const double fac = err > 0 ? sf * std::pow(err, expo) : clip_hi;
        h *= std::min(clip_hi, std::max(clip_lo, fac));
        if (!(h > 1e-14 * std::max(1.0, t))) { std::fprintf(stderr, "step size underflow at t=%g\n", t); std::exit(2); }
        ++R.rejected;
        prev_rejected = true;
        continue;
      }
      break;
    }
    // the next step (TSAdapt basic, then MATCHSTEP)
    double hn = h * std::min(clip_hi, std::max(clip_lo, err > 0 ? safety * std::pow(err, expo) : clip_hi));
    {
      const double te = t + h, hmax = tf - te;
      if (te < tf && te + hn > tf) hn = hmax;
      if (te < tf && te + hn < tf && hn * 2.0 > hmax) hn = hmax / 2;
      if (te < tf && te + hn < tf && hn * 1.01 > hmax) hn = hmax;
    }
    if (!P.fsal) { L.accel(t + h, W.z1.data(), W.k[s].data()); ++R.accels; }
    double* a1 = W.k[iend].data();
    double tn = t + h;
    ++R.steps;
    if (L.forcing_on) {
      double kin, lin, quart, t_off = NAN, lo = t, hi = NAN;
      L.energy_parts(W.z1.data(), &kin, &lin, &quart);
      const double E_end = kin + lin + quart;
      const bool at_end = E_end >= p.Estar;
      // inner scan: E on the interpolant inside the step (nltopo: its post-step; a crossing at the
      // step end is found first, by its TS event, which retakes the step)
      const int kk = at_end ? 0 : (int)std::floor(h / spacing);
      for (int i = 1; i <= kk; ++i) {
        const double ti = t + i * h / (kk + 1);
        Hermite(W.z.data(), W.z1.data(), a0, a1, N, h, (ti - t) / h, W.zi.data(), true);
        L.energy_parts(W.zi.data(), &kin, &lin, &quart);
        if (kin + lin + quart >= p.Estar) { hi = ti; break; }
        lo = ti;
      }
      const bool inside = !std::isnan(hi);
      if (inside || at_end) {
        if (!inside) hi = tn;
        for (int it = 0; it < 200 && hi - lo > 1e-14 * (1 + hi); ++it) {  // bisection on the interpolant
          const double mid = 0.5 * (lo + hi);
          Hermite(W.z.data(), W.z1.data(), a0, a1, N, h, (mid - t) / h, W.zi.data(), true);
          L.energy_parts(W.zi.data(), &kin, &lin, &quart);
          const double g = (kin + lin + quart) / p.Estar - 1;
          if (std::fabs(g) <= 1e-10) { lo = hi = mid; break; }
          (g < 0 ? lo : hi) = mid;
        }
        t_off = hi;
        if (inside) {  // restart from the interpolated state
          samples(t, h, t_off, a1);  // before the crossing: this step's interpolant
          Hermite(W.z.data(), W.z1.data(), a0, a1, N, h, (t_off - t) / h, W.zi.data(), true);
          std::copy(W.zi.begin(), W.zi.end(), W.z1.begin());
        } else {  // retake the step to t_off (forcing on): regula falsi (Illinois) on true steps from the interpolant's t_off
          double ta = 0, ga = E_start / p.Estar - 1, tb = h, gb = E_end / p.Estar - 1, tau = t_off - t;
          int side = 0;
          for (int it = 0; it < 50; ++it) {
            Attempt(L, P, W, p, t, tau, R);
            const double g = L.energy(W.z1.data()) / p.Estar - 1;
            if (std::fabs(g) <= 1e-10 || tb - ta <= 1e-14 * (1 + t)) break;
            if (g < 0) { ta = tau; ga = g; if (side == -1) gb *= 0.5; side = -1; }
            else { tb = tau; gb = g; if (side == 1) ga *= 0.5; side = 1; }
            tau = (ta * gb - tb * ga) / (gb - ga);
          }
          t_off = t + tau;
          if (!P.fsal) { L.accel(t_off, W.z1.data(), W.k[s].data()); ++R.accels; }
          samples(t, t_off - t, t_off, a1);
          hn = tn - t_off > 1e-10 ? tn - t_off : hn;  // PETSc's event: the rest of the original step
        }
        tn = t_off;
        L.forcing_on = false;
        R.t_off = t_off;
        t_start = t_off;
        window = true;
        std::swap(W.z, W.z1);
        L.accel(tn, W.z.data(), a0); ++R.accels;  // the step start without the forcing
        t = tn;
        h = hn;
        continue;
      }
      E_start = E_end;
    }
    samples(t, h, tn, a1);
    if (window) {  // 3-point Gauss-Legendre on the interpolant
      static const double x = std::sqrt(15.0) / 10, node[3] = {0.5 - x, 0.5, 0.5 + x}, wq[3] = {5.0 / 18, 8.0 / 18, 5.0 / 18};
      double* ui = W.zi.data();
      double* usq = W.usq.data();
      for (int q = 0; q < 3; ++q) {
        double lin, quart;
        Hermite(W.z.data(), W.z1.data(), a0, a1, N, h, node[q], ui, false);
        Potential(L, ui, &lin, &quart);
        const double w = wq[q] * h;
        for (int i = 0; i < N; ++i) usq[i] += w * ui[i] * ui[i];
        acc_lin += w * lin;
        acc_nl += w * quart;
      }
    }
    std::swap(W.z, W.z1);
    std::swap(W.k[0], W.k[iend]);  // FSAL / the end acceleration is the next step's first
    a0 = W.k[0].data();
    t = tn;
    h = hn;
  }
  R.nl_ratio = acc_lin > 0 ? acc_nl / acc_lin : NAN;
  R.E_final = L.energy(W.z.data());
  R.mcr = WindowMcr(W.usq.data(), N, tf - t_start);
  R.samples = (long)W.E.size();
  for (double e : W.E) R.E_sum += e;
  return R;
}

int main(int argc, char** argv) {
  Params p;
  p.dt = 0.2;  // the first step (options/simulate.opts' -sim_ts_dt)
  double sample_dt = 1.0;
  std::string scheme = "dep64";
  for (int i = 1; i < argc; ++i) {
    std::string o = argv[i];
    if (i + 1 >= argc) { std::fprintf(stderr, "missing value for %s\n", o.c_str()); return 1; }
    const char* val = argv[++i];
    if (ParseCommon(o, val, p)) continue;
    if (o == "--dt") p.dt = std::atof(val);
    else if (o == "--rtol") p.rtol = std::atof(val);
    else if (o == "--atol") p.atol = std::atof(val);
    else if (o == "--sample_dt") sample_dt = std::atof(val);
    else if (o == "--scheme") scheme = val;
    else { std::fprintf(stderr, "unknown option %s\n", o.c_str()); return 1; }
  }
  if (std::isnan(p.S)) { std::fprintf(stderr, "--amplitude S is required\n"); return 1; }
  const Pair* P = nullptr;
  for (const auto& x : nltopo::rkn::Pairs()) if (scheme == x.name) P = &x;
  if (!P) { std::fprintf(stderr, "unknown --scheme %s (dep64, dep86, dep1210)\n", scheme.c_str()); return 1; }
  Lattice L(p);
  Work W(L.N, *P);
  W.E.reserve(sample_dt > 0 ? (size_t)(p.t_final / sample_dt) + 2 : 0);
  double med, min_ms;
  const Result R = TimeRepeats(p.repeat, [&] { return solve(L, p, *P, sample_dt, W); }, &med, &min_ms);
  std::printf("N=%d S=%.6g scheme=%s rtol=%.3g atol=%.3g steps=%ld rejected=%ld rhs_evals=%ld cutoff=%s t_off=%.10g energy_final=%.12g mcr=%.10g "
              "nl_ratio=%.8g samples=%ld median_ms=%.3f us_per_step=%.4f\n",
              L.N, p.S, P->name, p.rtol, p.atol, R.steps, R.rejected, R.accels, std::isnan(R.t_off) ? "no" : "yes", R.t_off, R.E_final, R.mcr,
              R.nl_ratio, R.samples, med, 1e3 * med / R.steps);
  return 0;
}
