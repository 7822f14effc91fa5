// The localized Floquet route (stability/floquet_localized.hpp) against known
// truth: a constructed operator with a known quadruplet inside a dense circle
// spectrum; the undamped region map of the whole lattice against the dense
// monodromy of the project's tangent flow (equal to rounding); on the N = 102
// insulated orbit with a B-E instability, the damped route's multiplier and its
// independence of the window and the damping, and the truncated region against
// the damped whole lattice.
#include "helpers.hpp"
#include "nnm_fixture.hpp"
#include "stability/floquet_hooks.hpp"
#include "stability/floquet_exterior.hpp"
#include "stability/floquet_localized.hpp"
#include <algorithm>
#include <cmath>
#include <complex>

using namespace nltopo;
using namespace nltopo::test;
using cplx = std::complex<PetscReal>;

TEST_CASE("localized eigen part: a known quadruplet inside a dense circle spectrum, damped exterior", "[floquet][localized][serial]")
{
  // Region of 60 sites, interface cell at sites 29, 30; window 10 sites each side (c = 0), damped beyond.
  LocalizedOptions lo;
  lo.window = 5, lo.ramp = 5, lo.pad = 5, lo.damping = 0.7;
  const LocalizedRegion reg = MakeLocalizedRegion(62, 30, lo);
  const PetscInt n = reg.Sites(), n2 = 2 * n, i0 = reg.iface - reg.lo; // region site of the interface
  REQUIRE(n == 62);
  const PetscReal T = 3.1;
  std::vector<PetscReal> a((size_t)n2 * n2, 0.0);
  auto A = [&](PetscInt r, PetscInt c) -> PetscReal & { return a[(size_t)c * n2 + r]; };
  // every other site: a rotation of (u_s, v_s) by theta_s, its momentum row damped as the route damps it (exp(-c T))
  for (PetscInt s = 0; s < n; s++) {
    if (s == i0 || s == i0 + 1) continue;
    const PetscReal th = 2 * PETSC_PI * (0.013 + 0.977 * s / n), d = std::exp(-reg.c[s] * T);
    A(s, s) = std::cos(th), A(s, n + s) = std::sin(th);
    A(n + s, s) = -d * std::sin(th), A(n + s, n + s) = d * std::cos(th);
  }
  // the interface pair (q1, q2, p1, p2): S diag(r R(phi), R(phi)/r) S^-1, S symplectic (a shear [[I, G], [0, I]], G symmetric)
  const PetscReal r = 1.0023456789, phi = 2.2;
  const PetscReal c = std::cos(phi), s = std::sin(phi);
  PetscReal X[4][4] = {{r * c, -r * s, 0, 0}, {r * s, r * c, 0, 0}, {0, 0, c / r, -s / r}, {0, 0, s / r, c / r}};
  const PetscReal G[2][2] = {{0.3, -0.2}, {-0.2, 0.5}};
  PetscReal Sm[4][4] = {{1, 0, G[0][0], G[0][1]}, {0, 1, G[1][0], G[1][1]}, {0, 0, 1, 0}, {0, 0, 0, 1}};
  PetscReal Si[4][4] = {{1, 0, -G[0][0], -G[0][1]}, {0, 1, -G[1][0], -G[1][1]}, {0, 0, 1, 0}, {0, 0, 0, 1}};
  PetscReal B[4][4] = {};
  for (int i = 0; i < 4; i++)
    for (int j = 0; j < 4; j++)
      for (int k = 0; k < 4; k++)
        for (int l = 0; l < 4; l++) B[i][j] += Sm[i][k] * X[k][l] * Si[l][j];
  const PetscInt rows[4] = {i0, i0 + 1, n + i0, n + i0 + 1};
  for (int i = 0; i < 4; i++)
    for (int j = 0; j < 4; j++) A(rows[i], rows[j]) = B[i][j];
  LocalizedSpectrum sp;
  std::vector<PetscReal> work = a; // overwritten
  PCHK(LocalizedEigen(n2, work.data(), reg, {}, 4, FloquetOptions(), &sp));
  REQUIRE(sp.all.size() == (size_t)n2);
  // the dense circle spectrum: every window site's pair on the circle
  PetscInt on = 0;
  for (const cplx &m : sp.all) on += std::abs(std::abs(m) - 1) < 1e-12;
  REQUIRE(on == 2 * (2 * 2 * lo.window)); // 20 window sites besides the interface pair, two multipliers each
  INFO("leading " << sp.mu[0] << ", |mu| " << std::abs(sp.mu[0]) << ", edge " << sp.edge[0] << ", window " << sp.inside[0]);
  REQUIRE(std::abs(std::abs(sp.mu[0]) - r) < 1e-8);
  REQUIRE(std::abs(sp.mu[0] - std::polar(r, phi)) < 1e-8);
  REQUIRE(sp.edge[0] == Approx(1).margin(1e-12)); // on the interface cell only: E-E
  REQUIRE(Localisation(FloquetOptions(), sp.edge[0]) == 3);
  REQUIRE(sp.inside[0] == Approx(1).margin(1e-12));
  // then the circle (the inner member of the quadruplet, 1/r, is below the circle's window pairs)
  REQUIRE(std::abs(std::abs(sp.mu[1]) - 1) < 1e-12);
  // the eigenvector: A v = mu v on the region
  const std::vector<PetscReal> &v = sp.vector;
  PetscReal res = 0, nv = 0;
  for (PetscInt i = 0; i < n2; i++) {
    cplx y = 0;
    for (PetscInt j = 0; j < n2; j++) y += A(i, j) * cplx(v[j], v[n2 + j]);
    res = std::max(res, std::abs(y - sp.mu[0] * cplx(v[i], v[n2 + i])));
    nv = std::max(nv, std::abs(cplx(v[i], v[n2 + i])));
  }
  REQUIRE(res < 1e-10 * nv);
}

