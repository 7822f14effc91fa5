#include "stability/codim2.hpp"
#include "core/bytes.hpp"
#include "core/errors.hpp"
#include "core/gather.hpp"
#include "core/log.hpp"
#include "core/option_table.hpp"
#include "effects/effect.hpp"
#include "orbits/continuation.hpp"
#include "stability/collision_subspace.hpp"
#include <algorithm>
#include <cctype>
#include <cmath>
#include <complex>
#include <cstdlib>
#include <memory>

namespace nltopo {

static const char *const kParameterNames[] = {"lattice_gamma", "lattice_k", "lattice_cubic"};

const char *Codim2ParameterOption(Codim2Parameter p)
{
  static const char *const dashed[] = {"-lattice_gamma", "-lattice_k", "-lattice_cubic"};
  return dashed[(int)p];
}

PetscReal Codim2ParameterValue(const LatticeParams &lp, Codim2Parameter p)
{
  return p == Codim2Parameter::Gamma ? lp.gamma : p == Codim2Parameter::K ? lp.k : lp.Gamma;
}

void SetCodim2Parameter(LatticeParams *lp, Codim2Parameter p, PetscReal value)
{
  if (p == Codim2Parameter::Gamma) lp->gamma = value;
  else if (p == Codim2Parameter::K) lp->k = value;
  else lp->Gamma = value;
}

namespace {

// The range the lattice options themselves allow (lattice/params.cpp, effects' -lattice_cubic).
bool InParameterRange(Codim2Parameter p, PetscReal v)
{
  if (!std::isfinite(v)) return false;
  if (p == Codim2Parameter::Gamma) return v > -1 && v < 1;
  if (p == Codim2Parameter::K) return v >= 1e-6 && v <= 1e6;
  return std::abs(v) <= 1e6;
}

// The kinds -cont_codim2 follows, by the names (and codes) of /bifurcations "kind".
// regular: the orbit's shooting Jacobian (at fixed E) stays regular at the
// event, so the orbits are solved by the pivoting LU; at a branch point it is
// singular (the critical pair at +1 adds a null vector), and the start
// solver's SVD pseudo-inverse drops that direction (a fold is solved at fixed
// period, by the LU). chord: the test integrates the orbit's monodromy (into
// the stack's S), and the next orbit solve starts from it by chord Newton
// (the main solver's LU only: not at a branch point; a fold's test takes the
// shooting Jacobian instead).
struct Codim2KindName {
  const char *name, *tag;
  EventKind kind;
  bool regular, chord;
};
const Codim2KindName kCodim2Kinds[] = {{"fold", "fold", EventKind::Fold, true, false},
                                       {"branch_point", "bp", EventKind::BranchPoint, false, false},
                                       {"period_doubling", "pd", EventKind::PeriodDoubling, true, true},
                                       {"hamiltonian_hopf", "hh", EventKind::HamiltonianHopf, true, true}};

const Codim2KindName *KindOf(EventKind k)
{
  for (const Codim2KindName &n : kCodim2Kinds)
    if (n.kind == k) return &n;
  return nullptr;
}

} // namespace

static const auto &kCodim2Table = DeclareOptionTable<Codim2Options>("cont_", "Two-parameter continuation of events", [](OptionTable<Codim2Options> &t) {
  using C = Codim2Options;
  t.String("codim2", &C::spec,
           "Follow a located event of a branch (of -cont_branch, or a family of -cont_switch) in (E, p), p = -cont_codim2_parameter: "
           "<branch>:<kind>@<omega>, the event of that kind nearest omega "
           "(kind fold or 1, branch_point or 2, period_doubling or 3, hamiltonian_hopf or 5; not 4 or 6, which are no boundaries of stability); needs "
           "-cont_bifurcations")
      .Default("none")
      .Enum("codim2_parameter", &C::parameter, kParameterNames, 3,
            "The second parameter of -cont_codim2: the lattice option lattice_gamma, lattice_k or lattice_cubic (degenerate: its curves are E Gamma = "
            "const, a test)")
      .Real("codim2_min", &C::pmin, Closed(-1e6, 1e6), "-cont_codim2: the curve stops where p falls below this", OptionClass::Extent)
      .Real("codim2_max", &C::pmax, Closed(-1e6, 1e6), "-cont_codim2: the curve stops where p exceeds this", OptionClass::Extent)
      .Real("codim2_step", &C::step, Open(0, 1), "-cont_codim2: the first step along the curve, in the scaled plane (ln(q / q0), p / p0) of the event's q0, p0")
      .Real("codim2_step_min", &C::step_min, Open(0, 1),
            "-cont_codim2: the curve stops when the step falls below this (step collapse: a curve whose tangent turns by 0.3 rad over a "
            "step this short is the test function's noise, as near E -> 0)")
      .Real("codim2_step_max", &C::step_max, Open(0, 10), "-cont_codim2: the largest step along the curve (scaled plane)")
      .Real("codim2_energy_min", &C::emin, Closed(0, 1e12), "-cont_codim2: the curve stops where E falls below this (the first point below it is kept)",
            OptionClass::Extent)
      .Real("codim2_energy_max", &C::emax, Closed(0, 1e12), "-cont_codim2: the curve stops where E exceeds this (the first point above it is kept)",
            OptionClass::Extent)
      .Int("codim2_max_points", &C::max_points, Closed(1, 100000), "-cont_codim2: points of the curve on each side of the event", OptionClass::Extent)
      .Real("codim2_tol", &C::tol, Open(0, 1e-3), "-cont_codim2: the corrector has converged when its step in the scaled plane is below this")
      .Real("codim2_test_tol", &C::test_tol, Open(0, 1),
            "-cont_codim2: and the kind's test function g there is at most this times |grad g| (its first-order distance to the curve in the scaled "
            "plane)")
      .Bool("codim2_verbose", &C::verbose, "-cont_codim2: print one line per point of the curve", OptionClass::Bookkeeping);
});

PetscErrorCode ParseCodim2Spec(MPI_Comm comm, const std::string &item, Codim2Spec *s)
{
  PetscFunctionBeginUser;
  *s = Codim2Spec();
  const size_t colon = item.rfind(':');
  const std::string what = colon == std::string::npos ? "" : item.substr(colon + 1);
  const size_t at = what.find('@');
  const std::string kind = what.substr(0, at), w = at == std::string::npos ? "" : what.substr(at + 1);
  char *end = nullptr;
  s->omega = std::strtod(w.c_str(), &end);
  bool ok = colon != std::string::npos && colon > 0 && at != std::string::npos && !w.empty() && end && !*end && std::isfinite(s->omega) && s->omega > 0;
  const Codim2KindName *k = nullptr;
  for (const Codim2KindName &n : kCodim2Kinds)
    if (kind == n.name || kind == n.tag || kind == std::to_string((int)n.kind)) k = &n;
  // kinds 4 (a pass of equal signatures) and 6 (a resonance) leave every multiplier on the circle: no curve bounds a region of stability there
  PetscCheck(!(kind == "4" || kind == "6" || kind == "krein_collision" || kind == "resonance"), comm, PETSC_ERR_USER,
             "-cont_codim2 %s: kinds 4 (Krein collision, a pass) and 6 (internal resonance) are not boundaries of stability and are not followed; "
             "kinds fold (1), branch_point (2), period_doubling (3) and hamiltonian_hopf (5) are",
             item.c_str());
  PetscCheck(ok && k, comm, PETSC_ERR_USER,
             "-cont_codim2 %s: expected <branch>:<kind>@<omega> (kind fold or 1, branch_point or 2, period_doubling or 3, hamiltonian_hopf or 5; "
             "omega > 0), e.g. insulated:fold@1.9",
             item.c_str());
  s->text = item, s->branch = item.substr(0, colon), s->kind = k->kind;
  PetscFunctionReturn(0);
}

PetscErrorCode Codim2OptionsFromOptions(MPI_Comm comm, Codim2Options *o, Codim2Spec *s)
{
  PetscFunctionBeginUser;
  PetscCall(kCodim2Table.Read(comm, o));
  PetscCheck(o->pmin < o->pmax, comm, PETSC_ERR_USER, "-cont_codim2_min and -cont_codim2_max must satisfy min < max, got %g and %g", (double)o->pmin,
             (double)o->pmax);
  PetscCheck(o->step_min <= o->step && o->step <= o->step_max, comm, PETSC_ERR_USER,
             "-cont_codim2_step %g must lie in [-cont_codim2_step_min %g, -cont_codim2_step_max %g]", (double)o->step, (double)o->step_min,
             (double)o->step_max);
  *s = Codim2Spec();
  if (!o->spec.empty()) PetscCall(ParseCodim2Spec(comm, o->spec, s));
  PetscFunctionReturn(0);
}

namespace {

using OwnedKsp = Owned<KSP, KSPDestroy>;

// The orbit solver on the lattice at one value of p: what NnmSetup builds, without the linear modes.
struct Codim2Stack {
  Lattice lat;
  EffectList fx{lat};
  PeriodicFlow flow;
  Shooting shoot;
  OwnedKsp ksp; // the bordered tangent solve (LU of the assembled shooting Jacobian)
  OwnedVec z, zT, g, tz, X, t, e;
  OwnedMat S;
  PetscReal p = 0;

