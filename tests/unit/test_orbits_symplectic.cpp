// The symplectic shooting flow (-nnm_ts_type symsplit,
// orbits/variational_symplectic.hpp): every column of its monodromy, the beta
// and T columns included, is the derivative of the discrete map (central
// differences); at beta = 0 the monodromy is symplectic and det M = 1 to
// rounding, which the RK 5(4) route misses by its truncation error.
#include "monodromy_fd.hpp"
#include "orbits/flow.hpp"
#include <cmath>

using namespace nltopo;
using namespace nltopo::test;

namespace {

struct Chain10 { // N = 10, the paper's cubic coefficient
  LatticeParams p;
  Lattice lat;
  Chain10()
  {
    p.cells = 2;
    p.Gamma = 0.5;
    PCHK(lat.Setup(PETSC_COMM_WORLD, p));
  }
};

// The monodromy (first 2N columns of S) in site ordering (u_1..u_N, v_1..v_N), on every rank.
std::vector<std::vector<PetscReal>> SiteMonodromy(const Lattice &lat, Mat S)
{
  const PetscInt N = lat.N(), n = 2 * N;
  auto site = [&](PetscInt j) { return j < N ? lat.StateIndexU(j) : lat.StateIndexV(j - N); };
  std::vector<std::vector<PetscReal>> M(n, std::vector<PetscReal>(n));
  for (PetscInt b = 0; b < n; b++) {
    Vec c;
    PCHK(MatDenseGetColumnVecRead(S, site(b), &c));
    const auto col = Gather(c);
    PCHK(MatDenseRestoreColumnVecRead(S, site(b), &c));
    for (PetscInt a = 0; a < n; a++) M[a][b] = col[site(a)];
  }
  return M;
}

// max |M^T Omega M - Omega|, Omega = [[0, I], [-I, 0]].
PetscReal SymplecticDefect(const std::vector<std::vector<PetscReal>> &M)
{
  const size_t n = M.size(), N = n / 2;
  PetscReal d = 0;
  for (size_t a = 0; a < n; a++)
    for (size_t b = 0; b < n; b++) {
      long double s = 0; // (M^T Omega M)_ab = sum_i M_ia M_(i+N)b - M_(i+N)a M_ib
      for (size_t i = 0; i < N; i++) s += (long double)M[i][a] * M[i + N][b] - (long double)M[i + N][a] * M[i][b];
      const PetscReal omega = (a < N && b == a + N) ? 1.0 : (a >= N && b + N == a ? -1.0 : 0.0);
      d = std::max(d, std::abs((PetscReal)s - omega));
    }
  return d;
}

// det M by LU with partial pivoting.
PetscReal Determinant(std::vector<std::vector<PetscReal>> A)
{
  const size_t n = A.size();
  long double det = 1;
  for (size_t k = 0; k < n; k++) {
    size_t p = k;
    for (size_t i = k + 1; i < n; i++)
      if (std::abs(A[i][k]) > std::abs(A[p][k])) p = i;
    if (p != k) std::swap(A[p], A[k]), det = -det;
    det *= A[k][k];
    for (size_t i = k + 1; i < n; i++) {
      const PetscReal l = A[i][k] / A[k][k];
      for (size_t j = k; j < n; j++) A[i][j] -= l * A[k][j];
    }
  }
  return (PetscReal)det;
}

} // namespace