namespace {
// The first and the last orbit of a branch (z, T).
struct EndOrbits : public PointHook {
  OwnedVec first, last;
  PetscReal T0 = 0, T = 0;
  PetscErrorCode Point(Vec z0, PetscReal TT, PetscReal, Vec) override
  {
    PetscFunctionBeginUser;
    if (!first) {
      PetscCall(VecDuplicate(z0, first.out()));
      PetscCall(VecCopy(z0, first));
      T0 = TT;
    }
    if (!last) PetscCall(VecDuplicate(z0, last.out()));
    PetscCall(VecCopy(z0, last));
    T = TT;
    PetscFunctionReturn(0);
  }
};

// The flow of another lattice of the same springs (a longer one).
struct LongFlow {
  Lattice lat;
  EffectList fx{lat};
  PeriodicFlow flow;
  PetscErrorCode Setup(const LatticeParams &p)
  {
    PetscFunctionBeginUser;
    PetscCall(lat.Setup(PETSC_COMM_WORLD, p));
    PetscCall(BuildLatticeEffects(lat, &fx));
    PetscCall(flow.Setup(fx, FlowOptions()));
    PetscFunctionReturn(0);
  }
};

// z (of lattice a) padded with pad zero cells at both ends into zl (of lattice b).
void Pad(const Lattice &a, Vec z, const Lattice &b, PetscInt pad, Vec zl)
{
  std::vector<PetscReal> u, v, ul(b.N(), 0.0), vl(b.N(), 0.0);
  GetState(a, z, &u, &v);
  for (PetscInt i = 0; i < a.N(); i++) ul[2 * pad + i] = u[i], vl[2 * pad + i] = v[i];
  SetState(b, ul, vl, zl);
}
} // namespace

