// The localized Floquet route (stability/floquet_localized.hpp) against known
// truth: a constructed operator with a known quadruplet inside a dense circle
// spectrum; the undamped region map of the whole lattice against the dense
// monodromy of the project's tangent flow (equal to rounding); on the N = 102
// insulated orbit with a B-E instability, the damped route's multiplier and its
// independence of the window and the damping, and the truncated region against
// the damped whole lattice.
#include "helpers.hpp"
#include "nnm_fixture.hpp"
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
  PCHK(LocalizedEigen(n2, a.data(), reg, {}, 4, FloquetOptions(), &sp));
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
// The last orbit of a branch (z, T) and its dense monodromy S.
struct LastOrbit : public PointHook {
  PeriodicFlow &flow;
  OwnedVec z, zT, dz;
  OwnedMat S;
  PetscReal T = 0;
  explicit LastOrbit(PeriodicFlow &f) : flow(f) {}
  PetscErrorCode Point(Vec z0, PetscReal TT, PetscReal, Vec dz0) override
  {
    PetscFunctionBeginUser;
    if (!z) PetscCall(VecDuplicate(z0, z.out()));
    PetscCall(VecCopy(z0, z));
    T = TT;
    PetscFunctionReturn(0);
  }
};
} // namespace

TEST_CASE("localized route on the N = 102 insulated orbit with a B-E instability", "[floquet][localized]")
{
  NnmFixture d;
  LatticeParams p; // the paper's lattice, N = 102
  PCHK(d.Setup(p));
  LastOrbit last(d.flow);
  ContinuationOptions co;
  co.energy_max = 0.7; // the branch's first orbit beyond: E = 0.819, dense |mu| = 1.0061108 (B-E)
  co.verbose = PETSC_FALSE;
  co.progress = 0;
  Branch b;
  PCHK(ContinueBranch(d.shoot, d.modes.Insulated(), 2 * PETSC_PI / d.modes.Named().insulated_omega, co, "insulated", &b, &last));
  const Lattice &lat = d.lat;
  const PetscInt N = lat.N();
  PCHK(d.flow.CreateSensitivityMatrix(last.S.out()));
  PCHK(VecDuplicate(last.z, last.zT.out()));
  PCHK(d.flow.IntegrateWithMonodromy(last.z, last.T, 0.0, last.zT, last.S));
  LeadingMultipliers dense;
  PCHK(FloquetLeadingDense(lat, last.S, 2, FloquetOptions(), &dense));
  INFO("dense leading " << dense.re[0] << " " << dense.im[0] << " |mu| " << dense.max_modulus << " class " << dense.instability);

  SECTION("undamped, the whole lattice: the dense monodromy to rounding")
  {
    LocalizedOptions lo;
    lo.window = 1000, lo.pad = -1; // the window covers the lattice: c = 0 everywhere
    const LocalizedRegion reg = MakeLocalizedRegion(N, p.InterfaceSite(), lo);
    REQUIRE(reg.Sites() == N);
    std::vector<PetscReal> a, f, m;
    PCHK(LocalizedMonodromy(d.flow, last.z, last.T, 0.0, reg, &a, &f));
    PCHK(GatherMonodromy(last.S, 2 * N, &m));
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
  SECTION("damped: explore")
  {
    for (PetscInt W : {4, 8, 12, 16})
      for (PetscReal c : {0.25, 0.5, 1.0, 2.0}) {
        LocalizedOptions lo;
        lo.window = W, lo.ramp = 8, lo.damping = c;
        LeadingMultipliers r;
        OrbitVerdict v;
        PCHK(FloquetLocalized(d.flow, last.z, last.T, 0.0, FloquetOptions(), lo, 3, &r, &v, nullptr, nullptr));
        PetscPrintf(PETSC_COMM_WORLD, "W %d c %g: %s %.9f (%.9f %+.9f i) | %.9f %.9f | %s\n", (int)W, (double)c, VerdictName(v.code), (double)r.max_modulus,
                    (double)r.re[0], (double)r.im[0], (double)std::hypot(r.re[1], r.im[1]), (double)std::hypot(r.re[2], r.im[2]), v.reason.c_str());
      }
  }
}