  PetscErrorCode Build(MPI_Comm comm, const LatticeParams &lp, const FlowOptions &fo, const ShootingOptions &so, PetscInt multiple)
  {
    PC pc;
    PetscFunctionBeginUser;
    PetscCall(lat.Setup(comm, lp));
    PetscCall(BuildEffects(lat, nullptr, &fx));
    PetscCall(flow.Setup(fx, fo));
    flow.SetPeriodMultiple(multiple);
    PetscCall(shoot.Setup(flow, so));
    PetscCall(lat.CreateStateVector(z.out()));
    for (OwnedVec *v : {&zT, &g, &tz}) PetscCall(VecDuplicate(z, v->out()));
    PetscCall(shoot.CreateUnknowns(X.out()));
    PetscCall(VecDuplicate(X, t.out()));
    PetscCall(VecDuplicate(X, e.out()));
    PetscCall(flow.CreateSensitivityMatrix(S.out()));
    PetscCall(KSPCreate(comm, ksp.out()));
    PetscCall(KSPSetType(ksp, KSPPREONLY));
    PetscCall(KSPGetPC(ksp, &pc));
    PetscCall(PCSetType(pc, PCLU));
    PetscCall(PCFactorSetMatSolverType(pc, MATSOLVERMUMPS)); // pivoting: the bordered matrix has zero diagonal entries
    PetscFunctionReturn(0);
  }
};

// The orbit-based test function of the curve (Codim2Sample of codim2.hpp: the orbit at (q, p) and g there).
class Codim2Walk : public Codim2Function {
public:
  Codim2Walk(MPI_Comm comm, const LatticeParams &base, const FlowOptions &fo, const ShootingOptions &so, const FloquetOptions &flo, PetscInt multiple,
             const Codim2Options &o, const char *name, Codim2Curve *c)
      : comm_(comm), base_(base), fo_(fo), so_(so), flo_(flo), multiple_(multiple), o_(o), name_(name), c_(c)
  {
  }
  PetscErrorCode Run(const Codim2Start &start, const BifurcationEvent &e);
  PetscErrorCode Sample(PetscReal a, PetscReal b, const Codim2Sample &from, Codim2Sample *x) override;
  void Accept(const Codim2Sample &x) override { bstar_ = x.bmid, basis_ = x.basis; } // the collision moves along the curve
  bool Collision() const override { return c_->kind == EventKind::HamiltonianHopf; }

private:
  PetscErrorCode StackAt(PetscReal p, Codim2Stack **s);
  PetscErrorCode Evaluate(PetscReal a, PetscReal b, const Codim2Sample &guess, Codim2Sample *x);
  PetscErrorCode FoldTest(Codim2Stack &s, Codim2Sample *x);
  PetscErrorCode HopfTest(Codim2Stack &s, Codim2Sample *x);
  PetscErrorCode DoublingTest(Codim2Stack &s, Codim2Sample *x);
  PetscErrorCode BranchTest(Codim2Stack &s, Codim2Sample *x);
  PetscErrorCode PairTest(Codim2Stack &s, PetscReal t, Codim2Sample *x);
  PetscErrorCode Multipliers(Codim2Stack &s, Codim2Sample *x, std::vector<std::complex<PetscReal>> *nontrivial);
  bool ByEnergy() const { return c_->kind != EventKind::Fold; } // the orbit's coordinate q: E (kinds 2, 3, 5), or omega at a fold
  PetscErrorCode Record(const Codim2Sample &x);
  PetscReal A(const Codim2Sample &x) const { return std::log((ByEnergy() ? x.energy : x.omega) / q0_); } // ln(q / q0): a curve over decades of E in few steps
  PetscReal B(const Codim2Sample &x) const { return x.p / p0_; }

