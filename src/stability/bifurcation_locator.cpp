#include "stability/bifurcation_locator.hpp"
#include "core/progress.hpp"
#include "core/gather.hpp"
#include "core/log.hpp"
#include <algorithm>
#include <cmath>
#include <tuple>

namespace nltopo {

namespace {

PetscInt Sign(PetscReal x) { return x > 0 ? 1 : (x < 0 ? -1 : 0); }

} // namespace

PetscErrorCode BifurcationLocator::Setup(Shooting &shoot, const FloquetOptions &fo, const BifurcationOptions &bo)
{
  PetscFunctionBeginUser;
  shoot_ = &shoot, fo_ = fo, bo_ = bo;
  const Lattice &lat = shoot.Flow().Lat();
  N_ = lat.N();
  PetscCall(shoot.CreateUnknowns(Xa_.out()));
  for (OwnedVec *v : {&Xb_, &d_, &X_, &Xpred_, &t_}) PetscCall(VecDuplicate(Xa_, v->out()));
  PetscCall(lat.CreateStateVector(z_.out()));
  for (OwnedVec *v : {&za_, &zT_, &tz_, &g_}) PetscCall(VecDuplicate(z_, v->out()));
  PetscCall(shoot.Flow().CreateSensitivityMatrix(S_.out()));
  PetscFunctionReturn(0);
}

PetscErrorCode BifurcationLocator::SetSegment(PetscInt i)
{
  const Lattice &lat = shoot_->Flow().Lat();
  PetscFunctionBeginUser;
  if (seg_ == i) PetscFunctionReturn(0);
  PetscCall(StateFromRow(lat, rows_.data() + (size_t)(i + 1) * 2 * N_, z_));
  PetscCall(shoot_->Pack(z_, period_[i + 1], beta_[i + 1], Xb_));
  PetscCall(StateFromRow(lat, rows_.data() + (size_t)i * 2 * N_, za_));
  PetscCall(shoot_->Pack(za_, period_[i], beta_[i], Xa_));
  PetscCall(VecWAXPY(d_, -1.0, Xa_, Xb_));
  PetscCall(VecNormalize(d_, &chord_));
  seg_ = i;
  PetscFunctionReturn(0);
}

// The Newton start at sigma: the chord point, or the line through the
// nearest orbits solved on either side of sigma in this segment (a small
// bracket's ends, a far better start than the chord of the whole segment).
PetscErrorCode BifurcationLocator::Predict(PetscReal sigma, Vec X)
{
  const std::vector<PetscScalar> *lo = nullptr, *hi = nullptr;
  PetscReal slo = -1, shi = 2;
  PetscFunctionBeginUser;
  for (const auto &[sg, x] : solved_[seg_]) {
    if (sg <= sigma && sg > slo) slo = sg, lo = &x;
    if (sg >= sigma && sg < shi) shi = sg, hi = &x;
  }
  if (!lo || !hi || shi - slo > 0.5) {
    PetscCall(VecCopy(Xpred_, X));
    PetscFunctionReturn(0);
  }
  const PetscReal w = shi > slo ? (sigma - slo) / (shi - slo) : 0;
  PetscScalar *x;
  PetscCall(VecGetArrayWrite(X, &x));
  for (size_t k = 0; k < lo->size(); k++) x[k] = (1 - w) * (*lo)[k] + w * (*hi)[k];
  PetscCall(VecRestoreArrayWrite(X, &x));
  PetscFunctionReturn(0);
}

PetscErrorCode BifurcationLocator::Remember(PetscReal sigma, Vec X)
{
  const PetscScalar *x;
  PetscInt n;
  PetscFunctionBeginUser;
  PetscCall(VecGetLocalSize(X, &n));
  PetscCall(VecGetArrayRead(X, &x));
  solved_[seg_].push_back({sigma, std::vector<PetscScalar>(x, x + n)});
  PetscCall(VecRestoreArrayRead(X, &x));
  PetscFunctionReturn(0);
}

PetscErrorCode BifurcationLocator::Probe(PetscReal sigma, bool floquet, bool tangent, BifurcationSample *s, const PetscReal *target,
                                         std::vector<PetscReal> *vec, std::vector<PetscReal> *tz)
{
  PeriodicFlow &flow = shoot_->Flow();
  PetscReal T, beta;
  PetscInt its;
  bool ok;
  PetscFunctionBeginUser;
  *s = BifurcationSample();
  s->sigma = sigma;
  PetscCall(VecWAXPY(Xpred_, sigma * chord_, d_, Xa_));
  PetscCall(shoot_->SetArclengthConstraint(za_, d_, Xpred_));
  PetscCall(Predict(sigma, X_));
  // a probe that takes its monodromy anyway starts from the last one's: chord Newton (a tangent probe needs the
  // Jacobian at its orbit, so a plain Newton)
  if (floquet && !tangent && seed_ && shoot_->Seedable()) PetscCall(shoot_->SeedJacobian(X_, S_));
  PetscCall(shoot_->Solve(X_, &ok, &its));
  probes_++;
  if (!ok) {
    s->ok = false;
    PetscFunctionReturn(0);
  }
  PetscCall(Remember(sigma, X_));
  PetscCall(shoot_->Unpack(X_, z_, &T, &beta));
  EnergyParts e;
  PetscCall(flow.Effects().Energy(z_, &e));
  s->omega = 2 * PETSC_PI / T;
  s->energy = e.Total();
  last_T_ = T, last_beta_ = beta;
  if (tangent) { // before anything else uses the solver: the tangent takes the last Jacobian
    PetscReal dT, db;
    PetscCall(shoot_->Tangent(X_, d_, t_));
    PetscCall(shoot_->Unpack(t_, tz_, &dT, &db));
    PetscCall(flow.GradEnergy(z_, g_));
    PetscCall(VecDot(g_, tz_, &s->dEds));
    if (tz) {
      PetscReal nrm;
      PetscCall(VecNormalize(tz_, &nrm));
      tz->clear();
      PetscCall(AppendStateRow(flow.Lat(), tz_, tz));
      PetscCall(BroadcastFromRoot(flow.Lat().Comm(), MPIU_REAL, tz));
    }
  }
  if (floquet) {
    PetscCall(flow.IntegrateWithMonodromy(z_, T, flow.FloquetBeta(beta), zT_, S_));
    seed_ = true;
    PetscCall(FloquetAnalysis(flow.Lat(), S_, fo_, &s->fr, target, vec, vectors_));
    s->out = OutsideMultipliers(s->fr, fo_.tol, min_edge_);
  }
  PetscFunctionReturn(0);
}

// An event located in segment seg between a and c: at the middle of the bracket.
void BifurcationLocator::Place(PetscInt seg, const BifurcationSample &a, const BifurcationSample &c, BifurcationEvent *e) const
{
  e->point = seg;
  e->energy = 0.5 * (a.energy + c.energy);
  e->omega = 0.5 * (a.omega + c.omega);
  e->sigma = 0.5 * (a.sigma + c.sigma);
  e->s = s_[seg] + e->sigma * chord_;
  e->omega_bracket = std::abs(c.omega - a.omega);
}

PetscErrorCode BifurcationLocator::Folds(const Branch &b, PetscInt first_segment, std::vector<BifurcationEvent> *ev)
{
  const PetscInt np = (PetscInt)b.energy.size();
  PetscInt last_seg = -1;
  PetscFunctionBeginUser;
  for (PetscInt i = 1; i + 1 < np; i++) {
    if ((b.energy[i] - b.energy[i - 1]) * (b.energy[i + 1] - b.energy[i]) >= 0) continue;
    // dE/ds at i - 1, i, i + 1: the fold lies in the segment where it changes sign
    BifurcationSample a, c;
    PetscInt seg = -1;
    for (PetscInt j : {i - 1, i}) {
      if (j <= last_seg || j < first_segment) continue;
      PetscCall(SetSegment(j));
      PetscCall(Probe(0, false, true, &a));
      PetscCall(Probe(1, false, true, &c));
      if (a.ok && c.ok && Sign(a.dEds) * Sign(c.dEds) < 0) {
        seg = j;
        break;
      }
    }
    if (seg < 0) continue;
    last_seg = seg;
    const PetscInt sa = Sign(a.dEds);
    PetscInt used;
    bool conv;
    PetscCall(LocateChange([&](PetscReal sg, BifurcationSample *s) { return Probe(sg, false, true, s); },
                           [&](const BifurcationSample &, const BifurcationSample &x) { return Sign(x.dEds) == sa; },
                           [](const BifurcationSample &, const BifurcationSample &, const BifurcationSample &x) { return x.dEds; }, bo_.tol, bo_.max_probes, &a,
                           &c, &used, &conv));
    BifurcationEvent e;
    BifurcationSample tip;
    e.kind = EventKind::Fold;
    e.direction = sa > 0 ? 1 : -1;
    Place(seg, a, c, &e);
    PetscCall(Probe(c.sigma, false, true, &tip, nullptr, nullptr, &e.vector)); // the family tangent there
    if (!conv)
      PetscCall(PetscPrintf(shoot_->Flow().Lat().Comm(), "  warning: the energy fold after point %" PetscInt_FMT " was bracketed only to %.1e in omega (%s)\n",
                            seg, (double)e.omega_bracket, "Newton failed inside it, or -cont_bif_max_probes were spent"));
    ev->push_back(std::move(e));
  }
  PetscFunctionReturn(0);
}

PetscErrorCode BifurcationLocator::StabilityChanges(PetscInt i, std::vector<BifurcationEvent> *ev)
{
  MPI_Comm comm = shoot_->Flow().Lat().Comm();
  const PetscReal atol = bo_.angle_tol;
  std::vector<BifurcationSample> seen(2); // every orbit probed in the segment, by sigma
  PetscFunctionBeginUser;
  PetscCall(SetSegment(i));
  // the ends re-solved (Newton converges at once): the same computation as every probe
  PetscCall(Probe(0, true, false, &seen[0]));
  PetscCall(Probe(1, true, false, &seen[1]));
  if (!seen[0].ok || !seen[1].ok) PetscFunctionReturn(0);
  const SamePredicate same = [&](const BifurcationSample &a, const BifurcationSample &x) { return SameOutside(a.out, x.out, atol); };
  // the test function of the first change between a and c
  const TestFunction G = [&](const BifurcationSample &a, const BifurcationSample &c, const BifurcationSample &x) -> PetscReal {
    const auto ch = OutsideChanges(a.out, c.out, atol);
    if (ch.empty()) return NAN;
    return CollisionFunction(x.fr, ch[0].first.kind, ch[0].first.angle, fo_.tol, atol, min_edge_);
  };
  const SampleProbe probe = [&](PetscReal sg, BifurcationSample *x) -> PetscErrorCode {
    PetscFunctionBeginUser;
    PetscCall(Probe(sg, true, false, x));
    if (x->ok) seen.insert(std::upper_bound(seen.begin(), seen.end(), sg, [](PetscReal v, const BifurcationSample &y) { return v < y.sigma; }), *x);
    PetscFunctionReturn(0);
  };
  auto bracketed = [&](const BifurcationSample &a, const BifurcationSample &c) {
    return std::abs(c.omega - a.omega) <= bo_.tol && std::abs(c.energy - a.energy) <= bo_.tol * std::abs(c.energy);
  };
  // Every change seen between two neighbouring probes is located: a probe of
  // one search may reveal a change (a short bubble) the search itself steps over.
  std::vector<PetscReal> given_up; // left ends of brackets given up on (a failed Newton, or max probes)
  for (PetscInt round = 0; round < 64; round++) {
    size_t k = 0;
    for (; k + 1 < seen.size(); k++)
      if (!same(seen[k], seen[k + 1]) && !bracketed(seen[k], seen[k + 1]) && std::find(given_up.begin(), given_up.end(), seen[k].sigma) == given_up.end())
        break;
    if (k + 1 >= seen.size()) break;
    BifurcationSample a = seen[k], c = seen[k + 1];
    PetscInt used;
    bool conv;
    PetscCall(LocateChange(probe, same, G, bo_.tol, bo_.max_probes, &a, &c, &used, &conv));
    if (!conv) {
      given_up.push_back(a.sigma);
      PetscCall(PetscPrintf(comm,
                            "  warning: a change of stability after point %" PetscInt_FMT
                            " was bracketed only to %.1e in omega, %.1e in E/E, sigma %.3e (%" PetscInt_FMT " probes%s)\n",
                            i, (double)std::abs(c.omega - a.omega), (double)std::abs((c.energy - a.energy) / c.energy), (double)(c.sigma - a.sigma), used,
                            used < bo_.max_probes ? ", Newton failed inside it" : ": -cont_bif_max_probes"));
    }
  }
  for (size_t k = 0; k + 1 < seen.size(); k++) {
    const BifurcationSample &a = seen[k], &c = seen[k + 1];
    for (const auto &[o, born] : OutsideChanges(a.out, c.out, atol)) {
      BifurcationEvent e;
      e.kind = o.kind;
      e.direction = born;
      const BifurcationSample &U = born > 0 ? c : a; // off the circle
      Place(i, a, c, &e);
      e.mu_re = U.fr.re[o.index], e.mu_im = std::abs(U.fr.im[o.index]);
      // The signatures from the nearest orbit on the circle side where they are
      // defined: next to the collision the two eigenvectors merge and their
      // Krein values vanish (at +-1 the pair's eigenvalues may even round to real).
      for (PetscInt q = born > 0 ? (PetscInt)k : (PetscInt)k + 1; q >= 0 && q<(PetscInt)seen.size(); q += born> 0 ? -1 : 1) {
        CollidingSignatures(seen[q].fr, e.kind, o.angle, fo_.tol, e.krein, min_edge_);
        if (e.krein[0] && e.krein[1]) break;
      }
      e.instability = Localisation(fo_, U.fr.edge[o.index]);
      // The eigenvector from the nearest orbit on the unstable side where the
      // multiplier has moved 1e-3 off the circle: at the collision itself the
      // colliding eigenvectors merge (and at +1 mix with the trivial pair's
      // Jordan block), so there they are not determined.
      PetscInt qv = born > 0 ? (PetscInt)k + 1 : (PetscInt)k;
      PetscReal target[2] = {e.mu_re, e.mu_im};
      PetscReal mod = o.modulus;
      for (PetscInt q = qv; q >= 0 && q<(PetscInt)seen.size(); q += born> 0 ? 1 : -1) {
        const Outside *m = nullptr; // the same member: its kind, near in angle, nearest in modulus
        for (const Outside &x : seen[q].out)
          if (x.kind == o.kind && std::abs(x.angle - o.angle) <= atol && (!m || std::abs(std::log(x.modulus / mod)) < std::abs(std::log(m->modulus / mod))))
            m = &x;
        if (!m) break;
        mod = m->modulus;
        qv = q, target[0] = seen[q].fr.re[m->index], target[1] = std::abs(seen[q].fr.im[m->index]);
        if (m->modulus >= 1 + 1e-3) break;
      }
      BifurcationSample u;
      PetscCall(Probe(seen[qv].sigma, true, false, &u, target, &e.vector));
      ev->push_back(std::move(e));
    }
  }
  PetscFunctionReturn(0);
}

// Kind 4: each pair of circle multipliers that may pass between the
// segment's ends (PassCandidates) is followed by its eigenvectors
// (LocatePass); an avoided crossing is counted, not reported.
PetscErrorCode BifurcationLocator::Passes(PetscInt i, const FloquetResult &fi, const FloquetResult &fj, std::vector<BifurcationEvent> *ev)
{
  const auto cand = PassCandidates(fi, fj, fo_.tol, min_edge_);
  BifurcationSample a0, c0;
  PetscFunctionBeginUser;
  if (cand.empty()) PetscFunctionReturn(0);
  PetscCall(SetSegment(i));
  vectors_ = min_edge_;
  PetscCall(Probe(0, true, false, &a0));
  PetscCall(Probe(1, true, false, &c0));
  const SampleProbe probe = [&](PetscReal sg, BifurcationSample *x) { return Probe(sg, true, false, x); };
  for (const auto &[tha, thb] : cand) {
    if (!a0.ok || !c0.ok) break;
    PetscInt ia = -1, ib = -1; // the candidates' members at the segment's start, by angle
    for (const auto &[k, th] : UpperCircle(a0.fr, fo_.tol, min_edge_)) {
      if (ia < 0 || std::abs(th - tha) < std::abs(std::atan2(a0.fr.im[ia], a0.fr.re[ia]) - tha)) ia = k;
      if (ib < 0 || std::abs(th - thb) < std::abs(std::atan2(a0.fr.im[ib], a0.fr.re[ib]) - thb)) ib = k;
    }
    if (ia < 0 || ia == ib || a0.fr.krein[ia] == 0 || a0.fr.krein[ia] != a0.fr.krein[ib]) continue; // equal (definite) signatures only
    BifurcationSample a, c;
    PetscInt used;
    TrackedOutcome out;
    PetscCall(LocatePass(probe, a0, c0, ia, ib, bo_.tol, bo_.max_probes, &a, &c, &used, &out));
    if (out == TrackedOutcome::Avoided) passes_avoided_++;
    if (out != TrackedOutcome::Crossed) continue;
    PetscInt ja, jb;
    TrackPair(a0.fr, ia, ib, c.fr, &ja, &jb);
    BifurcationEvent e;
    e.kind = EventKind::KreinCollision;
    e.direction = 0;
    Place(i, a, c, &e);
    const PetscReal th = 0.5 * (std::atan2(c.fr.im[ja], c.fr.re[ja]) + std::atan2(c.fr.im[jb], c.fr.re[jb]));
    e.mu_re = std::cos(th), e.mu_im = std::sin(th);
    e.krein[0] = e.krein[1] = a0.fr.krein[ia];
    const PetscInt la = Localisation(fo_, c.fr.edge[ja]), lb = Localisation(fo_, c.fr.edge[jb]);
    e.instability = la == lb ? la : 2;
    e.vector = RealPhase(c.fr.vectors[ja]);
    ev->push_back(std::move(e));
  }
  vectors_ = -1;
  PetscFunctionReturn(0);
}

PetscErrorCode BifurcationLocator::HalfPeriod(bool *symmetric, FloquetResult *half)
{
  PeriodicFlow &flow = shoot_->Flow();
  PetscReal n0, d;
  PetscFunctionBeginUser;
  *symmetric = false;
  if (flow.Steps() % 2) PetscFunctionReturn(0); // not the orbit's own step size: no verdict, every crossing kept
  {
    // half the steps over half the period: the orbit's own discrete map, on
    // which z(T/2) = -z(0) holds to the Newton tolerance when the family has
    // the symmetry (the step commutes with z -> -z: the force is odd)
    PeriodMultipleScope half_period(flow, flow.PeriodMultiple(), 2 * flow.PeriodDivisor());
    PetscCall(flow.IntegrateWithMonodromy(z_, 0.5 * last_T_, flow.FloquetBeta(last_beta_), zT_, S_));
    seed_ = false; // (half the period's: no seed)
  }
  PetscCall(VecNorm(z_, NORM_2, &n0));
  PetscCall(VecAXPY(zT_, 1.0, z_));
  PetscCall(VecNorm(zT_, NORM_2, &d));
  *symmetric = d <= 1e-6 * n0;
  PetscCall(FloquetAnalysis(flow.Lat(), S_, fo_, half, nullptr, nullptr, 0));
  PetscFunctionReturn(0);
}

// Kind 6: where the number of circle multipliers below a root of unity
// e^{i theta_r} (ResonanceRoots) differs between the segment's ends, each
// member at the start is followed by its eigenvector to the end (a member
// whose edge share crossed -cont_bif_bulk's threshold changes the count
// without crossing anything); the crossing of a member that passes theta_r is
// located on its angle minus theta_r, and kept when the orbit's harmonics
// drive it (bifurcations.hpp, ResonanceDriven). On an orbit with the
// half-period symmetry even orders are not searched.
PetscErrorCode BifurcationLocator::Resonances(PetscInt i, const FloquetResult &fi, const FloquetResult &fj, std::vector<BifurcationEvent> *ev)
{
  std::vector<std::pair<PetscInt, PetscInt>> roots;
  for (const auto &[p, q] : ResonanceRoots(bo_.resonance_order)) {
    const PetscReal th = 2 * PETSC_PI * p / q;
    if (CountBelow(fi, th, fo_.tol, min_edge_) != CountBelow(fj, th, fo_.tol, min_edge_)) roots.push_back({p, q});
  }
  BifurcationSample a0, c0;
  bool symmetric = false;
  FloquetResult half;
  PetscFunctionBeginUser;
  if (roots.empty()) PetscFunctionReturn(0);
  PetscCall(SetSegment(i));
  vectors_ = min_edge_;
  PetscCall(Probe(0, true, false, &a0));
  if (a0.ok) PetscCall(HalfPeriod(&symmetric, &half));
  PetscCall(Probe(1, true, false, &c0));
  const SampleProbe probe = [&](PetscReal sg, BifurcationSample *x) { return Probe(sg, true, false, x); };
  auto angle = [](const FloquetResult &r, PetscInt k) { return std::atan2(r.im[k], r.re[k]); };
  // each member at the start and its continuation at the end, one to one (a
  // clash goes to the larger overlap; the other member is not followed)
  std::vector<std::pair<PetscInt, PetscReal>> members; // (start index, end angle)
  if (a0.ok && c0.ok) {
    std::vector<std::tuple<PetscInt, PetscInt, PetscReal>> match; // (ia, jc, overlap)
    for (const auto &[ia, tha] : UpperCircle(a0.fr, fo_.tol, min_edge_)) {
      PetscInt jc;
      const PetscReal o = TrackMember(a0.fr, ia, c0.fr, &jc);
      if (o >= 0.5) match.push_back({ia, jc, o});
    }
    for (const auto &[ia, jc, o] : match) {
      bool best = true;
      for (const auto &[ib, jb, ob] : match) best = best && !(jb == jc && ib != ia && (ob > o || (ob == o && ib < ia)));
      if (best) members.push_back({ia, angle(c0.fr, jc)});
    }
  }
  for (const auto &[ia, thc] : members) {
    const PetscReal tha = angle(a0.fr, ia);
    for (const auto &[p, q] : roots) {
      const PetscReal th = 2 * PETSC_PI * p / q;
      if (!((tha - th) * (thc - th) < 0) || (symmetric && q % 2 == 0)) continue;
      BifurcationSample a, c;
      PetscInt used;
      TrackedOutcome out;
      PetscCall(LocateRootCrossing(probe, a0, c0, ia, th, bo_.tol, bo_.max_probes, &a, &c, &used, &out));
      if (out != TrackedOutcome::Crossed) continue;
      const PetscInt k = c.aux_index;
      if (symmetric) {
        // the crossing member's half-period multiplier nu at the crossing: the
        // half-period map's member whose eigenvector is the crossing one's (or
        // its conjugate: nu in the lower half plane)
        BifurcationSample u;
        PetscCall(Probe(c.sigma, false, false, &u));
        if (!u.ok) continue;
        bool sym;
        PetscReal nu_re = 0, nu_im = 0;
        PetscCall(HalfPeriod(&sym, &half));
        if (HalfPeriodMultiplier(half, c.fr.vectors[k], &nu_re, &nu_im) < 0.5) continue;
        if (!ResonanceDriven(q, nu_re, nu_im)) {
          resonances_undriven_++;
          continue;
        }
      }
      BifurcationEvent e;
      e.kind = EventKind::Resonance;
      e.direction = thc > tha ? 1 : -1; // +1: the member's angle grows along the branch
      Place(i, a, c, &e);
      e.mu_re = std::cos(th), e.mu_im = std::sin(th);
      e.krein[0] = c.fr.krein[k];
      e.instability = Localisation(fo_, c.fr.edge[k]);
      e.resonance[0] = p, e.resonance[1] = q;
      e.vector = RealPhase(c.fr.vectors[k]);
      ev->push_back(std::move(e));
    }
  }
  vectors_ = -1;
  PetscFunctionReturn(0);
}

PetscErrorCode BifurcationLocator::OrbitAt(PetscInt segment, PetscReal sigma, Vec X, bool *converged)
{
  PetscInt its;
  PetscFunctionBeginUser;
  PetscCheck(segment >= 0 && (size_t)(segment + 1) < period_.size(), shoot_->Flow().Lat().Comm(), PETSC_ERR_ARG_OUTOFRANGE,
             "bifurcations: no segment %" PetscInt_FMT " in the last located branch", segment);
  PetscCall(SetSegment(segment));
  PetscCall(VecWAXPY(Xpred_, sigma * chord_, d_, Xa_));
  PetscCall(shoot_->SetArclengthConstraint(za_, d_, Xpred_));
  PetscCall(Predict(sigma, X));
  PetscCall(shoot_->Solve(X, converged, &its));
  probes_++;
  PetscFunctionReturn(0);
}

PetscErrorCode BifurcationLocator::Report(const char *name, PetscInt k, const BifurcationEvent &e)
{
  static const char *const loc[] = {"", "B-B", "B-E", "E-E"};
  MPI_Comm comm = shoot_->Flow().Lat().Comm();
  PetscFunctionBeginUser;
  if (e.kind == EventKind::Fold) {
    PetscCall(PetscPrintf(comm, "  [%s] event %" PetscInt_FMT ": energy fold (E %s) at omega %.9f (bracket %.1e), E %.6g, s %.6g\n", name, k,
                          e.direction > 0 ? "maximum" : "minimum", (double)e.omega, (double)e.omega_bracket, (double)e.energy, (double)e.s));
    PetscFunctionReturn(0);
  }
  if (e.kind == EventKind::KreinCollision || e.kind == EventKind::Resonance) {
    char what[64] = "";
    if (e.kind == EventKind::Resonance)
      PetscCall(PetscSNPrintf(what, sizeof(what), " through exp(2 pi i %" PetscInt_FMT "/%" PetscInt_FMT ")", e.resonance[0], e.resonance[1]));
    char krein[32];
    if (e.kind == EventKind::Resonance) PetscCall(PetscSNPrintf(krein, sizeof(krein), "Krein %+d", (int)e.krein[0]));
    else PetscCall(PetscSNPrintf(krein, sizeof(krein), "Krein (%+d, %+d)", (int)e.krein[0], (int)e.krein[1]));
    PetscCall(PetscPrintf(comm, "  [%s] event %" PetscInt_FMT ": %s %s%s at omega %.9f (bracket %.1e), E %.6g, mu %.6f%+.6fi, %s\n", name, k,
                          EventKindName(e.kind), loc[e.instability], what, (double)e.omega, (double)e.omega_bracket, (double)e.energy, (double)e.mu_re,
                          (double)e.mu_im, krein));
    PetscFunctionReturn(0);
  }
  PetscCall(PetscPrintf(comm, "  [%s] event %" PetscInt_FMT ": %s %s, %s at omega %.9f (bracket %.1e), E %.6g, mu %.6f%+.6fi, Krein (%+d, %+d)\n", name, k,
                        EventKindName(e.kind), loc[e.instability], e.direction > 0 ? "instability begins" : "instability ends", (double)e.omega,
                        (double)e.omega_bracket, (double)e.energy, (double)e.mu_re, (double)e.mu_im, (int)e.krein[0], (int)e.krein[1]));
  PetscFunctionReturn(0);
}

PetscErrorCode BifurcationLocator::Locate(const Branch &b, const std::vector<PetscReal> &re, const std::vector<PetscReal> &im,
                                          const std::vector<PetscReal> &edge, const char *name, std::vector<BifurcationEvent> *events,
                                          const std::vector<PetscInt> &krein, PetscInt first_segment)
{
  const Lattice &lat = shoot_->Flow().Lat();
  MPI_Comm comm = lat.Comm();
  const PetscInt np = (PetscInt)b.energy.size(), n2 = 2 * N_;
  PetscFunctionBeginUser;
  PetscCall(PetscLogEventBegin(Log().bifurcations, 0, 0, 0, 0));
  events->clear();
  seg_ = -1;
  passes_avoided_ = resonances_undriven_ = 0;
  solved_.clear();
  // B-B events are left out unless asked for; a lattice without an interface has no edge region to tell them by
  min_edge_ = bo_.bulk || lat.Params().layout != Layout::Interface ? 0 : 1 - fo_.edge_weight;
  rows_ = b.z0; // rank 0's rows to every rank
  PetscCall(BroadcastFromRoot(comm, MPIU_REAL, &rows_));
  const PetscInt nr = (PetscInt)rows_.size();
  PetscCheck(nr == np * n2 && re.size() == (size_t)(np * n2) && im.size() == re.size(), comm, PETSC_ERR_PLIB,
             "bifurcations: branch %s has %" PetscInt_FMT " points but %" PetscInt_FMT " orbit values and %zu multipliers", name, np, nr, re.size());
  period_ = b.period, beta_ = b.beta;
  s_.assign(np, 0);
  for (PetscInt i = 1; i < np; i++) {
    PetscReal d2 = (period_[i] - period_[i - 1]) * (period_[i] - period_[i - 1]) + (beta_[i] - beta_[i - 1]) * (beta_[i] - beta_[i - 1]);
    for (PetscInt k = 0; k < n2; k++) d2 += std::pow(rows_[i * n2 + k] - rows_[(i - 1) * n2 + k], 2);
    s_[i] = s_[i - 1] + std::sqrt(d2);
  }
  ProgressMeter progress;
  progress.Start(comm, progress_every_);
  PetscCall(Folds(b, first_segment, events));
  std::vector<BifurcationEvent> changes;
  const PetscInt first = std::max(first_segment, (PetscInt)0), nseg = std::max<PetscInt>(np - 1 - first, 1);
  for (PetscInt i = first; i + 1 < np; i++) {
    char what[128];
    PetscCall(PetscSNPrintf(what, sizeof what, "locating: segment %" PetscInt_FMT " of %" PetscInt_FMT ", %zu event(s) found", i - first, nseg,
                            events->size() + changes.size()));
    PetscCall(progress.Report(name, what, (double)(i - first) / nseg));
    const PetscReal *r0 = re.data() + i * n2, *i0 = im.data() + i * n2;
    const bool finite = std::all_of(r0, r0 + 2 * n2, [](PetscReal x) { return std::isfinite(x); }); // both points (a resumed branch may lack them)
    if (!finite) continue;
    FloquetResult fi, fj;
    fi.re.assign(r0, r0 + n2), fi.im.assign(i0, i0 + n2), fj.re.assign(r0 + n2, r0 + 2 * n2), fj.im.assign(i0 + n2, i0 + 2 * n2);
    if (edge.size() == re.size())
      fi.edge.assign(edge.begin() + i * n2, edge.begin() + (i + 1) * n2), fj.edge.assign(edge.begin() + (i + 1) * n2, edge.begin() + (i + 2) * n2);
    if (!SameOutside(OutsideMultipliers(fi, fo_.tol, min_edge_), OutsideMultipliers(fj, fo_.tol, min_edge_), bo_.angle_tol))
      PetscCall(StabilityChanges(i, &changes));
    if (krein.size() == re.size()) fi.krein.assign(krein.begin() + i * n2, krein.begin() + (i + 1) * n2);
    if (bo_.passes) PetscCall(Passes(i, fi, fj, &changes));
    if (bo_.resonance_order >= 3) PetscCall(Resonances(i, fi, fj, &changes));
  }
  // At an energy fold a pair passes +1 (the reduced map on the energy
  // surface has a saddle-node there, and the multiplier +1 is fourfold): the
  // changes of stability there, through +1 or of quadruplets near it, are the fold's.
  for (BifurcationEvent &c : changes) {
    bool at_fold = false;
    const bool stability = c.kind == EventKind::BranchPoint || c.kind == EventKind::PeriodDoubling || c.kind == EventKind::HamiltonianHopf;
    for (const BifurcationEvent &f : *events)
      if (stability && f.kind == EventKind::Fold && std::hypot(c.mu_re - 1, c.mu_im) < 0.05 &&
          std::abs(c.s - f.s) <= 1e-4 * std::max(s_.back(), (PetscReal)1e-300))
        at_fold = true;
    if (!at_fold) events->push_back(std::move(c));
  }
  std::stable_sort(events->begin(), events->end(), [](const BifurcationEvent &x, const BifurcationEvent &y) { return x.s < y.s; });
  for (size_t k = 0; k < events->size(); k++) PetscCall(Report(name, (PetscInt)k, (*events)[k]));
  if (passes_avoided_ || resonances_undriven_)
    PetscCall(PetscPrintf(comm,
                          "  [%s] not events: %" PetscInt_FMT " avoided crossings of equal signature, %" PetscInt_FMT
                          " root-of-unity crossings no harmonic of the orbit drives\n",
                          name, passes_avoided_, resonances_undriven_));
  PetscCall(PetscLogEventEnd(Log().bifurcations, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

} // namespace nltopo
