#include "stability/bifurcations.hpp"
#include "core/option_table.hpp"
#include <algorithm>
#include <cmath>
#include <complex>
#include <numeric>

namespace nltopo {

const char *EventKindName(EventKind k)
{
  switch (k) {
  case EventKind::Fold: return "energy fold";
  case EventKind::BranchPoint: return "branch point (+1)";
  case EventKind::PeriodDoubling: return "period doubling (-1)";
  case EventKind::KreinCollision: return "Krein collision (equal signatures, pass)";
  case EventKind::HamiltonianHopf: return "Hamiltonian-Hopf (opposite signatures)";
  case EventKind::Resonance: return "internal resonance";
  }
  return "?";
}

std::vector<PetscInt> NontrivialIndices(const PetscReal *re, const PetscReal *im, PetscInt n)
{
  using C = std::complex<PetscReal>;
  if (n < 2) return {};
  std::vector<PetscReal> d(n);
  for (PetscInt j = 0; j < n; j++) {
    const C mu(re[j], im[j]);
    d[j] = std::abs(mu) > 0 ? std::abs(0.5 * (mu + 1.0 / mu) - 1.0) : 1e300;
    if (!std::isfinite(d[j])) d[j] = 1e300;
  }
  std::vector<PetscInt> idx(n);
  std::iota(idx.begin(), idx.end(), 0);
  std::partial_sort(idx.begin(), idx.begin() + 2, idx.end(), [&](PetscInt a, PetscInt b) { return d[a] < d[b]; });
  idx.erase(idx.begin(), idx.begin() + 2);
  std::sort(idx.begin(), idx.end());
  return idx;
}

std::vector<Outside> OutsideMultipliers(const FloquetResult &r, PetscReal tol, PetscReal min_edge)
{
  std::vector<Outside> out;
  const bool filter = min_edge > 0 && r.edge.size() == r.re.size();
  for (PetscInt j : NontrivialIndices(r.re.data(), r.im.data(), (PetscInt)r.re.size())) {
    const PetscReal m = std::hypot(r.re[j], r.im[j]);
    if (!(m > 1 + tol)) continue; // NaN: not counted
    if (filter && r.edge[j] < min_edge) continue;
    if (std::abs(r.im[j]) <= tol * m) out.push_back({r.re[j] > 0 ? EventKind::BranchPoint : EventKind::PeriodDoubling, r.re[j] > 0 ? 0 : PETSC_PI, m, j});
    else if (r.im[j] > 0) out.push_back({EventKind::HamiltonianHopf, std::atan2(r.im[j], r.re[j]), m, j});
  }
  std::sort(out.begin(), out.end(), [](const Outside &x, const Outside &y) { return x.kind != y.kind ? x.kind < y.kind : x.angle < y.angle; });
  return out;
}

std::vector<std::pair<Outside, PetscInt>> OutsideChanges(const std::vector<Outside> &a, const std::vector<Outside> &b, PetscReal angle_tol)
{
  // greedy matching, closest pairs first (in angle and log-modulus)
  std::vector<std::pair<PetscReal, std::pair<size_t, size_t>>> cand;
  for (size_t i = 0; i < a.size(); i++)
    for (size_t j = 0; j < b.size(); j++)
      if (a[i].kind == b[j].kind && std::abs(a[i].angle - b[j].angle) <= angle_tol) // near in angle; real ones (all at 0 or pi) by modulus
        cand.push_back({std::abs(a[i].angle - b[j].angle) + std::abs(std::log(a[i].modulus / b[j].modulus)), {i, j}});
  std::sort(cand.begin(), cand.end());
  std::vector<char> ua(a.size(), 0), ub(b.size(), 0);
  for (const auto &c : cand)
    if (!ua[c.second.first] && !ub[c.second.second]) ua[c.second.first] = ub[c.second.second] = 1;
  std::vector<std::pair<Outside, PetscInt>> ch;
  for (size_t j = 0; j < b.size(); j++)
    if (!ub[j]) ch.push_back({b[j], 1});
  for (size_t i = 0; i < a.size(); i++)
    if (!ua[i]) ch.push_back({a[i], -1});
  return ch;
}

bool SameOutside(const std::vector<Outside> &a, const std::vector<Outside> &b, PetscReal angle_tol)
{
  return a.size() == b.size() && OutsideChanges(a, b, angle_tol).empty();
}

namespace {

// The nontrivial multipliers on the circle (||mu| - 1| <= tol; not the inside partners of unstable ones): index and angle in (-pi, pi].
std::vector<std::pair<PetscInt, PetscReal>> OnCircle(const FloquetResult &r, PetscReal tol, PetscReal min_edge)
{
  std::vector<std::pair<PetscInt, PetscReal>> c;
  const bool filter = min_edge > 0 && r.edge.size() == r.re.size();
  for (PetscInt j : NontrivialIndices(r.re.data(), r.im.data(), (PetscInt)r.re.size()))
    if (std::abs(std::hypot(r.re[j], r.im[j]) - 1) <= tol && !(filter && r.edge[j] < min_edge)) c.push_back({j, std::atan2(r.im[j], r.re[j])});
  return c;
}

// The two circle multipliers that collide at e^{i angle}: for a collision in
// the upper half plane the two nearest to it there; at +1 or -1 the pair
// (upper member first) nearest to it, among those with an edge share of at
// least min_edge (the pair keeps its eigenvector through +-1; a collision in
// the upper half plane may be with a bulk pair). Fewer than 2: none.
std::vector<std::pair<PetscInt, PetscReal>> Colliding(const FloquetResult &r, EventKind kind, PetscReal angle, PetscReal tol, PetscReal min_edge)
{
  std::vector<std::pair<PetscInt, PetscReal>> c = OnCircle(r, tol, kind == EventKind::HamiltonianHopf ? 0 : min_edge), pick;
  auto dist = [&](PetscReal th) {
    if (kind == EventKind::HamiltonianHopf) return std::abs(th - angle);
    if (kind == EventKind::BranchPoint) return std::abs(th);
    return PETSC_PI - std::abs(th); // period doubling: distance from pi
  };
  if (kind == EventKind::HamiltonianHopf) c.erase(std::remove_if(c.begin(), c.end(), [](const auto &x) { return x.second < 0; }), c.end());
  std::sort(c.begin(), c.end(), [&](const auto &x, const auto &y) { return dist(x.second) < dist(y.second); });
  if (c.size() < 2) return {};
  pick = {c[0], c[1]};
  if (kind != EventKind::HamiltonianHopf && pick[0].second < pick[1].second) std::swap(pick[0], pick[1]); // upper member first
  return pick;
}

} // namespace

PetscReal CollisionFunction(const FloquetResult &r, EventKind kind, PetscReal angle, PetscReal tol, PetscReal angle_tol, PetscReal min_edge)
{
  // off the circle: the matching outside multiplier
  const Outside *best = nullptr;
  const std::vector<Outside> out = OutsideMultipliers(r, tol, min_edge);
  for (const Outside &o : out)
    if (o.kind == kind && std::abs(o.angle - angle) <= angle_tol &&
        (!best || std::abs(o.angle - angle) < std::abs(best->angle - angle) || (o.angle == best->angle && o.modulus < best->modulus)))
      best = &o; // (real ones tie in angle: the one nearest the circle, the newest)
  if (best) return -std::pow(2 * std::log(best->modulus), 2);
  const auto c = Colliding(r, kind, angle, tol, min_edge);
  if (c.empty()) return NAN;
  PetscReal d = std::abs(c[0].second - c[1].second);
  d = std::min(d, 2 * PETSC_PI - d); // the pair near -1 at +-(pi - delta): 2 delta
  return d * d;
}

void CollidingSignatures(const FloquetResult &r, EventKind kind, PetscReal angle, PetscReal tol, PetscInt krein[2], PetscReal min_edge)
{
  krein[0] = krein[1] = 0;
  const auto c = Colliding(r, kind, angle, tol, min_edge);
  if (c.empty() || r.kappa.size() != r.re.size()) return;
  for (int k = 0; k < 2; k++) {
    const PetscReal v = r.kappa[c[k].first];
    krein[k] = v > 0 ? 1 : (v < 0 ? -1 : 0);
  }
}

std::vector<std::pair<PetscInt, PetscReal>> UpperCircle(const FloquetResult &r, PetscReal tol, PetscReal min_edge)
{
  std::vector<std::pair<PetscInt, PetscReal>> c = OnCircle(r, tol, min_edge);
  c.erase(std::remove_if(c.begin(), c.end(), [&](const auto &x) { return !(r.im[x.first] > 0) || x.second >= PETSC_PI; }), c.end());
  std::sort(c.begin(), c.end(), [](const auto &x, const auto &y) { return x.second < y.second; });
  return c;
}

std::vector<std::pair<PetscReal, PetscReal>> PassCandidates(const FloquetResult &a, const FloquetResult &c, PetscReal tol, PetscReal min_edge)
{
  const auto la = UpperCircle(a, tol, min_edge), lc = UpperCircle(c, tol, min_edge);
  std::vector<std::pair<PetscReal, PetscReal>> cand;
  if (la.size() != lc.size() || la.size() < 2) return cand; // a pair joined or left the circle: the outside set changed there
  PetscReal move = 0;                                       // the largest move of a member (in order of angle, which a pass leaves as it is)
  for (size_t k = 0; k < la.size(); k++) move = std::max(move, std::abs(lc[k].second - la[k].second));
  const bool signs = a.krein.size() == a.re.size();
  for (size_t k = 0; k + 1 < la.size(); k++) {
    if (signs && (a.krein[la[k].first] == 0 || a.krein[la[k].first] != a.krein[la[k + 1].first])) continue;
    if (la[k + 1].second - la[k].second <= 2 * move && lc[k + 1].second - lc[k].second <= 2 * move) cand.push_back({la[k].second, la[k + 1].second});
  }
  return cand;
}

namespace {

// |ref.vectors[i]^H x.vectors[j]| for every j (-1 where x has none; both of unit norm).
std::vector<PetscReal> Overlaps(const FloquetResult &ref, PetscInt i, const FloquetResult &x)
{
  std::vector<PetscReal> o(x.vectors.size(), -1);
  const auto &p = ref.vectors[i];
  for (size_t j = 0; j < x.vectors.size(); j++) {
    const auto &q = x.vectors[j];
    if (q.size() != p.size()) continue;
    std::complex<PetscReal> d = 0;
    for (size_t k = 0; k < p.size(); k++) d += std::conj(p[k]) * q[k];
    o[j] = std::abs(d);
  }
  return o;
}

bool HasVector(const FloquetResult &r, PetscInt i) { return i >= 0 && (size_t)i < r.vectors.size() && !r.vectors[i].empty(); }

} // namespace

PetscReal TrackMember(const FloquetResult &ref, PetscInt i, const FloquetResult &x, PetscInt *j)
{
  *j = -1;
  if (!HasVector(ref, i)) return 0;
  const std::vector<PetscReal> o = Overlaps(ref, i, x);
  PetscReal best = 0;
  for (size_t k = 0; k < o.size(); k++)
    if (o[k] > best) best = o[k], *j = (PetscInt)k;
  return best;
}

PetscReal TrackPair(const FloquetResult &ref, PetscInt ia, PetscInt ib, const FloquetResult &x, PetscInt *ja, PetscInt *jb)
{
  *ja = *jb = -1;
  if (!HasVector(ref, ia) || !HasVector(ref, ib)) return 0;
  const std::vector<PetscReal> oa = Overlaps(ref, ia, x), ob = Overlaps(ref, ib, x);
  const PetscInt n = (PetscInt)oa.size();
  PetscReal best = -1;
  for (PetscInt j = 0; j < n; j++)
    for (PetscInt k = 0; k < n; k++)
      if (j != k && std::min(oa[j], ob[k]) > best) best = std::min(oa[j], ob[k]), *ja = j, *jb = k;
  return std::max(best, (PetscReal)0);
}

std::vector<std::pair<PetscInt, PetscInt>> ResonanceRoots(PetscInt max_order)
{
  std::vector<std::pair<PetscInt, PetscInt>> roots;
  for (PetscInt q = 3; q <= max_order; q++)
    for (PetscInt p = 1; 2 * p < q; p++)
      if (std::gcd(p, q) == 1) roots.push_back({p, q});
  std::sort(roots.begin(), roots.end(), [](const auto &x, const auto &y) { return x.first * y.second < y.first * x.second; });
  return roots;
}

PetscInt CountBelow(const FloquetResult &r, PetscReal angle, PetscReal tol, PetscReal min_edge)
{
  PetscInt n = 0;
  for (const auto &x : UpperCircle(r, tol, min_edge)) n += x.second < angle;
  return n;
}

PetscReal HalfPeriodMultiplier(const FloquetResult &half, const std::vector<std::complex<PetscReal>> &v, PetscReal *nu_re, PetscReal *nu_im)
{
  PetscReal best = 0;
  for (size_t j = 0; j < half.vectors.size(); j++) {
    const auto &w = half.vectors[j];
    if (w.size() != v.size()) continue;
    std::complex<PetscReal> h = 0, t = 0; // w^H v (nu = the member), w^T v (nu = its conjugate, eigenvector conj w)
    for (size_t k = 0; k < v.size(); k++) h += std::conj(w[k]) * v[k], t += w[k] * v[k];
    if (std::abs(h) > best) best = std::abs(h), *nu_re = half.re[j], *nu_im = half.im[j];
    if (std::abs(t) > best) best = std::abs(t), *nu_re = half.re[j], *nu_im = -half.im[j];
  }
  return best;
}

bool ResonanceDriven(PetscInt q, PetscReal nu_re, PetscReal nu_im)
{
  if (q % 2 == 0) return false;
  const std::complex<PetscReal> p = std::pow(std::complex<PetscReal>(nu_re, nu_im), (int)q);
  return std::abs(p + 1.0) < std::abs(p - 1.0); // nu^q near (-1)^q = -1
}

EventKind KreinCollisionOutcome(PetscInt k1, PetscInt k2) { return k1 * k2 < 0 ? EventKind::HamiltonianHopf : EventKind::KreinCollision; }

// -cont_bifurcations and -cont_bif_*: the events located along each branch.
static const auto &kBifurcationTable =
    DeclareOptionTable<BifurcationOptions>("cont_", "Bifurcations along the branches", [](OptionTable<BifurcationOptions> &t) {
      using B = BifurcationOptions;
      t.Bool("bifurcations", &B::enabled,
             "Detect and locate energy folds, branch points (+1), period doublings (-1), Krein collisions and internal resonances along each "
             "branch (needs -floquet without -floquet_mf; on with it)")
          .Default("on with -floquet without -floquet_mf")
          .Real("bif_tol", &B::tol, Closed(1e-14, 1e-2), "Located event: the final bracket spans at most this in omega and this times E in energy")
          .Int("bif_max_probes", &B::max_probes, Closed(1, 1000), "Orbits solved at most to locate one event")
          .Bool("bif_bulk", &B::bulk,
                "Also locate the events of bulk eigenvectors (B-B: collisions among band pairs, which shrink as the lattice grows); off: "
                "only those with an edge part (B-E, E-E) and folds")
          .Bool("bif_passes", &B::passes,
                "Also locate Krein collisions of equal signature, where two pairs on the circle meet and pass (kind 4; tracked by their "
                "eigenvectors)")
          .Int("bif_resonance_order", &B::resonance_order, Closed(0, 12),
               "Locate internal resonances: crossings of exp(2 pi i p/q) for 3 <= q <= this that the orbit's harmonics drive (kind 6); "
               "below 3: none")
          .Real("bif_angle_tol", &B::angle_tol, Open(0, 1), "Unstable multipliers of two orbits within this angle (rad) are the same one");
    });

PetscErrorCode BifurcationOptionsFromOptions(MPI_Comm comm, PetscBool dense_floquet, BifurcationOptions *o)
{
  std::vector<PetscBool> set;
  PetscFunctionBeginUser;
  o->enabled = dense_floquet;
  PetscCall(kBifurcationTable.Read(comm, o, &set));
  PetscCheck(!(kBifurcationTable.Given(set, "bifurcations") && o->enabled && !dense_floquet), comm, PETSC_ERR_USER,
             "-cont_bifurcations needs -floquet without -floquet_mf (the events are read from all 2N Floquet multipliers of every orbit)");
  PetscFunctionReturn(0);
}

PetscErrorCode LocateChange(const SampleProbe &probe, const SamePredicate &same, const TestFunction &G, PetscReal tol, PetscInt max_probes,
                            BifurcationSample *a, BifurcationSample *c, PetscInt *probes, bool *converged)
{
  PetscFunctionBeginUser;
  *probes = 0;
  *converged = false;
  auto done = [&]() { return std::abs(c->omega - a->omega) <= tol && std::abs(c->energy - a->energy) <= tol * std::abs(c->energy); };
  // Illinois (regula falsi whose retained end has its value halved when it is
  // kept twice in a row): superlinear, and bracketing throughout. A bisection
  // after every secant step that did not halve the bracket (G is linear only
  // near the change: far from it the pair nearest a collision may be another),
  // so that two probes at least halve it.
  PetscReal fa = 1, fc = 1;
  PetscInt kept = 0; // +1: a was kept last, -1: c
  bool secant_failed = false;
  while (!done()) {
    const PetscReal w = c->sigma - a->sigma;
    if (*probes >= max_probes || w < 1e-15) PetscFunctionReturn(0);
    const PetscReal ga = fa * G(*a, *c, *a), gc = fc * G(*a, *c, *c);
    PetscReal sigma = 0.5 * (a->sigma + c->sigma);
    const bool secant = std::isfinite(ga) && std::isfinite(gc) && ga * gc < 0 && !secant_failed;
    if (secant) {
      // a quarter of the tolerance from either end at least (a probe closer than that cannot shrink the bracket usefully)
      const PetscReal rate = std::max(std::abs(c->omega - a->omega) / tol, std::abs(c->energy - a->energy) / (tol * std::abs(c->energy)));
      const PetscReal h = std::min(0.25 * w / std::max(rate, (PetscReal)1), 0.25 * w);
      sigma = std::min(std::max(a->sigma + w * ga / (ga - gc), a->sigma + h), c->sigma - h);
    }
    BifurcationSample m;
    PetscCall(probe(sigma, &m));
    ++*probes;
    // Newton fails right at a branch point (the shooting Jacobian is singular
    // there), where a good secant step may land: step a little aside, twice
    for (PetscReal aside : {0.25 * (c->sigma - sigma), -0.25 * (sigma - a->sigma)}) {
      if (m.ok || *probes >= max_probes) break;
      PetscCall(probe(sigma + aside, &m));
      ++*probes;
    }
    if (!m.ok) PetscFunctionReturn(0);
    if (same(*a, m)) {
      *a = std::move(m);
      fa = 1;
      fc = kept == -1 ? 0.5 * fc : 1; // c kept twice
      kept = -1;
    } else {
      *c = std::move(m);
      fc = 1;
      fa = kept == 1 ? 0.5 * fa : 1;
      kept = 1;
    }
    secant_failed = secant && c->sigma - a->sigma > 0.5 * w;
  }
  *converged = true;
  PetscFunctionReturn(0);
}

namespace {

// Both searches: aux(x, &index) is the test function on x's multipliers
// (NaN: the member(s) not found); a probe where it is NaN counts as failed.
using TrackedFunction = std::function<PetscReal(const FloquetResult &, PetscInt *)>;

PetscErrorCode LocateTracked(const SampleProbe &probe, const BifurcationSample &a0, const BifurcationSample &c0, const TrackedFunction &aux, PetscReal tol,
                             PetscInt max_probes, BifurcationSample *a, BifurcationSample *c, PetscInt *probes, TrackedOutcome *out)
{
  auto track = [&](BifurcationSample *x) {
    if (x->ok) x->aux = aux(x->fr, &x->aux_index);
    if (!std::isfinite(x->aux)) x->ok = false;
  };
  PetscFunctionBeginUser;
  *probes = 0;
  *a = a0, *c = c0;
  track(a);
  track(c);
  if (!a->ok || !c->ok) {
    *out = TrackedOutcome::Untracked;
    PetscFunctionReturn(0);
  }
  if (!(a->aux * c->aux < 0)) {
    *out = TrackedOutcome::NoCrossing;
    PetscFunctionReturn(0);
  }
  const PetscReal slope = std::abs(c->aux - a->aux) / (c->sigma - a->sigma);
  const PetscReal sa = a->aux > 0 ? 1 : -1;
  const SampleProbe tracked = [&](PetscReal sg, BifurcationSample *x) -> PetscErrorCode {
    PetscFunctionBeginUser;
    PetscCall(probe(sg, x));
    track(x);
    PetscFunctionReturn(0);
  };
  bool conv;
  PetscCall(LocateChange(
      tracked, [&](const BifurcationSample &, const BifurcationSample &x) { return x.aux * sa > 0; },
      [](const BifurcationSample &, const BifurcationSample &, const BifurcationSample &x) { return x.aux; }, tol, max_probes, a, c, probes, &conv));
  if (!conv) *out = TrackedOutcome::NotLocated;
  else if (std::max(std::abs(a->aux), std::abs(c->aux)) > 10 * slope * (c->sigma - a->sigma) + 1e-12) *out = TrackedOutcome::Avoided;
  else *out = TrackedOutcome::Crossed;
  PetscFunctionReturn(0);
}

PetscReal Angle(const FloquetResult &r, PetscInt k) { return std::atan2(r.im[k], r.re[k]); }

} // namespace

PetscErrorCode LocatePass(const SampleProbe &probe, const BifurcationSample &a0, const BifurcationSample &c0, PetscInt ia, PetscInt ib, PetscReal tol,
                          PetscInt max_probes, BifurcationSample *a, BifurcationSample *c, PetscInt *probes, TrackedOutcome *out)
{
  const TrackedFunction aux = [&](const FloquetResult &x, PetscInt *index) -> PetscReal {
    PetscInt ja, jb;
    if (TrackPair(a0.fr, ia, ib, x, &ja, &jb) < 0.5) return NAN;
    *index = ja;
    return Angle(x, ja) - Angle(x, jb);
  };
  return LocateTracked(probe, a0, c0, aux, tol, max_probes, a, c, probes, out);
}

PetscErrorCode LocateRootCrossing(const SampleProbe &probe, const BifurcationSample &a0, const BifurcationSample &c0, PetscInt ia, PetscReal angle,
                                  PetscReal tol, PetscInt max_probes, BifurcationSample *a, BifurcationSample *c, PetscInt *probes, TrackedOutcome *out)
{
  const TrackedFunction aux = [&](const FloquetResult &x, PetscInt *index) -> PetscReal {
    PetscInt j;
    if (TrackMember(a0.fr, ia, x, &j) < 0.5) return NAN;
    *index = j;
    return Angle(x, j) - angle;
  };
  return LocateTracked(probe, a0, c0, aux, tol, max_probes, a, c, probes, out);
}

} // namespace nltopo