  MPI_Comm comm_;
  LatticeParams base_;
  FlowOptions fo_;
  ShootingOptions so_;
  FloquetOptions flo_;
  PetscInt multiple_;
  const Codim2Options &o_;
  const char *name_;
  Codim2Curve *c_;
  PetscReal q0_ = 1, p0_ = 1;                        // scales of the plane: the event's q and p (1 if p = 0)
  PetscReal bstar_ = 0;                              // kind 5: where the two colliding pairs' b = (mu + 1/mu)/2 meet (followed along the curve)
  std::vector<PetscReal> basis_;                     // kind 5: their invariant subspace at the last point (rank 0)
  std::vector<std::unique_ptr<Codim2Stack>> stacks_; // the lattices of the last two values of p (a gradient alternates between them)
  OwnedMat seed_;                                    // the last test's monodromy: the next orbit solve's chord Jacobian (kinds 3, 5)
};

PetscErrorCode Codim2Walk::StackAt(PetscReal p, Codim2Stack **s)
{
  PetscFunctionBeginUser;
  for (auto &k : stacks_)
    if (k->p == p) {
      *s = k.get();
      PetscFunctionReturn(0);
    }
  if (stacks_.size() >= 2) stacks_.erase(stacks_.begin());
  LatticeParams lp = base_;
  SetCodim2Parameter(&lp, c_->parameter, p);
  auto k = std::make_unique<Codim2Stack>();
  PetscCall(k->Build(comm_, lp, fo_, so_, multiple_));
  k->shoot.SetEnergyStartSolver(!KindOf(c_->kind)->regular);
  k->p = p;
  *s = k.get();
  stacks_.push_back(std::move(k));
  PetscFunctionReturn(0);
}

// The multipliers of the orbit s.z (x's period and beta) on s's lattice,
// eigenvalues only, into x->mu (Record writes them); nontrivial: those
// without the trivial pair at +1 (NontrivialIndices).
PetscErrorCode Codim2Walk::Multipliers(Codim2Stack &s, Codim2Sample *x, std::vector<std::complex<PetscReal>> *nontrivial)
{
  std::vector<PetscReal> re, im;
  PetscFunctionBeginUser;
  PetscCall(s.flow.IntegrateWithMonodromy(s.z, x->period, s.flow.FloquetBeta(x->beta), s.zT, s.S));
  PetscCall(MonodromyMultipliers(s.S, 2 * s.lat.N(), &x->mu));
  for (const auto &m : x->mu) re.push_back(m.real()), im.push_back(m.imag());
  nontrivial->clear();
  for (PetscInt j : NontrivialIndices(re.data(), im.data(), (PetscInt)re.size())) nontrivial->push_back(x->mu[j]);
  PetscFunctionReturn(0);
}

// Kind 1: g = d ln E / d ln omega = -(T / E) dE/dT along the family at fixed p,
// from the family tangent t at fixed T: the assembled shooting Jacobian with the
// period row e_T (SetPeriodConstraint) solves J t = e_last, so t_T = 1 and
// dE/dT = grad E . t_z, exactly at the orbit (not the last Newton iterate's Jacobian).
PetscErrorCode Codim2Walk::FoldTest(Codim2Stack &s, Codim2Sample *x)
{
  PetscReal dT, db, dE;
  PetscInt lo, hi;
  const PetscInt last = 2 * s.lat.N() + 1;
  PetscFunctionBeginUser;
  PetscCall(s.shoot.Jacobian(s.X, s.shoot.Operator()));
  PetscCall(KSPSetOperators(s.ksp, s.shoot.Operator(), s.shoot.Operator()));
  PetscCall(VecZeroEntries(s.e));
  PetscCall(VecGetOwnershipRange(s.e, &lo, &hi));
  if (last >= lo && last < hi) PetscCall(VecSetValue(s.e, last, 1.0, INSERT_VALUES));
  PetscCall(VecAssemblyBegin(s.e));
  PetscCall(VecAssemblyEnd(s.e));
  PetscCall(KSPSolve(s.ksp, s.e, s.t));
  PetscCall(s.shoot.Unpack(s.t, s.tz, &dT, &db));
  PetscCall(s.flow.GradEnergy(s.z, s.g));
  PetscCall(VecDot(s.g, s.tz, &dE));
  x->g = -(x->period / x->energy) * dE / dT;
  PetscFunctionReturn(0);
}

// Kind 5: B = (M + M^-1)/2 has b = (mu + 1/mu)/2 for each pair; a pair on the
// circle gives a real b = cos(theta) in [-1, 1], a quadruplet's two upper members
// give b and conj(b). The two colliding pairs are, among the values of b
// nearest b* (where they meet), the two whose invariant subspace continues
// the last point's (TrackCollision; at the start: the two nearest b*), and
// g = Re (b1 - b2)^2 is the discriminant of B on
// their 4-dim invariant subspace (B is 2 x 2 on one vector per pair): > 0 on
// the circle side, < 0 for the quadruplet, 0 at the non-semisimple double b,
// and smooth through it (the locator's G is its square-root-free form in angles).
PetscErrorCode Codim2Walk::HopfTest(Codim2Stack &s, Codim2Sample *x)
{
  const PetscInt n = 2 * s.lat.N();
  std::vector<PetscReal> a;
  CollisionChoice c;
  PetscMPIInt rank;
  PetscFunctionBeginUser;
  PetscCall(s.flow.IntegrateWithMonodromy(s.z, x->period, s.flow.FloquetBeta(x->beta), s.zT, s.S));
  PetscCall(GatherMonodromy(s.S, n, &a));
  PetscCallMPI(MPI_Comm_rank(s.lat.Comm(), &rank));
  // the pairs whose subspace continues the last point's, among those nearest b* (rank 0, then every rank)
  PetscErrorCode ierr = 0;
  char msg[256] = "";
  if (rank == 0) PetscCall(CaptureError([&]() { return TrackCollision((int)n, a.data(), flo_.tol, bstar_, basis_, &c); }, &ierr, msg, sizeof msg));
  PetscCall(FailTogether(s.lat.Comm(), ierr, msg)); // (rank 0's LAPACK failure: every rank, not a wait in the broadcast)
  PetscReal head[3] = {c.ok ? 1.0 : 0.0, c.g, c.bmid};
  PetscCallMPI(MPI_Bcast(head, 3, MPIU_REAL, 0, s.lat.Comm()));
  c.mu.resize(n);
  PetscCallMPI(MPI_Bcast(c.mu.data(), (PetscMPIInt)(2 * n), MPIU_REAL, 0, s.lat.Comm()));
  x->mu = std::move(c.mu), x->basis = std::move(c.basis);
  if (head[0] != 0) x->g = head[1], x->bmid = head[2]; // (g stays NaN without two pairs to collide)
  PetscFunctionReturn(0);
}

// Kind 3: the pair nearest -1 is the two nontrivial multipliers nearest -1 (on
// the circle e^(+-i theta), or real -r, -1/r), and b = (mu1 + mu2 + 1/mu1 +
// 1/mu2) / 4 = tr(B on their 2-dim invariant subspace) / 2 = (mu + 1/mu)/2.
// g = b + 1 = cos(theta) + 1 >= 0 while the pair is on the circle, = -(r - 1)^2
// / (2 r) <= 0 once it has left along the negative real axis: smooth through
// the event, where |mu| and the angle are not. At -1 itself the pair is a
// Jordan block and each computed mu is off by the root of rounding; their sum
// (a trace on the invariant subspace) is not, nor is g.
PetscErrorCode Codim2Walk::DoublingTest(Codim2Stack &s, Codim2Sample *x) { return PairTest(s, -1, x); }

// Kind 2: as kind 3 at +1. The pair is the two nontrivial multipliers nearest
// +1 in b = (mu + 1/mu)/2 (the trivial Jordan pair, also at +1, projected out
// by NontrivialIndices; |b - 1| puts a pair's two members at one distance, so
// a real pair r, 1/r is not split), b = (mu1 + mu2 + 1/mu1 + 1/mu2) / 4 and
// g = b - 1 = cos(theta) - 1 <= 0 on the circle, (r - 1)^2 / (2 r) >= 0 once
// the pair is real: smooth through +1, where each computed mu is off by the
// root of rounding (a Jordan block) and their sum is not. The orbit at fixed E
// (Evaluate) is solved as for kinds 3 and 5, although its Jacobian is singular
// at the event: the critical vector has the other symmetry than the orbit, so
// Newton's residual has no component along it but rounding, which the start
// solver's SVD pseudo-inverse does not amplify (docs/continuation.md).
PetscErrorCode Codim2Walk::BranchTest(Codim2Stack &s, Codim2Sample *x) { return PairTest(s, +1, x); }

// Kinds 2 and 3: g = b - t of the pair nearest t = +1 or -1 in b = (mu + 1/mu)/2
// (|b - t| puts a pair's two members at one distance, so a real pair r, 1/r is
// not split), b = (mu1 + mu2 + 1/mu1 + 1/mu2) / 4 over its two members.
PetscErrorCode Codim2Walk::PairTest(Codim2Stack &s, PetscReal t, Codim2Sample *x)
{
  using C = std::complex<PetscReal>;
  std::vector<C> mu;
  PetscFunctionBeginUser;
  PetscCall(Multipliers(s, x, &mu));
  if (mu.size() < 2) PetscFunctionReturn(0); // g stays NaN
  auto dist = [t](const C &u) { return std::abs(0.5 * (u + 1.0 / u) - t); };
  std::partial_sort(mu.begin(), mu.begin() + 2, mu.end(), [&](const C &u, const C &v) { return dist(u) < dist(v); });
  x->g = 0.25 * std::real(mu[0] + mu[1] + 1.0 / mu[0] + 1.0 / mu[1]) - t;
  x->bmid = t;
  PetscFunctionReturn(0);
}

// The orbit at the scaled point (a, b) = (omega / q0, p / p0), from guess's orbit, and g there.
PetscErrorCode Codim2Walk::Evaluate(PetscReal a, PetscReal b, const Codim2Sample &guess, Codim2Sample *x)
{
  Codim2Stack *s;
  PetscInt its;
  bool ok;
  EnergyParts en;
  PetscFunctionBeginUser;
  *x = Codim2Sample();
  x->p = b * p0_;
  const PetscReal q = q0_ * std::exp(a);
  if (ByEnergy()) x->energy = q, x->period = guess.period;
  else x->omega = q, x->period = 2 * PETSC_PI / x->omega;
  if (!InParameterRange(c_->parameter, x->p) || !(q > 0 && std::isfinite(q))) PetscFunctionReturn(0);
  PetscCall(StackAt(x->p, &s));
  PetscCall(StateFromRow(s->lat, guess.z0.data(), s->z));
  PetscCall(s->shoot.Pack(s->z, x->period, guess.beta, s->X));
  if (ByEnergy()) PetscCall(s->shoot.SetEnergyConstraint(s->z, x->energy)); // (kind 2: the start solver, the SVD pseudo-inverse)
  else PetscCall(s->shoot.SetPeriodConstraint(s->z, x->period));
  if (seed_ && s->shoot.Seedable()) PetscCall(s->shoot.SeedJacobian(s->X, seed_)); // the guess's neighbour's monodromy (any p): a chord
  PetscCall(s->shoot.Solve(s->X, &ok, &its));
  c_->solves++;
  if (!ok) PetscFunctionReturn(0);
  PetscCall(s->shoot.Unpack(s->X, s->z, &x->period, &x->beta));
  PetscCall(s->flow.Effects().Energy(s->z, &en));
  x->energy = en.Total(), x->omega = 2 * PETSC_PI / x->period;
  PetscCall(AppendStateRow(s->lat, s->z, &x->z0));
  PetscCall(BroadcastFromRoot(comm_, MPIU_REAL, &x->z0));
  if (c_->kind == EventKind::HamiltonianHopf) PetscCall(HopfTest(*s, x));
  else if (c_->kind == EventKind::PeriodDoubling) PetscCall(DoublingTest(*s, x));
  else if (c_->kind == EventKind::BranchPoint) PetscCall(BranchTest(*s, x));
  else PetscCall(FoldTest(*s, x));
  if (KindOf(c_->kind)->chord) { // (s->S: the orbit's monodromy, from the test)
    if (!seed_) PetscCall(MatDuplicate(s->S, MAT_DO_NOT_COPY_VALUES, seed_.out()));
    PetscCall(MatCopy(s->S, seed_, SAME_NONZERO_PATTERN));
  }
  x->ok = std::isfinite(x->g);
  PetscFunctionReturn(0);
}

// The follower's sample: the orbit and g at (a, b), and the scaled point the orbit reached.
PetscErrorCode Codim2Walk::Sample(PetscReal a, PetscReal b, const Codim2Sample &from, Codim2Sample *x)
{
  PetscFunctionBeginUser;
  PetscCall(Evaluate(a, b, from, x));
  if (x->ok) x->a = A(*x), x->b = B(*x);
  else x->a = a, x->b = b;
  if (!ByEnergy()) x->bmid = 1; // (a fold: at +1)
  PetscFunctionReturn(0);
}

// Appends point x with its multipliers nearest the kind's critical point (+1 for a fold).
PetscErrorCode Codim2Walk::Record(const Codim2Sample &x)
{
  std::vector<std::complex<PetscReal>> all = x.mu;
  PetscFunctionBeginUser;
  if (all.empty()) { // (the event's own start point: not sampled)
    Codim2Stack *s;
    Codim2Sample y = x;
    std::vector<std::complex<PetscReal>> nontrivial;
    PetscCall(StackAt(x.p, &s));
    PetscCall(StateFromRow(s->lat, x.z0.data(), s->z));
    PetscCall(Multipliers(*s, &y, &nontrivial));
    all = y.mu;
  }
  // nearest the critical point: +1 (fold, branch point: the trivial pair and the critical one), -1 (period doubling),
  // or in b = (mu + 1/mu)/2 to the colliding pairs' (Hamiltonian-Hopf)
  using C = std::complex<PetscReal>;
  const PetscReal crit = c_->kind == EventKind::PeriodDoubling ? -1 : 1;
  auto dist = [&](PetscInt i) {
    const C mu = all[i];
    return c_->kind == EventKind::HamiltonianHopf ? std::abs(0.5 * (mu + 1.0 / mu) - x.bmid) : std::abs(mu - crit);
  };
  std::vector<PetscInt> idx(all.size());
  for (size_t k = 0; k < idx.size(); k++) idx[k] = (PetscInt)k;
  std::sort(idx.begin(), idx.end(), [&](PetscInt i, PetscInt j) { return dist(i) < dist(j); });
  PetscReal mm = 0;
  for (const C &mu : all) mm = std::max(mm, std::abs(mu));
  c_->p.push_back(x.p), c_->energy.push_back(x.energy), c_->omega.push_back(x.omega), c_->period.push_back(x.period), c_->test.push_back(x.g);
  c_->max_modulus.push_back(mm);
  for (PetscInt k = 0; k < Codim2Curve::kMultipliers; k++) {
    const bool have = (size_t)k < idx.size();
    c_->mu_re.push_back(have ? all[idx[k]].real() : NAN), c_->mu_im.push_back(have ? all[idx[k]].imag() : NAN);
  }
  PetscFunctionReturn(0);
}

PetscErrorCode Codim2Walk::Run(const Codim2Start &start, const BifurcationEvent &e)
{
  Codim2Sample s0;
  Codim2Trace t;
  PetscFunctionBeginUser;
  q0_ = ByEnergy() ? start.energy : start.omega;
  bstar_ = std::real(0.5 * (std::complex<PetscReal>(e.mu_re, e.mu_im) + 1.0 / std::complex<PetscReal>(e.mu_re, e.mu_im)));
  const PetscReal pe = Codim2ParameterValue(base_, c_->parameter);
  p0_ = pe != 0 ? std::abs(pe) : 1;
  PetscCheck(pe >= o_.pmin && pe <= o_.pmax, comm_, PETSC_ERR_USER, "-cont_codim2 %s: the run's %s %g lies outside [-cont_codim2_min %g, -cont_codim2_max %g]",
             o_.spec.c_str(), Codim2ParameterOption(c_->parameter), (double)pe, (double)o_.pmin, (double)o_.pmax);
  // the event's own point: g = 0 at the event's p, from its located orbit
  s0.ok = true, s0.omega = start.omega, s0.energy = start.energy, s0.p = pe, s0.period = start.period, s0.beta = start.beta, s0.z0 = start.z0;
  s0.a = A(s0), s0.b = B(s0), s0.bmid = bstar_;
  const std::string label = std::string(name_) + " codim2 " + c_->name;
  PetscCall(FollowCodim2(comm_, *this, o_, s0, label.c_str(), &t));
  PetscCheck(t.started, comm_, PETSC_ERR_NOT_CONVERGED,
             "-cont_codim2 %s: the event's orbit (omega %g, %s %g) was not found again with the test function at zero (%" PetscInt_FMT " corrector iterations)",
             o_.spec.c_str(), (double)start.omega, Codim2ParameterOption(c_->parameter), (double)pe, t.its);
  const Codim2Sample &x0 = t.pts[t.start];
  PetscCall(PetscPrintf(comm_, "  [%s codim2 %s] the %s at %s %g: omega %.9f, E %.8g (test function %.1e); followed in %s\n", name_, c_->name.c_str(),
                        EventKindName(c_->kind), Codim2ParameterOption(c_->parameter), (double)x0.p, (double)x0.omega, (double)x0.energy, (double)x0.g,
                        Codim2ParameterOption(c_->parameter)));
  for (const Codim2Sample &x : t.pts) PetscCall(Record(x));
  c_->event_point = t.start;
  for (const Codim2Trace::Point &q : t.points) {
    c_->point_kind.push_back((PetscInt)q.kind);
    c_->point_p.push_back(q.x.p), c_->point_energy.push_back(q.x.energy), c_->point_omega.push_back(q.x.omega), c_->point_arc.push_back(q.arc);
  }
  c_->stop_reason = "p decreasing: " + t.why_down + "; p increasing: " + t.why_up;
  PetscCall(PetscPrintf(comm_, "  [%s codim2 %s] %zu points, %s %.6g .. %.6g, E %.6g .. %.6g, %zu codim-2 points, %" PetscInt_FMT " orbits solved: %s\n", name_,
                        c_->name.c_str(), c_->p.size(), Codim2ParameterOption(c_->parameter), (double)c_->p.front(), (double)c_->p.back(),
                        (double)c_->energy.front(), (double)c_->energy.back(), t.points.size(), c_->solves, c_->stop_reason.c_str()));
  PetscFunctionReturn(0);
}

} // namespace

PetscErrorCode ContinueCodim2(MPI_Comm comm, const LatticeParams &base, const FlowOptions &fo, const ShootingOptions &so, const FloquetOptions &flo,
                              PetscInt period_multiple, const Codim2Options &o, const BifurcationEvent &e, PetscInt event, const Codim2Start &start,
                              const char *name, Codim2Curve *curve)
{
  static PetscLogEvent ev = 0;
  PetscLogDouble t0, t1;
  PetscFunctionBeginUser;
  const Codim2KindName *k = KindOf(e.kind);
  PetscCheck(k, comm, PETSC_ERR_SUP,
             "-cont_codim2: a %s bounds no region of stability and is not followed (folds, branch points, period doublings and "
             "Hamiltonian-Hopf onsets are)",
             EventKindName(e.kind));
  PetscCheck(so.jacobian == ShootingJacobian::Dense, comm, PETSC_ERR_SUP,
             "-cont_codim2 needs -nnm_jacobian dense (its test function factors the shooting Jacobian)");
  PetscCheck(start.z0.size() == (size_t)(2 * base.N()), comm, PETSC_ERR_PLIB, "-cont_codim2: the event's orbit has %zu values for 2N = %" PetscInt_FMT,
             start.z0.size(), 2 * base.N());
  if (!ev) PetscCall(NamedLogEvent("Codim2", &ev));
  PetscCall(PetscLogEventBegin(ev, 0, 0, 0, 0));
  PetscCall(PetscTime(&t0));
  *curve = Codim2Curve();
  curve->kind = e.kind, curve->event = event, curve->parameter = o.parameter;
  curve->name = std::string(k->tag) + std::to_string(event);
  {
    Codim2Walk walk(comm, base, fo, so, flo, period_multiple, o, name, curve);
    PetscCall(walk.Run(start, e));
  }
  PetscCall(PetscTime(&t1));
  curve->seconds = t1 - t0;
  PetscCall(PetscLogEventEnd(ev, 0, 0, 0, 0));
  PetscFunctionReturn(0);
}

void Codim2CurveFields(Codim2Curve &c, Bytes &w, bool put)
{
  auto f = [&](auto &x) { w.Field(x, put); };
  f(c.name), f(c.kind), f(c.event), f(c.parameter), f(c.p), f(c.energy), f(c.omega), f(c.period), f(c.test), f(c.max_modulus), f(c.mu_re), f(c.mu_im);
  f(c.event_point), f(c.point_kind), f(c.point_p), f(c.point_energy), f(c.point_omega), f(c.point_arc), f(c.stop_reason), f(c.solves), f(c.seconds);
}

std::vector<Codim2Crossing> Codim2Intersections(const std::vector<PetscReal> &p1, const std::vector<PetscReal> &e1, const std::vector<PetscReal> &p2,
                                                const std::vector<PetscReal> &e2)
{
  std::vector<Codim2Crossing> out;
  const size_t n1 = std::min(p1.size(), e1.size()), n2 = std::min(p2.size(), e2.size());
  for (size_t i = 0; i + 1 < n1; i++)
    for (size_t j = 0; j + 1 < n2; j++) {
      // P1 + t d1 = P2 + u d2 (affine: the same t, u in any scaling of p and E)
      const PetscReal d1p = p1[i + 1] - p1[i], d1e = e1[i + 1] - e1[i], d2p = p2[j + 1] - p2[j], d2e = e2[j + 1] - e2[j];
      const PetscReal rp = p2[j] - p1[i], re = e2[j] - e1[i];
      const PetscReal det = d1p * (-d2e) - d1e * (-d2p);
      const PetscReal scale = std::hypot(d1p, d1e) * std::hypot(d2p, d2e);
      if (!(std::abs(det) > 1e-14 * scale)) continue; // parallel (or a repeated point)
      const PetscReal t = (rp * (-d2e) - re * (-d2p)) / det, u = (d1p * re - d1e * rp) / det;
      // half-open segments (a crossing at a shared vertex is counted once), the last one closed
      const bool in1 = t >= 0 && (t < 1 || (i + 2 == n1 && t <= 1)), in2 = u >= 0 && (u < 1 || (j + 2 == n2 && u <= 1));
      if (in1 && in2) out.push_back({p1[i] + t * d1p, e1[i] + t * d1e, (PetscReal)i + t, (PetscReal)j + u});
    }
  return out;
}

namespace {

// A curve whose E has fallen below 1e-4 of its start's runs into the linear
// limit (E -> 0 at a finite p, the frequency shift's sign change there: ln E
// grows without bound along it); the walk ends it there. (A closed form has E = 0.)
bool AtLinearLimit(const Codim2Sample &x, const Codim2Sample &start) { return start.energy > 0 && x.energy <= 1e-4 * start.energy; }

// Pseudo-arclength on g(a, b) = 0 (the head of codim2.hpp), on any Codim2Function.
class Codim2Follower {
public:
  Codim2Follower(MPI_Comm comm, Codim2Function &f, const Codim2Options &o, const char *label) : comm_(comm), f_(f), o_(o), label_(label) {}
  PetscErrorCode Correct(const PetscReal ypred[2], const PetscReal tau[2], const Codim2Sample &from, Codim2Sample *x, PetscReal grad[2], PetscInt *its,
                         bool *ok, bool have_grad = false, PetscReal max_move = INFINITY);
  PetscErrorCode Walk(const Codim2Sample &x0, const PetscReal grad0[2], PetscInt dir, std::vector<Codim2Sample> *pts, std::vector<Codim2Trace::Point> *turns,
                      std::string *why, bool *collapsed);

private:
  PetscErrorCode Gradient(const Codim2Sample &x, PetscReal grad[2], bool *ok);
  PetscErrorCode TurnAt(const Codim2Sample &x, const PetscReal tau[2], PetscReal s, Codim2Sample *xs, PetscReal *phi, bool *ok);
  PetscErrorCode Phi(const Codim2Sample &x, const PetscReal tau[2], PetscReal *phi, bool *ok);
  struct Step { // a step of the walk: from x along tau by ds
    Codim2Sample x;
    PetscReal tau[2], ds;
  };
  PetscErrorCode FindTurn(const Step &last, const Step &step, const Codim2Sample &nx, const PetscReal tau_n[2], PetscInt k, Codim2Trace::Point *q, bool *found);
  PetscErrorCode LocateTurn(const Codim2Sample &x, const PetscReal tau[2], PetscReal ds, PetscReal phi0, PetscReal phi1, Codim2Sample *xt, PetscReal *st);

