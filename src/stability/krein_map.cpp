#include "stability/krein_map.hpp"
#include "core/log.hpp"
#include <algorithm>
#include <cmath>
#include <cstdio>

namespace nltopo {

const char *const kKreinPairNames[kKreinPairClasses] = {"AA", "AO", "OO", "EA", "EO", "EE"};

PetscInt SturmCount(const std::vector<PetscReal> &d, const std::vector<PetscReal> &e, PetscReal x)
{
  // LDL^T of T - x I: the pivots' signs count the eigenvalues below x (Sylvester's law of inertia)
  PetscInt neg = 0;
  PetscReal q = 1;
  const PetscReal tiny = 1e-300;
  for (size_t i = 0; i < d.size(); i++) {
    q = d[i] - x - (i > 0 ? e[i - 1] * e[i - 1] / q : 0.0);
    if (q == 0) q = -tiny; // a zero pivot: perturbed (the count is that of x + 0)
    neg += q < 0;
  }
  return neg;
}

std::vector<PetscReal> TridiagonalEigenvaluesIn(const std::vector<PetscReal> &d, const std::vector<PetscReal> &e, PetscReal lo, PetscReal hi)
{
  std::vector<PetscReal> out;
  if (!(hi > lo)) return out;
  const PetscInt c0 = SturmCount(d, e, lo), c1 = SturmCount(d, e, hi);
  for (PetscInt j = c0; j < c1; j++) { // the j-th eigenvalue (0-based): count(x) > j above it
    PetscReal a = lo, b = hi;
    for (int it = 0; it < 200 && b - a > 4 * PETSC_MACHINE_EPSILON * std::max(std::abs(a), std::abs(b)); it++) {
      const PetscReal m = 0.5 * (a + b);
      if (SturmCount(d, e, m) > j) b = m;
      else a = m;
    }
    out.push_back(0.5 * (a + b));
  }
  return out;
}

PetscErrorCode KreinSpectrumSetup(const Lattice &lat, KreinSpectrum *s)
{
  const MPI_Comm comm = lat.Comm();
  const PetscInt N = lat.N(), xs = lat.OwnedStart(), xm = lat.OwnedCount();
  PetscMPIInt size;
  PetscLogEvent event; // "KreinMap" in -log_view: the map's only cost beyond O(1) per orbit
  PetscFunctionBeginUser;
  PetscCall(NamedLogEvent("KreinMap", &event));
  PetscCall(PetscLogEventBegin(event, 0, 0, 0, 0));
  s->bands = InfiniteBandEdges(lat.Params());
  // K on every rank: the diagonal and the bonds (K(i, i+1) = -k_i; the sign does not enter the count)
  PetscCallMPI(MPI_Comm_size(comm, &size));
  std::vector<PetscMPIInt> counts(size), displs(size, 0);
  const PetscMPIInt mine = (PetscMPIInt)xm;
  PetscCallMPI(MPI_Allgather(&mine, 1, MPI_INT, counts.data(), 1, MPI_INT, comm));
  for (PetscMPIInt r = 1; r < size; r++) displs[r] = displs[r - 1] + counts[r - 1];
  std::vector<PetscReal> dl(xm), el(xm), d(N), e(N);
  for (PetscInt k = 0; k < xm; k++) dl[k] = lat.DiagonalSprings()[xs + k], el[k] = lat.BondSprings()[xs + k];
  PetscCallMPI(MPI_Allgatherv(dl.data(), mine, MPIU_REAL, d.data(), counts.data(), displs.data(), MPIU_REAL, comm));
  PetscCallMPI(MPI_Allgatherv(el.data(), mine, MPIU_REAL, e.data(), counts.data(), displs.data(), MPIU_REAL, comm));
  e.resize(std::max<PetscInt>(N - 1, 0));
  // Gershgorin bounds, and the bands (omega^2) widened by 1e-10 relative: a
  // finite lattice's band modes lie strictly inside the infinite lattice's
  // bands, so only the localised ones fall outside
  PetscReal lo = 0, hi = 0;
  for (PetscInt i = 0; i < N; i++) {
    const PetscReal r = (i > 0 ? std::abs(e[i - 1]) : 0) + (i < N - 1 ? std::abs(e[i]) : 0);
    lo = std::min(lo, d[i] - r), hi = std::max(hi, d[i] + r);
  }
  const BandEdges &b = s->bands;
  const PetscReal m = 1e-10;
  const PetscReal cut[4] = {b.acoustic_bottom * b.acoustic_bottom * (1 - m), b.acoustic_top * b.acoustic_top * (1 + m),
                            b.optical_bottom * b.optical_bottom * (1 - m), b.optical_top * b.optical_top * (1 + m)};
  s->localized.clear();
  for (const auto &[l, h] : {std::pair<PetscReal, PetscReal>{lo - 1, cut[0]}, {cut[1], cut[2]}, {cut[3], hi + 1}})
    for (PetscReal lambda : TridiagonalEigenvaluesIn(d, e, l, h))
      if (lambda > 0) s->localized.push_back(std::sqrt(lambda));
  PetscCall(PetscLogEventEnd(event, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

std::vector<PetscReal> BranchEdgeModes(const KreinSpectrum &s, PetscReal omega_lin)
{
  std::vector<PetscReal> e = s.localized;
  auto own = std::min_element(e.begin(), e.end(), [&](PetscReal a, PetscReal b) { return std::abs(a - omega_lin) < std::abs(b - omega_lin); });
  if (own != e.end() && std::abs(*own - omega_lin) <= 1e-6 * omega_lin) e.erase(own);
  return e;
}

PetscReal LargestSum(const BandEdges &b, const std::vector<PetscReal> &edges)
{
  PetscReal top = b.optical_top;
  for (PetscReal x : edges) top = std::max(top, x);
  return 2 * top;
}

PetscInt OpenResonances(const BandEdges &b, const std::vector<PetscReal> &edges, PetscReal sum, PetscReal sum_prev)
{
  auto in = [](PetscReal x, PetscReal l, PetscReal h) { return x >= l && x <= h; };
  const PetscReal a0 = b.acoustic_bottom, a1 = b.acoustic_top, o0 = b.optical_bottom, o1 = b.optical_top;
  PetscInt mask = 0;
  if (in(sum, 2 * a0, 2 * a1)) mask |= kPairAA;
  if (in(sum, a0 + o0, a1 + o1)) mask |= kPairAO;
  if (in(sum, 2 * o0, 2 * o1)) mask |= kPairOO;
  const PetscReal lo = std::min(sum, sum_prev), hi = std::max(sum, sum_prev), r = 1e-12 * hi; // EE: crossed since the previous orbit (or equal to rounding)
  for (size_t i = 0; i < edges.size(); i++) {
    const PetscReal e = edges[i];
    if (in(sum, e + a0, e + a1)) mask |= kPairEA;
    if (in(sum, e + o0, e + o1)) mask |= kPairEO;
    for (size_t j = i; j < edges.size(); j++)
      if (in(e + edges[j], lo - r, hi + r)) mask |= kPairEE;
  }
  return mask;
}

std::vector<PetscInt> EnergyCriterionFlags(const std::vector<PetscReal> &E, const std::vector<PetscReal> &Omega)
{
  const size_t n = E.size();
  std::vector<PetscInt> f(n, 0);
  for (size_t i = 1; i + 1 < n; i++) {
    if ((E[i] - E[i - 1]) * (E[i + 1] - E[i]) < 0) f[i] |= 1;
    if ((Omega[i] - Omega[i - 1]) * (Omega[i + 1] - Omega[i]) < 0) f[i] |= 2;
  }
  return f;
}

std::vector<PetscReal> EnergySlope(const std::vector<PetscReal> &E, const std::vector<PetscReal> &Omega)
{
  const size_t n = E.size();
  std::vector<PetscReal> s(n, NAN);
  if (n < 2) return s;
  for (size_t i = 0; i < n; i++) {
    const size_t a = i ? i - 1 : 0, b = i + 1 < n ? i + 1 : n - 1;
    s[i] = (E[b] - E[a]) / (Omega[b] - Omega[a]); // a central difference of the chord (a non-uniform grid: exact for a quadratic only when uniform)
  }
  return s;
}

KreinMap ComputeKreinMap(const KreinSpectrum &s, PetscReal omega_lin, const std::vector<PetscReal> &E, const std::vector<PetscReal> &period)
{
  KreinMap m;
  const size_t n = E.size();
  m.edges = BranchEdgeModes(s, omega_lin);
  std::vector<PetscReal> Om(n);
  for (size_t i = 0; i < n; i++) Om[i] = 2 * PETSC_PI / period[i];
  const PetscReal top = LargestSum(s.bands, m.edges);
  m.kmax = 1;
  for (PetscReal w : Om) m.kmax = std::max<PetscInt>(m.kmax, (PetscInt)std::floor(top / w));
  m.open.assign(n * m.kmax, 0);
  for (size_t i = 0; i < n; i++)
    for (PetscInt k = 1; k <= m.kmax; k++) m.open[i * m.kmax + k - 1] = OpenResonances(s.bands, m.edges, k * Om[i], k * Om[i ? i - 1 : 0]);
  m.criterion = EnergyCriterionFlags(E, Om);
  m.slope = EnergySlope(E, Om);
  return m;
}

std::string KreinMapSummary(const KreinMap &m, const BandEdges &, const std::vector<PetscReal> &E, const std::vector<PetscReal> &period)
{
  const size_t n = E.size();
  char buf[256];
  std::string out = "Krein map (w_q + w_q' = k Omega; E modes";
  for (PetscReal e : m.edges) std::snprintf(buf, sizeof buf, " %.4f", (double)e), out += buf;
  out += "): ";
  bool any = false;
  for (PetscInt k = 1; k <= m.kmax; k++)
    for (int c = 0; c < kKreinPairClasses; c++) {
      PetscReal lo = INFINITY, hi = -INFINITY;
      size_t cnt = 0;
      for (size_t i = 0; i < n; i++)
        if (m.open[i * m.kmax + k - 1] & (PetscInt(1) << c)) {
          const PetscReal w = 2 * PETSC_PI / period[i];
          lo = std::min(lo, w), hi = std::max(hi, w), cnt++;
        }
      if (!cnt) continue;
      std::snprintf(buf, sizeof buf, "%s%s k=%d at Omega %.5g..%.5g (%zu orbit%s)", any ? "; " : "", kKreinPairNames[c], (int)k, (double)lo, (double)hi, cnt,
                    cnt == 1 ? "" : "s");
      out += buf, any = true;
    }
  if (!any) out += "no resonance open";
  std::string crit, turns;
  size_t nturn = 0;
  for (size_t i = 0; i < n; i++) {
    if (m.criterion[i] & 1) std::snprintf(buf, sizeof buf, "%s%.4g", crit.empty() ? "" : ", ", (double)E[i]), crit += buf;
    if (m.criterion[i] & 2) nturn++;
  }
  out += "; dE/dOmega = 0 (E extremum) ";
  out += crit.empty() ? std::string("nowhere") : "at E = " + crit;
  std::snprintf(buf, sizeof buf, "; Omega turns at %zu orbit(s)", nturn);
  out += buf;
  return out;
}

} // namespace nltopo