TEST_CASE("localized route on the insulated orbit with a B-E instability: dense, window and damping independence, truncation", "[floquet][localized]")
{
  NnmFixture d;
  LatticeParams p; // the paper's lattice, N = 102
  PCHK(d.Setup(p));
  EndOrbits orb;
  ContinuationOptions co;
  co.energy_max = 0.7; // the branch's first orbit beyond it: E = 0.819, dense |mu| = 1.0061108 (B-E)
  co.verbose = PETSC_FALSE;
  co.progress = 0;
  Branch b;
  PCHK(ContinueBranch(d.shoot, d.modes.Insulated(), 2 * PETSC_PI / d.modes.Named().insulated_omega, co, "insulated", &b, &orb));
  const Lattice &lat = d.lat;
  const PetscInt N = lat.N();
  OwnedMat S;
  OwnedVec zT;
  PCHK(d.flow.CreateSensitivityMatrix(S.out()));
  PCHK(VecDuplicate(orb.last, zT.out()));
  PCHK(d.flow.IntegrateWithMonodromy(orb.last, orb.T, 0.0, zT, S));
  LeadingMultipliers dense;
  PCHK(FloquetLeadingDense(lat, S, 2, FloquetOptions(), &dense));
  const cplx mu_dense(dense.re[0], dense.im[0]);
  INFO("N = 102 dense leading " << mu_dense << ", |mu| " << dense.max_modulus << ", class " << dense.instability);
  REQUIRE(dense.max_modulus == Approx(1.0061108).margin(1e-6));
  REQUIRE(dense.instability == 2);

  // The region map without damping on the whole lattice is the project's tangent map: the dense monodromy to rounding.
  {
    LocalizedOptions lo;
    lo.window = 1000, lo.pad = -1; // the window covers the lattice: c = 0 everywhere
    const LocalizedRegion reg = MakeLocalizedRegion(N, p.InterfaceSite(), lo);
    REQUIRE(reg.Sites() == N);
    std::vector<PetscReal> a, f, m;
    PCHK(LocalizedMonodromy(d.flow, orb.last, orb.T, 0.0, reg, &a, &f));
    PCHK(GatherMonodromy(S, 2 * N, &m));
    if (Rank() == 0) {
      PetscReal err = 0, mx = 0;
      for (PetscInt c = 0; c < 2 * N; c++)
        for (PetscInt r = 0; r < 2 * N; r++) {
          const PetscInt rs = r < N ? lat.StateIndexU(r) : lat.StateIndexV(r - N), cs = c < N ? lat.StateIndexU(c) : lat.StateIndexV(c - N);
          err = std::max(err, std::abs(a[(size_t)c * 2 * N + r] - m[(size_t)cs * 2 * N + rs]));
          mx = std::max(mx, std::abs(m[(size_t)cs * 2 * N + rs]));
        }
      INFO("undamped region map vs dense monodromy: " << err << " of " << mx);
      REQUIRE(err < 1e-11 * mx);
    }
  }

  // The same orbit on N = 402 (75 cells of rest added at each end: the orbit is 1e-18 there), room for the window and the layer.
  LatticeParams pl = p;
  pl.cells = 100;
  LongFlow L;
  PCHK(L.Setup(pl));
  OwnedVec z, zl, zTl;
  PCHK(L.lat.CreateStateVector(z.out()));
  PCHK(VecDuplicate(z, zTl.out()));
  Pad(lat, orb.last, L.lat, 75, z);
  { // periodic to the orbit's amplitude at the N = 102 lattice's ends (~1e-8): enough for comparisons of maps at this one orbit
    PetscReal r, r0, nz;
    PCHK(L.flow.Integrate(z, orb.T, 0.0, zTl));
    PCHK(VecAXPY(zTl, -1.0, z));
    PCHK(VecNorm(zTl, NORM_2, &r));
    PCHK(VecNorm(z, NORM_2, &nz));
    PCHK(d.flow.Integrate(orb.last, orb.T, 0.0, zT));
    PCHK(VecAXPY(zT, -1.0, orb.last));
    PCHK(VecNorm(zT, NORM_2, &r0));
    INFO("padded orbit: |z(T) - z0| / |z0| = " << r / nz << ", on N = 102 " << r0 / nz);
    REQUIRE(r < 1e-7 * nz);
  }
  // The damped route: the B-E pair of the dense N = 102 route becomes a resonance with the band continuum. Its
  // multiplier is the long-lattice limit (|mu| - 1 differs from the finite-N bubble's), its phase the pair's.
  LocalizedOptions lo;
  lo.window = 20, lo.ramp = 20, lo.damping = 1;
  FloquetOptions fo;
  LeadingMultipliers r;
  OrbitVerdict v;
  OwnedVec vr, vi;
  PCHK(VecDuplicate(z, vr.out()));
  PCHK(VecDuplicate(z, vi.out()));
  PCHK(FloquetLocalized(L.flow, z, orb.T, 0.0, fo, lo, 3, &r, &v, vr, vi));
  const cplx mu(r.re[0], r.im[0]);
  INFO("localized N = 402: " << VerdictName(v.code) << " " << mu << " |mu| " << std::abs(mu) << " class " << v.cls << " | " << v.reason);
  REQUIRE(v.code == Verdict::UnstableLocalized);
  REQUIRE(v.cls == 2); // B-E: it radiates into the absorbing layer
  REQUIRE(std::abs(mu) > 1 + 1e-3);
  REQUIRE(std::abs(std::arg(mu) - std::arg(mu_dense)) < 5e-3);
  REQUIRE(v.bound == Approx(std::abs(mu) - 1).epsilon(1e-12));

  // (b) independence: W and c halved and doubled move the multiplier by far less than |mu| - 1
  LocalizedIndependenceResult ind;
  PCHK(LocalizedIndependence(L.flow, z, orb.T, 0.0, fo, lo, 3, &ind));
  INFO("independence: W/2 " << ind.change[0] << ", 2W " << ind.change[1] << ", c/2 " << ind.change[2] << ", 2c " << ind.change[3] << ", modulus "
                            << ind.max_modulus_change);
  REQUIRE(std::abs(ind.mu0 - mu) == 0);
  REQUIRE(ind.max_change < 1e-5);
  REQUIRE(ind.max_modulus_change < 1e-5);

  // the truncated region against the damped whole lattice (the damping to the lattice's ends)
  LocalizedOptions full = lo;
  full.pad = -1;
  LeadingMultipliers rf;
  OrbitVerdict vf;
  PCHK(FloquetLocalized(L.flow, z, orb.T, 0.0, fo, full, 3, &rf, &vf, nullptr, nullptr));
  INFO("whole lattice damped " << rf.re[0] << " " << rf.im[0]);
  REQUIRE(std::abs(cplx(rf.re[0], rf.im[0]) - mu) < 1e-12);

  // confirmed on the undamped lattice: the window norm of the vector grows as |mu|^k
  FloquetOptions vo = fo;
  OrbitVerdict c = v;
  PCHK(ConfirmLocalizedGrowth(L.flow, z, orb.T, 0.0, vr, vi, lo, vo, &c));
  INFO("confirmed rate " << c.confirmed_rate << " against ln|mu| " << std::log(std::abs(mu)) << ": " << c.reason);
  REQUIRE(c.code == Verdict::UnstableLocalized);

  // the -floquet_mf hook's dispatch (-floquet_mf_which localized beyond -floquet_mf_dense_max): the same verdict and vector
  {
    FloquetMfOptions mo;
    mo.which = FloquetMfWhich::Localized, mo.dense_max = 0, mo.nev = 3, mo.loc = lo;
    FloquetMfHook hook(L.flow, fo, mo);
    REQUIRE(std::string(hook.Route()) == "localized");
    PCHK(hook.Point(z, orb.T, 0.0, nullptr));
    REQUIRE(hook.loc_verdict.code == Verdict::UnstableLocalized);
    REQUIRE(hook.loc_verdict.mu_re == mu.real());
    REQUIRE(hook.c.stable.back() == kUnstable);
    REQUIRE(hook.c.instability.back() == 2);
    PetscReal dv;
    PCHK(VecAXPY(hook.loc_vr, -1.0, vr));
    PCHK(VecNorm(hook.loc_vr, NORM_INFINITY, &dv));
    REQUIRE(dv == 0);
  }

  // a stable orbit (the branch's first, E = 1e-5): stable-to(-floquet_tol)
  OwnedVec z1;
  PCHK(VecDuplicate(z, z1.out()));
  Pad(lat, orb.first, L.lat, 75, z1);
  LeadingMultipliers r1;
  OrbitVerdict v1;
  PCHK(FloquetLocalized(L.flow, z1, orb.T0, 0.0, fo, lo, 3, &r1, &v1, nullptr, nullptr));
  INFO(v1.reason);
  REQUIRE(v1.code == Verdict::StableTo);
  REQUIRE(v1.bound == fo.tol);
  REQUIRE(r1.max_modulus < 1 + 1e-9);
}

