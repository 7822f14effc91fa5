// Floquet multipliers and Krein signatures against known truth: the linear
// limit (exp(+-i 2 pi omega_k / omega_j), signature +1 on exp(+i ...)), the
// symplectic structure (reciprocal and conjugate pairs, det M = 1) and the two
// trivial multipliers of an isolated NNM.
#include "bands/linear_modes.hpp"
#include "helpers.hpp"
#include "orbits/continuation.hpp"
#include "stability/floquet.hpp"
#include <cmath>
#include <complex>

using namespace nltopo;
using namespace nltopo::test;
using cplx = std::complex<PetscReal>;

namespace {
struct Capture : public PointHook {
  PeriodicFlow &flow;
  FloquetResult last;
  OwnedMat S;
  OwnedVec zT;
  explicit Capture(PeriodicFlow &f) : flow(f) {}
  PetscErrorCode Point(Vec z0, PetscReal T, PetscReal beta) override
  {
    PetscFunctionBeginUser;
    if (!S) {
      PetscCall(flow.CreateSensitivityMatrix(S.out()));
      PetscCall(VecDuplicate(z0, zT.out()));
    }
    PetscCall(flow.IntegrateWithMonodromy(z0, T, beta, zT, S));
    PetscCall(FloquetAnalysis(flow.Lat(), S, FloquetOptions(), &last));
    PetscFunctionReturn(0);
  }
};
} // namespace

TEST_CASE("Floquet multipliers in the linear limit, symplectic pairs, det M = 1, Krein signs", "[floquet]")
{
  LatticeParams p;
  p.cells = 2; // N = 10
  Lattice lat;
  PCHK(lat.Setup(PETSC_COMM_WORLD, p));
  LinearModes modes;
  PCHK(modes.Compute(lat, LinearModesOptions()));
  PeriodicFlow flow;
  FlowOptions fo;
  fo.steps = 512; // det M = 1 to 1e-8 needs the RK error below it (2e-8 at 256 steps)
  PCHK(flow.Setup(lat, fo));
  Shooting shoot;
  PCHK(shoot.Setup(flow, ShootingOptions()));
  ContinuationOptions co;
  co.verbose = PETSC_FALSE;
  co.max_points = 1; // the orbit at E = 1e-5
  const PetscInt N = lat.N();
  const auto &w = modes.Omega();
  for (PetscInt j : {0, 3, 7}) {
    Capture cap(flow);
    Branch b;
    PCHK(ContinueBranch(shoot, modes.Mode(j), 2 * PETSC_PI / w[j], co, "floquet", &b, &cap));
    const FloquetResult &r = cap.last;
    REQUIRE((PetscInt)r.re.size() == 2 * N);
    std::vector<cplx> mu;
    for (PetscInt i = 0; i < 2 * N; i++) mu.emplace_back(r.re[i], r.im[i]);
    auto nearest = [&](cplx z) {
      size_t best = 0;
      for (size_t i = 1; i < mu.size(); i++)
        if (std::abs(mu[i] - z) < std::abs(mu[best] - z)) best = i;
      return best;
    };
    cplx prod = 1;
    for (auto &m : mu) {
      prod *= m;
      REQUIRE(std::abs(mu[nearest(1.0 / m)] - 1.0 / m) < 1e-6); // reciprocal partner
      REQUIRE(std::abs(mu[nearest(std::conj(m))] - std::conj(m)) < 1e-6); // conjugate partner
      REQUIRE(std::abs(std::abs(m) - 1) < 1e-6); // the linear limit is stable
    }
    REQUIRE(std::abs(prod - 1.0) < 1e-8); // det M = exp(int trace A) = 1
    REQUIRE(r.stable);
    REQUIRE(r.trivial == 2); // time shift and the family direction
    // exp(+-i 2 pi omega_k / omega_j) for every linear mode k, and signature +1 on the + member
    for (PetscInt k = 0; k < N; k++) {
      const PetscReal th = 2 * PETSC_PI * w[k] / w[j];
      const cplx ep = std::polar<PetscReal>(1, th), em = std::conj(ep);
      const size_t ip = nearest(ep), im = nearest(em);
      INFO("branch " << j << ", mode " << k << ", theta " << th);
      REQUIRE(std::abs(mu[ip] - ep) < 1e-5);
      REQUIRE(std::abs(mu[im] - em) < 1e-5);
      if (k != j && std::abs(std::sin(th)) > 1e-3) {
        REQUIRE(r.krein[ip] == 1);
        REQUIRE(r.krein[im] == -1);
      }
    }
  }
}
