#pragma once
// The coefficients of the symsplit schemes (timeint/ts_symsplit.hpp), free of
// PETSc so that the plain C++ baseline (benchmarks/plain_splitting.cpp) runs
// exactly the same methods.
#include <cmath>
#include <vector>

namespace nltopo {
namespace symsplit {

// A symmetric kick-drift-kick method: K(kick[0]) D(drift[0]) K(kick[1]) ...
// D(drift[s-1]) K(kick[s]), where K(b): v += b h a(t, u) and D(c): u += c h v,
// t += c h. Consistency: sum(kick) = sum(drift) = 1.
struct Scheme {
  const char *name, *source;
  int order;
  std::vector<double> kick, drift;
};

// A composition of Stormer-Verlet steps of lengths w_i h (kick-drift-kick),
// adjacent half kicks merged.
inline Scheme Composition(const char *name, const char *source, int order, const std::vector<double> &w)
{
  Scheme s{name, source, order, {}, {}};
  s.kick.push_back(0.5 * w.front());
  for (size_t i = 0; i < w.size(); i++) {
    s.drift.push_back(w[i]);
    s.kick.push_back(0.5 * (w[i] + (i + 1 < w.size() ? w[i + 1] : 0.0)));
  }
  return s;
}

// A symmetric composition w_m ... w_1 w_0 w_1 ... w_m from its half (w_1..w_m;
// w_0 = 1 - 2 sum).
inline std::vector<double> Symmetric(const std::vector<double> &half)
{
  double sum = 0;
  for (double x : half) sum += x;
  std::vector<double> w(half.rbegin(), half.rend());
  w.push_back(1 - 2 * sum);
  w.insert(w.end(), half.begin(), half.end());
  return w;
}

inline const std::vector<Scheme> &Schemes()
{
  static const std::vector<Scheme> list = [] {
    std::vector<Scheme> l;
    l.push_back(Composition("verlet", "Stormer-Verlet (velocity Verlet, kick-drift-kick)", 2, {1.0}));
    const double cr = std::cbrt(2.0), y1 = 1 / (2 - cr), y0 = -cr / (2 - cr);
    l.push_back(Composition("yoshida4", "Yoshida (1990), Phys. Lett. A 150:262, triple jump of Verlet", 4, {y1, y0, y1}));
    // Yoshida (1990), Table 1, solution A (order 6) and solution D (order 8): w_1..w_m
    l.push_back(Composition("yoshida6", "Yoshida (1990), Phys. Lett. A 150:262, Table 1, solution A", 6,
                            Symmetric({-1.17767998417887, 0.235573213359357, 0.784513610477560})));
    l.push_back(Composition(
        "yoshida8", "Yoshida (1990), Phys. Lett. A 150:262, Table 2, solution D", 8,
        Symmetric({0.102799849391985, -1.96061023297549, 1.93813913762276, -0.158240635368243, -1.44485223686048, 0.253693336566229, 0.914844246229740})));
    // Blanes & Moan (2002), J. Comput. Appl. Math. 142:313-330, Table 3: the
    // optimised RKN splittings SRKN_6^b (order 4) and SRKN_11^b (order 6), kick first
    // (digits as carried by mockingbirdnest/Principia, integrators/methods.hpp)
    l.push_back({"bm4",
                 "Blanes & Moan (2002), J. Comput. Appl. Math. 142:313, Table 3, SRKN_6^b",
                 4,
                 {0.0829844064174052, 0.396309801498368, -0.0390563049223486, 0.1195241940131508, -0.0390563049223486, 0.396309801498368, 0.0829844064174052},
                 {0.245298957184271, 0.60487266571108, -0.350171622895351, -0.350171622895351, 0.60487266571108, 0.245298957184271}});
    l.push_back({"bm6",
                 "Blanes & Moan (2002), J. Comput. Appl. Math. 142:313, Table 3, SRKN_11^b",
                 6,
                 {0.0414649985182624, 0.198128671918067, -0.0400061921041533, 0.0752539843015807, -0.0115113874206879, 0.2366699247869311, 0.2366699247869311,
                  -0.0115113874206879, 0.0752539843015807, -0.0400061921041533, 0.198128671918067, 0.0414649985182624},
                 {0.123229775946271, 0.290553797799558, -0.127049212625417, -0.246331761062075, 0.357208872795928, 0.20477705429147, 0.357208872795928,
                  -0.246331761062075, -0.127049212625417, 0.290553797799558, 0.123229775946271}});
    // McLachlan (1995), SIAM J. Sci. Comput. 16:151-168, SS15: a 15-stage symmetric
    // composition of Verlet of order 8 (26 digits as carried by SciML/OrdinaryDiffEq.jl, McAte8)
    l.push_back(Composition("ss8", "McLachlan (1995), SIAM J. Sci. Comput. 16:151, SS15", 8,
                            {0.7416703643506129534482278, -0.4091008258000315939973001, 0.19075471029623837995387626, -0.57386247111608226665638773,
                             0.29906418130365592384446354, 0.33462491824529818378495798, 0.31529309239676659663205666, -0.79688793935291635401978884,
                             0.31529309239676659663205666, 0.33462491824529818378495798, 0.29906418130365592384446354, -0.57386247111608226665638773,
                             0.19075471029623837995387626, -0.4091008258000315939973001, 0.7416703643506129534482278}));
    return l;
  }();
  return list;
}

} // namespace symsplit
} // namespace nltopo