TEST_CASE_METHOD(Chain10, "symplectic shooting flow: every column of S and the T column are derivatives of the discrete map", "[orbits][symsplit]")
{
  ScopedOptions opts{{"-nnm_ts_type", "symsplit"}, {"-nnm_ts_symsplit_scheme", "bm4"}};
  const PetscInt N = lat.N();
  PeriodicFlow flow;
  FlowOptions fo;
  fo.steps = 24; // coarse: the discrete map differs visibly from the exact flow
  auto fx_flow = Effects(lat);
  PCHK(flow.Setup(*fx_flow, fo));
  REQUIRE(flow.Symplectic());
  OwnedVec z0, zT, zp, zm, w, dz, f;
  OwnedMat S;
  PCHK(lat.CreateStateVector(z0.out()));
  for (OwnedVec *v : {&zT, &zp, &zm, &w, &dz, &f}) PCHK(VecDuplicate(z0, v->out()));
  auto u = Pseudo(N, 5), v = Pseudo(N, 6); // amplitude ~1: strongly nonlinear
  SetState(lat, u, v, z0);
  const PetscReal T = 3.3, beta = 0.01, h = 1e-6;
  PCHK(flow.CreateSensitivityMatrix(S.out()));
  PCHK(flow.IntegrateWithMonodromy(z0, T, beta, zT, S));
  PetscReal maxerr, maxval;
  MonodromyAgainstFD(lat, flow, u, v, T, beta, S, h, &maxerr, &maxval);
  INFO("max |S - FD| = " << maxerr << ", max |S| = " << maxval);
  REQUIRE(maxerr < 1e-7 * std::max<PetscReal>(1, maxval));

  // One tangent direction (dz, dbeta, dT) against the central difference of the
  // discrete map along it; f(z(T)) (the exact flow's T-derivative) misses it.
  SetState(lat, Pseudo(N, 9), Pseudo(N, 10), dz);
  const PetscReal dbeta = 0.3, dT = 0.7;
  PCHK(flow.IntegrateWithTangent(z0, T, beta, dz, dbeta, dT, zT, w));
  PCHK(VecWAXPY(zp, h, dz, z0));
  PCHK(VecWAXPY(zm, -h, dz, z0));
  PCHK(flow.Integrate(zp, T + h * dT, beta + h * dbeta, zp));
  PCHK(flow.Integrate(zm, T - h * dT, beta - h * dbeta, zm));
  PCHK(VecAXPY(zp, -1.0, zm));
  PCHK(VecScale(zp, 0.5 / h));
  const PetscReal ew = RelativeDifference(w, zp);
  INFO("|w - FD| / |FD| = " << ew);
  REQUIRE(ew < 1e-7);
  // the T column alone differs from f_beta(z(T)) by the discretisation error
  PCHK(VecZeroEntries(dz));
  PCHK(flow.IntegrateWithTangent(z0, T, 0.0, dz, 0.0, 1.0, zT, w));
  PCHK(flow.Integrate(z0, T + h, 0.0, zp));
  PCHK(flow.Integrate(z0, T - h, 0.0, zm));
  PCHK(VecAXPY(zp, -1.0, zm));
  PCHK(VecScale(zp, 0.5 / h));
  PCHK(flow.EvalRhs(T, zT, f));
  const PetscReal eT = RelativeDifference(w, zp), ef = RelativeDifference(f, zp);
  INFO("T column: |w - FD| / |FD| = " << eT << ", |f(z(T)) - FD| / |FD| = " << ef);
  REQUIRE(eT < 1e-7);
  REQUIRE(ef > 1e2 * eT);
}

TEST_CASE_METHOD(Chain10, "symplectic shooting flow: at beta = 0 the monodromy is symplectic and det M = 1 to rounding", "[orbits][symsplit]")
{
  const PetscInt N = lat.N();
  auto u = Pseudo(N, 5), v = Pseudo(N, 6);
  for (auto &x : u) x *= 0.5;
  for (auto &x : v) x *= 0.5;
  const PetscReal T = 3.3;
  auto monodromy = [&](const char *type) {
    ScopedOptions opts{{"-nnm_ts_type", type}};
    PeriodicFlow flow;
    FlowOptions fo;
    fo.steps = 128;
    auto fx_flow = Effects(lat);
    PCHK(flow.Setup(*fx_flow, fo));
    OwnedVec z0, zT;
    OwnedMat S;
    PCHK(lat.CreateStateVector(z0.out()));
    PCHK(VecDuplicate(z0, zT.out()));
    SetState(lat, u, v, z0);
    PCHK(flow.CreateSensitivityMatrix(S.out()));
    PCHK(flow.IntegrateWithMonodromy(z0, T, flow.FloquetBeta(1e-3), zT, S)); // symsplit: taken at beta = 0
    return SiteMonodromy(lat, S);
  };
  const auto Ms = monodromy("symsplit"), Mr = monodromy("rk");
  PetscReal norm = 0;
  for (auto &row : Ms)
    for (PetscReal x : row) norm = std::max(norm, std::abs(x));
  const PetscReal ds = SymplecticDefect(Ms), dr = SymplecticDefect(Mr), dets = Determinant(Ms), detr = Determinant(Mr);
  INFO("max |M| = " << norm << "; symsplit: defect " << ds << ", |det - 1| " << std::abs(dets - 1) << "; rk 5dp with beta = 1e-3: defect " << dr
                    << ", |det - 1| " << std::abs(detr - 1));
  REQUIRE(ds < 1e-13 * norm * norm);
  REQUIRE(std::abs(dets - 1) < 1e-12);
  REQUIRE(dr > 1e3 * ds); // the test can tell: RK with beta != 0 is not symplectic
}