  MPI_Comm comm_;
  Codim2Function &f_;
  const Codim2Options &o_;
  const char *label_;
  static constexpr PetscReal kH = 1e-6;            // finite-difference step of grad g in the scaled plane
  static constexpr PetscInt kMaxIts = 10;          // corrector iterations
  static constexpr PetscReal kNoise = 1e-5;        // the largest |g| a converged point may have
  static constexpr PetscInt kTurnIts = 60;         // secant steps locating a turn
  static constexpr PetscReal kMaxCorrection = 0.3; // a step's corrector moves the predicted point at most this times the step
  static constexpr PetscReal kMaxAngle = 0.3;      // and the tangent turns at most this (rad) over the step
};

// Broyden's rank-one update of grad along the step d that changed g by dg:
// the change g itself saw, no sample more. Refused (false, grad kept) when it
// would change grad by more than half its length: over a step that short the
// change is g's noise, not its curvature (near E -> 0, where g is only as
// exact as the orbit).
bool Broyden(const PetscReal d[2], PetscReal dg, PetscReal grad[2])
{
  const PetscReal dd = d[0] * d[0] + d[1] * d[1];
  if (!(dd > 0)) return true;
  const PetscReal r = dg - (grad[0] * d[0] + grad[1] * d[1]);
  if (!(std::abs(r) <= 0.5 * std::hypot(grad[0], grad[1]) * std::sqrt(dd))) return false;
  grad[0] += r * d[0] / dd, grad[1] += r * d[1] / dd;
  return true;
}

// grad g at x in the scaled plane, by forward differences (kH).
PetscErrorCode Codim2Follower::Gradient(const Codim2Sample &x, PetscReal grad[2], bool *ok)
{
  Codim2Sample xa, xb;
  PetscFunctionBeginUser;
  PetscCall(f_.Sample(x.a + kH, x.b, x, &xa));
  PetscCall(f_.Sample(x.a, x.b + kH, x, &xb));
  *ok = xa.ok && xb.ok;
  grad[0] = (xa.g - x.g) / kH, grad[1] = (xb.g - x.g) / kH;
  PetscFunctionReturn(0);
}

// Newton on [g(y); tau . (y - ypred)] from ypred (tau = 0: p fixed at ypred's, the
// start point); *x the converged point, grad the gradient there. A secant
// method (Broyden's rank-one rule on each step's change of g, no samples
// more): the gradient is the one given (have_grad: the last point's, on a
// step of the walk; it is first updated along the predictor's step from
// that point, which carries the curve's turn) or taken by differences at
// the first iterate (two samples more), and again whenever a step did not
// halve the last. The converged point is sampled at the iteration's limit,
// with the updated gradient: the next step's tangent. An iterate farther
// than max_move from ypred ends it unconverged.
PetscErrorCode Codim2Follower::Correct(const PetscReal ypred[2], const PetscReal tau[2], const Codim2Sample &from, Codim2Sample *x, PetscReal grad[2],
                                       PetscInt *its, bool *ok, bool have_grad, PetscReal max_move)
{
  PetscReal y[2] = {ypred[0], ypred[1]}, last = INFINITY, d[2] = {0, 0}, g_prev = 0;
  const bool fixed_p = tau[0] == 0 && tau[1] == 0;
  const PetscReal row[2] = {fixed_p ? 0 : tau[0], fixed_p ? 1 : tau[1]}; // the constraint's row
  Codim2Sample cur = from;
  bool fresh = have_grad, gok = false;
  PetscFunctionBeginUser;
  *ok = false;
  if (have_grad && from.ok && std::isfinite(from.g)) d[0] = ypred[0] - from.a, d[1] = ypred[1] - from.b, g_prev = from.g; // the predictor's step
  for (*its = 1; *its <= kMaxIts; (*its)++) {
    PetscCall(f_.Sample(y[0], y[1], cur, x));
    if (!x->ok) PetscFunctionReturn(0);
    cur = *x;
    if (!fresh) { // the first iterate without a gradient, or a step that did not halve the last
      PetscCall(Gradient(*x, grad, &gok));
      if (!gok) PetscFunctionReturn(0);
      fresh = true;
    } else if (!Broyden(d, x->g - g_prev, grad)) { // the change is noise: a fresh gradient here
      PetscCall(Gradient(*x, grad, &gok));
      if (!gok) PetscFunctionReturn(0);
    }
    const PetscReal F[2] = {x->g, row[0] * (y[0] - ypred[0]) + row[1] * (y[1] - ypred[1])};
    const PetscReal det = grad[0] * row[1] - grad[1] * row[0];
    if (!(std::abs(det) > 0) || !std::isfinite(det)) PetscFunctionReturn(0);
    d[0] = -(F[0] * row[1] - grad[1] * F[1]) / det, d[1] = -(grad[0] * F[1] - row[0] * F[0]) / det;
    g_prev = x->g;
    const PetscReal step = std::hypot(d[0], d[1]);
    if (step <= o_.tol) {
      // the point at the iteration's limit: on the curve to about the square of the last step, so that
      // where the walk puts its points does not drift with rounding (1 and 2 ranks give the same rows)
      PetscCall(f_.Sample(y[0] + d[0], y[1] + d[1], cur, x));
      if (!x->ok) PetscFunctionReturn(0);
      // g's first-order distance to its zero set is small (a tiny step from a
      // garbage gradient is no convergence; g itself is only as exact as the orbit)
      // (each kind's g is dimensionless and O(1) off the curve: kNoise bounds it
      // where the orbit solves are too imprecise for the gradient, near E -> 0)
      *ok = std::abs(x->g) <= o_.test_tol * std::hypot(grad[0], grad[1]) && std::abs(x->g) <= kNoise;
      PetscFunctionReturn(0);
    }
    y[0] += d[0], y[1] += d[1];
    if (std::hypot(y[0] - ypred[0], y[1] - ypred[1]) > max_move) PetscFunctionReturn(0); // (the caller refuses a point this far: no more samples)
    fresh = step <= 0.5 * last; // the secant iteration converges: keep updating its gradient; else a new one next
    last = step;
  }
  PetscFunctionReturn(0);
}

// The curve at arclength s from x along tau (the corrector of a step of s), and
// phi there: the b-component of its tangent (oriented as tau), from central
// differences of g (the walk's secant gradient is good for a tangent, not
// for locating where its b-component vanishes).
PetscErrorCode Codim2Follower::TurnAt(const Codim2Sample &x, const PetscReal tau[2], PetscReal s, Codim2Sample *xs, PetscReal *phi, bool *ok)
{
  PetscReal grad[2];
  PetscInt its;
  PetscFunctionBeginUser;
  const PetscReal yp[2] = {x.a + s * tau[0], x.b + s * tau[1]};
  PetscCall(Correct(yp, tau, x, xs, grad, &its, ok));
  if (!*ok) PetscFunctionReturn(0);
  PetscCall(Phi(*xs, tau, phi, ok));
  PetscFunctionReturn(0);
}

// phi at the curve's point x: the b-component of its unit tangent, oriented
// as tau, from central differences of g (four samples).
PetscErrorCode Codim2Follower::Phi(const Codim2Sample &x, const PetscReal tau[2], PetscReal *phi, bool *ok)
{
  Codim2Sample lo, hi, left, right;
  PetscFunctionBeginUser;
  PetscCall(f_.Sample(x.a - kH, x.b, x, &lo));
  PetscCall(f_.Sample(x.a + kH, x.b, x, &hi));
  PetscCall(f_.Sample(x.a, x.b - kH, x, &left));
  PetscCall(f_.Sample(x.a, x.b + kH, x, &right));
  *ok = lo.ok && hi.ok && left.ok && right.ok;
  const PetscReal ga = (hi.g - lo.g) / (2 * kH), gb = (right.g - left.g) / (2 * kH);
  const PetscReal sign = -gb * tau[0] + ga * tau[1] < 0 ? -1 : 1; // the tangent (-gb, ga) oriented along tau
  *phi = sign * ga / std::hypot(ga, gb);
  PetscFunctionReturn(0);
}

// A turn in p between x (s = 0, tangent b-component phi0) and the next point
// (s = ds, phi1 of the other sign): the zero of phi(s) by the Illinois variant
// of regula falsi, to the corrector's tolerance in s. *xt the curve there.
PetscErrorCode Codim2Follower::LocateTurn(const Codim2Sample &x, const PetscReal tau[2], PetscReal ds, PetscReal phi0, PetscReal phi1, Codim2Sample *xt,
                                          PetscReal *st)
{
  PetscReal s0 = 0, s1 = ds, f0 = phi0, f1 = phi1;
  PetscInt side = 0;
  PetscFunctionBeginUser;
  *st = 0.5 * ds;
  for (PetscInt k = 0; k < kTurnIts && s1 - s0 > o_.tol; k++) {
    PetscReal s = (s0 * f1 - s1 * f0) / (f1 - f0), phi;
    bool ok;
    if (!(s > s0 && s < s1)) s = 0.5 * (s0 + s1);
    PetscCall(TurnAt(x, tau, s, xt, &phi, &ok));
    if (!ok) { // bisection on failure
      s = 0.5 * (s0 + s1);
      PetscCall(TurnAt(x, tau, s, xt, &phi, &ok));
      if (!ok) break;
    }
    *st = s;
    if (phi == 0) break;
    if ((phi < 0) == (f0 < 0)) {
      s0 = s, f0 = phi;
      if (side == -1) f1 *= 0.5;
      side = -1;
    } else {
      s1 = s, f1 = phi;
      if (side == 1) f0 *= 0.5;
      side = 1;
    }
  }
  PetscFunctionReturn(0);
}

// The turn in p that the walk's chords show around step.x (the point k of
// this side, 0 the start): in the chord from last.x (if k > 0) or in the one
// to nx, as the tangent at step.x says (accurate, from central differences;
// the walk's secant tangents are not, near their sign change). q: the turn,
// located by LocateTurn; arc its fractional row. found: false if the
// tangents at the chord's ends do not change sign (no turn there to locate).
PetscErrorCode Codim2Follower::FindTurn(const Step &last, const Step &step, const Codim2Sample &nx, const PetscReal tau_n[2], PetscInt k, Codim2Trace::Point *q,
                                        bool *found)
{
  PetscReal phi_x, phi_o, st;
  bool ok, ok_o;
  PetscFunctionBeginUser;
  *found = false;
  PetscCall(Phi(step.x, step.tau, &phi_x, &ok));
  if (!ok) PetscFunctionReturn(0);
  const bool before = k > 0 && phi_x * (nx.b - step.x.b) > 0; // x is already past the turn: it lies in the chord from last.x
  const Step &in = before ? last : step;
  if (before) PetscCall(Phi(last.x, last.tau, &phi_o, &ok_o));
  else PetscCall(Phi(nx, tau_n, &phi_o, &ok_o));
  if (!ok_o || phi_x * phi_o >= 0) PetscFunctionReturn(0);
  PetscCall(before ? LocateTurn(in.x, in.tau, in.ds, phi_o, phi_x, &q->x, &st) : LocateTurn(in.x, in.tau, in.ds, phi_x, phi_o, &q->x, &st));
  q->arc = (PetscReal)(before ? k - 1 : k) + st / in.ds;
  *found = true;
  PetscFunctionReturn(0);
}

// From x0 along the curve in direction dir (+1: p grows at the start), into pts;
// the turns in p on the way into turns (arc: the walk's fractional point index, 0 at x0).
PetscErrorCode Codim2Follower::Walk(const Codim2Sample &x0, const PetscReal grad0[2], PetscInt dir, std::vector<Codim2Sample> *pts,
                                    std::vector<Codim2Trace::Point> *turns, std::string *why, bool *collapsed)
{
  Codim2Sample x = x0;
  PetscReal tau[2], gx[2] = {grad0[0], grad0[1]}; // gx: the gradient at x
  PetscReal ds = o_.step;
  Step last{}; // the step that reached x
  PetscFunctionBeginUser;
  *collapsed = false;
  f_.Accept(x0);
  const PetscReal n0 = std::hypot(grad0[0], grad0[1]);
  tau[0] = -grad0[1] / n0, tau[1] = grad0[0] / n0; // orthogonal to grad g
  const PetscReal lead = std::abs(tau[1]) > 1e-12 ? tau[1] : tau[0];
  if (lead * dir < 0) tau[0] = -tau[0], tau[1] = -tau[1];
  for (;;) {
    if ((PetscInt)pts->size() >= o_.max_points) {
      *why = "reached -cont_codim2_max_points";
      break;
    }
    Codim2Sample nx;
    PetscReal ng[2];
    PetscInt its = 0;
    bool ok = false, refreshed = false;
    for (bool retry = false; !ok && ds >= o_.step_min; retry = true) {
      if (retry && !refreshed) { // the first failure: x's own gradient and tangent (the secant ones may have misled the step), same step
        bool gok;
        PetscCall(Gradient(x, gx, &gok));
        refreshed = true;
        if (gok) {
          const PetscReal nn = std::hypot(gx[0], gx[1]), t0[2] = {-gx[1] / nn, gx[0] / nn}, o = t0[0] * tau[0] + t0[1] * tau[1] < 0 ? -1 : 1;
          tau[0] = o * t0[0], tau[1] = o * t0[1];
          ds *= 2; // (undoes the halving below: the failed step again, on the new tangent)
        }
      }
      const PetscReal yp[2] = {x.a + ds * tau[0], x.b + ds * tau[1]};
      ng[0] = gx[0], ng[1] = gx[1];
      PetscCall(Correct(yp, tau, x, &nx, ng, &its, &ok, !retry, 2 * kMaxCorrection * ds)); // (a retry: a fresh gradient, the last one may have misled it)
      // a step is taken only on the same curve: the corrector moved the point a fraction of the step, and
      // the tangent turned little (another curve near, e.g. the next collision of the same pairs, would
      // otherwise catch a long step)
      if (ok) {
        const PetscReal nn = std::hypot(ng[0], ng[1]), c = std::abs(-ng[1] / nn * tau[0] + ng[0] / nn * tau[1]);
        ok = std::hypot(nx.a - yp[0], nx.b - yp[1]) <= kMaxCorrection * ds && c >= std::cos(kMaxAngle);
        // (a collision past +-1 is of real pairs off the circle: the Hamiltonian-Hopf curve ends at +-1, the steps collapse onto it)
        ok = ok && !(f_.Collision() && std::abs(nx.bmid) > 1);
      }
      if (!ok) ds *= 0.5;
    }
    if (!ok) {
      *why = "step collapse (the corrector failed at every step size)", *collapsed = true;
      break;
    }
    // past a bound of p or E: that point is kept (the curve crosses the window's edge) and the side ends
    const char *out = nx.p < o_.pmin          ? "reached -cont_codim2_min"
                      : nx.p > o_.pmax        ? "reached -cont_codim2_max"
                      : nx.energy < o_.emin   ? "reached -cont_codim2_energy_min"
                      : nx.energy > o_.emax   ? "reached -cont_codim2_energy_max"
                      : AtLinearLimit(nx, x0) ? "the linear limit (E below 1e-4 of the start's)"
                                              : nullptr;
    const PetscReal nn = std::hypot(ng[0], ng[1]);
    PetscReal nt[2] = {-ng[1] / nn, ng[0] / nn};
    if (nt[0] * tau[0] + nt[1] * tau[1] < 0) nt[0] = -nt[0], nt[1] = -nt[1];
    const Step step{x, {tau[0], tau[1]}, ds};
    // p is not monotone over the last two chords (the first: the start's tangent): a turn in p, in one of them
    if ((pts->empty() ? tau[1] : x.b - last.x.b) * (nx.b - x.b) < 0) {
      Codim2Trace::Point q{Codim2PointKind::Turn, Codim2Sample(), 0};
      bool found;
      PetscCall(FindTurn(last, step, nx, nt, (PetscInt)pts->size(), &q, &found));
      if (found) {
        turns->push_back(q);
        if (o_.verbose)
          PetscCall(PetscPrintf(comm_, "  [%s] %+d turn in p at %.10g (a = q/q0 %.10g), row %.4f of this side\n", label_, (int)dir, (double)q.x.p,
                                (double)q.x.a, (double)q.arc));
      }
    }
    last = step;
    tau[0] = nt[0], tau[1] = nt[1];
    gx[0] = ng[0], gx[1] = ng[1];
    x = nx;
    f_.Accept(x);
    pts->push_back(x);
    if (o_.verbose)
      PetscCall(PetscPrintf(comm_, "  [%s] %+d %3zu  p %.8g  E = %-11.6g omega = %.9f  g %.1e  corrector %" PetscInt_FMT "  ds %.3g\n", label_, (int)dir,
                            pts->size(), (double)x.p, (double)x.energy, (double)x.omega, (double)x.g, its, (double)ds));
    if (out) {
      *why = out;
      break;
    }
    // (secant iterations from the last point's gradient: a step that converged in a few grows, one that needed many shrinks)
    if (its <= 6) ds = std::min(1.5 * ds, o_.step_max);
    else if (its >= 9) ds = std::max(0.7 * ds, o_.step_min);
  }
  PetscFunctionReturn(0);
}

// How a side of the curve that collapsed at its last point ends: a collision
// reaching +-1 (kind 5: 1 - |bmid| within kEdge; the test function loses its
// pairs there, as they leave the circle at +-1 or become real), the linear
// limit (E below kLinear times the start's), or unclassified.
Codim2PointKind EndKind(const Codim2Function &f, const Codim2Sample &last, const Codim2Sample &start, bool collapsed)
{
  constexpr PetscReal kEdge = 1e-2, kLinear = 1e-2;
  if (AtLinearLimit(last, start)) return Codim2PointKind::LinearLimit;
  if (!collapsed) return Codim2PointKind::End;
  if (f.Collision() && 1 - std::abs(last.bmid) <= kEdge) return last.bmid > 0 ? Codim2PointKind::CollisionPlus : Codim2PointKind::CollisionMinus;
  if (start.energy > 0 && last.energy <= kLinear * start.energy) return Codim2PointKind::LinearLimit;
  return Codim2PointKind::End;
}

} // namespace

PetscErrorCode FollowCodim2(MPI_Comm comm, Codim2Function &f, const Codim2Options &o, const Codim2Sample &guess, const char *label, Codim2Trace *t)
{
  Codim2Follower w(comm, f, o, label);
  Codim2Sample x0;
  PetscReal grad0[2];
  const PetscReal none[2] = {0, 0};
  std::vector<Codim2Sample> down, up;
  std::vector<Codim2Trace::Point> tdown, tup;
  bool ok, cdown, cup;
  PetscFunctionBeginUser;
  *t = Codim2Trace();
  f.Accept(guess);
  const PetscReal y[2] = {guess.a, guess.b};
  PetscCall(w.Correct(y, none, guess, &x0, grad0, &t->its, &ok));
  if (!ok) PetscFunctionReturn(0);
  t->started = true;
  PetscCall(w.Walk(x0, grad0, -1, &down, &tdown, &t->why_down, &cdown));
  PetscCall(w.Walk(x0, grad0, +1, &up, &tup, &t->why_up, &cup));
  t->pts.assign(down.rbegin(), down.rend());
  t->start = (PetscInt)down.size();
  t->pts.push_back(x0);
  t->pts.insert(t->pts.end(), up.begin(), up.end());
  const PetscReal last = (PetscReal)t->pts.size() - 1;
  t->points.push_back({EndKind(f, t->pts.front(), x0, cdown), t->pts.front(), 0});
  for (auto it = tdown.rbegin(); it != tdown.rend(); ++it) t->points.push_back({it->kind, it->x, (PetscReal)t->start - it->arc});
  for (const Codim2Trace::Point &q : tup) t->points.push_back({q.kind, q.x, (PetscReal)t->start + q.arc});
  t->points.push_back({EndKind(f, t->pts.back(), x0, cup), t->pts.back(), last});
  PetscFunctionReturn(0);
}

} // namespace nltopo