TEST_CASE("exterior route: the finite lattice's own multipliers from the window of M - M_lin, against the dense route", "[floquet][localized][exterior]")
{
  NnmFixture d;
  LatticeParams p; // the paper's lattice, N = 102
  PCHK(d.Setup(p));
  EndOrbits orb;
  ContinuationOptions co;
  co.energy_max = 0.7; // the branch's last orbit: E = 0.819, a B-E quadruplet
  co.verbose = PETSC_FALSE;
  co.progress = 0;
  Branch b;
  PCHK(ContinueBranch(d.shoot, d.modes.Insulated(), 2 * PETSC_PI / d.modes.Named().insulated_omega, co, "insulated", &b, &orb));
  // The orbit on N = 402 (75 rest cells added at each end): the region of M - M_lin (40 cells each side, 162 sites)
  // is a truncation of this lattice, and its 804 x 804 dense monodromy is the truth.
  LatticeParams pl = p;
  pl.cells = 100;
  LongFlow L;
  PCHK(L.Setup(pl));
  OwnedVec z, zT, vr, vi;
  OwnedMat S;
  PCHK(L.lat.CreateStateVector(z.out()));
  PCHK(VecDuplicate(z, zT.out()));
  PCHK(VecDuplicate(z, vr.out()));
  PCHK(VecDuplicate(z, vi.out()));
  Pad(d.lat, orb.last, L.lat, 75, z);
  PCHK(L.flow.CreateSensitivityMatrix(S.out()));
  PCHK(L.flow.IntegrateWithMonodromy(z, orb.T, 0.0, zT, S));
  FloquetOptions fo;
  fo.tol = 1e-4;
  LeadingMultipliers dense;
  PCHK(FloquetLeadingDense(L.lat, S, 2, fo, &dense));
  const cplx mu_dense(dense.re[0], dense.im[0]);
  INFO("N = 402 dense leading " << mu_dense << ", |mu| " << dense.max_modulus << ", class " << dense.instability);
  REQUIRE(dense.max_modulus > 1 + 1e-3);

  // the route through -floquet_loc_exterior (the damped route's window small, its answer kept in the reason only)
  LocalizedOptions lo;
  lo.exterior = PETSC_TRUE, lo.exterior_cells = 40, lo.window = 10, lo.ramp = 10, lo.resolve = PETSC_FALSE;
  LeadingMultipliers r;
  OrbitVerdict v;
  PCHK(FloquetLocalized(L.flow, z, orb.T, 0.0, fo, lo, 3, &r, &v, vr, vi));
  INFO(VerdictName(v.code) << ": " << v.reason);
  REQUIRE(v.reason.find("exterior route (M - M_lin on ") == 0); // resolved: the window reaches at most half-way to the region's ends
  REQUIRE(v.reason.find("-site region") != std::string::npos);
  REQUIRE(r.converged >= 1);
  const cplx mu(r.re[0], r.im[0]);
  REQUIRE(std::abs(mu - mu_dense) < 1e-8); // the finite lattice's own quadruplet, not the damped route's long-lattice limit
  // every root is a multiplier of the dense monodromy: the dense route's second pair, where it is beyond the circle
  if (dense.re.size() > 1 && std::hypot(dense.re[1], dense.im[1]) > 1 + fo.tol / 10) {
    REQUIRE(r.converged > 1);
    REQUIRE(std::abs(cplx(r.re[1], r.im[1]) - cplx(dense.re[1], dense.im[1])) < 1e-8);
  }
  REQUIRE(v.code == Verdict::UnstableLocalized);
  REQUIRE(v.cls == dense.instability);
  REQUIRE(v.whole_lattice_vector);
  // the whole lattice's eigenvector: M v = mu v, confirmed growing as |mu|^k over -floquet_confirm_periods
  PCHK(ConfirmLocalizedGrowth(L.flow, z, orb.T, 0.0, vr, vi, lo, fo, &v));
  INFO("confirmed rate " << v.confirmed_rate << " against ln|mu| " << std::log(std::abs(mu_dense)) << ": " << v.reason);
  REQUIRE(v.code == Verdict::UnstableLocalized);
  REQUIRE(v.confirmed_rate == Approx(std::log(std::abs(mu_dense))).epsilon(1e-3));

  // the branch's first orbit (E = 1e-5) is stable: stable-to(-floquet_tol) on the exterior route (M - M_lin
  // decays slowly at this amplitude: its window to 1e-10 of |M| fits the 162-site region, to 1e-12 it does not)
  lo.exterior_tol = 1e-10;
  OwnedVec z1;
  PCHK(VecDuplicate(z, z1.out()));
  Pad(d.lat, orb.first, L.lat, 75, z1);
  PCHK(FloquetLocalized(L.flow, z1, orb.T0, 0.0, fo, lo, 3, &r, &v, nullptr, nullptr));
  INFO(v.reason);
  REQUIRE(v.code == Verdict::StableTo);
  REQUIRE(v.bound == fo.tol);
  REQUIRE(v.reason.find("exterior route") == 0);
}
