#include "orbits/linear_monodromy_pc.hpp"
#include <cmath>

extern "C" { // LAPACK's banded LU (Debian liblapack)
void dgbtrf_(const int *m, const int *n, const int *kl, const int *ku, double *ab, const int *ldab, int *ipiv, int *info);
void dgbtrs_(const char *trans, const int *n, const int *kl, const int *ku, const int *nrhs, const double *ab, const int *ldab, const int *ipiv, double *b,
             const int *ldb, int *info, size_t trans_len);
}

namespace nltopo {

static const int kBandKl = 3, kBandKu = 3, kBandLd = 2 * kBandKl + kBandKu + 1; // B T in the order (a_0, b_0, a_1, b_1, ...)

PetscErrorCode LinearMonodromyPC::Setup(const Lattice &lat)
{
  MPI_Comm comm = lat.Comm();
  PetscMPIInt size;
  PetscFunctionBeginUser;
  lat_ = &lat;
  N_ = lat.N();
  PetscCallMPI(MPI_Comm_size(comm, &size));
  counts_.resize(size);
  displs_.resize(size);
  const PetscMPIInt mine = (PetscMPIInt)lat.OwnedCount(), start = (PetscMPIInt)lat.OwnedStart();
  PetscCallMPI(MPI_Allgather(&mine, 1, MPI_INT, counts_.data(), 1, MPI_INT, comm));
  PetscCallMPI(MPI_Allgather(&start, 1, MPI_INT, displs_.data(), 1, MPI_INT, comm));
  // The chain's diagonals from the assembled K (rows i-1, i, i+1 only: model.md's nearest-neighbour bonds).
  std::vector<PetscReal> d(mine), e(mine, 0.0);
  for (PetscInt i = start; i < start + mine; i++) {
    PetscInt nc;
    const PetscInt *cols;
    const PetscScalar *vals;
    PetscCall(MatGetRow(lat.K(), i, &nc, &cols, &vals));
    for (PetscInt k = 0; k < nc; k++) {
      PetscCheck(std::abs(cols[k] - i) <= 1, comm, PETSC_ERR_ARG_WRONG, "-nnm_mf_pc linear needs a tridiagonal K (nearest-neighbour chain)");
      if (cols[k] == i) d[i - start] = vals[k];
      if (cols[k] == i + 1) e[i - start] = vals[k];
    }
    PetscCall(MatRestoreRow(lat.K(), i, &nc, &cols, &vals));
  }
  for (auto *v : {&ru_, &rv_, &gu_, &gv_, &t1_, &t2_}) v->resize(N_);
  PetscCall(SetStiffness(d, e));
  PetscFunctionReturn(0);
}

// The whole chain's diagonals d, e (e[N-1] = 0) from owned rows.
PetscErrorCode LinearMonodromyPC::GatherChain(const std::vector<PetscReal> &diag, const std::vector<PetscReal> &off, std::vector<PetscReal> *d,
                                              std::vector<PetscReal> *e)
{
  MPI_Comm comm = lat_->Comm();
  PetscFunctionBeginUser;
  const PetscMPIInt mine = (PetscMPIInt)lat_->OwnedCount();
  PetscCheck((PetscMPIInt)diag.size() == mine && (PetscMPIInt)off.size() == mine, comm, PETSC_ERR_ARG_SIZ, "stiffness diagonals must have the owned length");
  d->resize(N_);
  e->resize(N_);
  PetscCallMPI(MPI_Allgatherv(diag.data(), mine, MPIU_REAL, d->data(), counts_.data(), displs_.data(), MPIU_REAL, comm));
  PetscCallMPI(MPI_Allgatherv(off.data(), mine, MPIU_REAL, e->data(), counts_.data(), displs_.data(), MPIU_REAL, comm));
  (*e)[N_ - 1] = 0; // no bond past the last site
  PetscFunctionReturn(0);
}

PetscErrorCode LinearMonodromyPC::SetStiffness(const std::vector<PetscReal> &diag, const std::vector<PetscReal> &off)
{
  PetscFunctionBeginUser;
  PetscCall(GatherChain(diag, off, &diag_, &off_));
  lambda_max_ = 0; // Gershgorin bound of the spectrum
  for (PetscInt i = 0; i < N_; i++) lambda_max_ = std::max(lambda_max_, std::abs(diag_[i]) + std::abs(off_[i]) + (i > 0 ? std::abs(off_[i - 1]) : 0.0));
  T_ = 0; // refactor at the next SetPeriod
  PetscFunctionReturn(0);
}

PetscErrorCode LinearMonodromyPC::SetParametricTerm(const std::vector<PetscReal> &cdiag, const std::vector<PetscReal> &coff,
                                                    const std::vector<PetscReal> &sdiag, const std::vector<PetscReal> &soff, PetscReal weight)
{
  PetscFunctionBeginUser;
  parametric_ = !cdiag.empty();
  pw_ = weight;
  if (parametric_) {
    PetscCall(GatherChain(cdiag, coff, &kcd_, &kco_));
    PetscCall(GatherChain(sdiag, soff, &ksd_, &kso_));
    cu_.resize(N_);
    cv_.resize(N_);
  }
  T_ = 0;
  PetscFunctionReturn(0);
}

// Gaussian elimination with partial pivoting of the tridiagonal K - shift I
// (the algorithm of LAPACK's dgttrf): row i+1 may be swapped into row i, which
// fills a second superdiagonal du2.
void LinearMonodromyPC::TridiagonalLU::Factor(const std::vector<PetscReal> &diag, const std::vector<PetscReal> &off, PetscReal shift)
{
  const size_t n = diag.size();
  d.resize(n);
  for (size_t i = 0; i < n; i++) d[i] = diag[i] - shift;
  dl.assign(off.begin(), off.end() - 1);
  du.assign(off.begin(), off.end() - 1);
  du2.assign(n, 0.0);
  swapped.assign(n, 0);
  for (size_t i = 0; i + 1 < n; i++) {
    if (std::abs(d[i]) >= std::abs(dl[i])) {
      const PetscReal f = d[i] != 0 ? dl[i] / d[i] : 0;
      dl[i] = f;
      d[i + 1] -= f * du[i];
    } else {
      const PetscReal f = d[i] / dl[i];
      d[i] = dl[i];
      dl[i] = f;
      const PetscReal t = du[i];
      du[i] = d[i + 1];
      d[i + 1] = t - f * d[i + 1];
      if (i + 2 < n) {
        du2[i] = du[i + 1];
        du[i + 1] = -f * du[i + 1];
      }
      swapped[i] = 1;
    }
  }
}

// Smallest |pivot| over largest: ~ the distance of the shift to K's nearest eigenvalue, relative.
PetscReal LinearMonodromyPC::TridiagonalLU::PivotRatio() const
{
  PetscReal lo = PETSC_MAX_REAL, hi = 0;
  for (PetscReal p : d) lo = std::min(lo, std::abs(p)), hi = std::max(hi, std::abs(p));
  return hi > 0 ? lo / hi : 0;
}

void LinearMonodromyPC::TridiagonalLU::Solve(PetscReal *b) const
{
  const size_t n = d.size();
  for (size_t i = 0; i + 1 < n; i++) {
    if (!swapped[i]) b[i + 1] -= dl[i] * b[i];
    else {
      const PetscReal t = b[i];
      b[i] = b[i + 1];
      b[i + 1] = t - dl[i] * b[i];
    }
  }
  b[n - 1] /= d[n - 1];
  if (n > 1) b[n - 2] = (b[n - 2] - du[n - 2] * b[n - 1]) / d[n - 2];
  for (size_t i = n - 2; i-- > 0;) b[i] = (b[i] - du[i] * b[i + 1] - du2[i] * b[i + 2]) / d[i];
}

PetscErrorCode LinearMonodromyPC::SetPeriod(PetscReal T)
{
  PetscFunctionBeginUser;
  PetscCheck(T > 0, lat_->Comm(), PETSC_ERR_ARG_OUTOFRANGE, "linear monodromy preconditioner: period %g must be positive", (double)T);
  if (T == T_) PetscFunctionReturn(0);
  T_ = T;
  const PetscReal w1 = 2 * PETSC_PI / T;
  // w_nmax^2 >= 64 lambda_max: the dropped tail terms are below (1/64)^4 of the tail.
  const PetscInt nmax = std::max<PetscInt>(4, (PetscInt)std::ceil(8 * std::sqrt(lambda_max_) / w1));
  lu_.resize(nmax + 1);
  lu_[0].Factor(diag_, off_, 0.0);
  for (PetscInt n = 1; n <= nmax; n++) {
    // A shift on an eigenvalue of K to rounding (the linear period itself, where
    // the branch starts: M_lin - I is singular there) is moved off it by 1e-9
    // relative: the exact inverse does not exist, and Newton moves T off the
    // resonance by the nonlinear frequency shift anyway.
    PetscReal shift = (n * w1) * (n * w1);
    lu_[n].Factor(diag_, off_, shift);
    for (int k = 0; k < 8 && lu_[n].PivotRatio() < 1e-12; k++) {
      shift *= 1 - 1e-9;
      lu_[n].Factor(diag_, off_, shift);
    }
    if (n == 1) shift1_ = shift;
  }
  if (parametric_) PetscCall(FactorRotatingWave());
  // s_j = w1^{-2j} (zeta(2j) - sum_{n<=nmax} n^{-2j}), j = 1..4
  const PetscReal zeta[4] = {std::pow(PETSC_PI, 2) / 6, std::pow(PETSC_PI, 4) / 90, std::pow(PETSC_PI, 6) / 945, std::pow(PETSC_PI, 8) / 9450};
  for (int j = 0; j < 4; j++) {
    PetscReal partial = 0;
    for (PetscInt n = nmax; n >= 1; n--) partial += std::pow((PetscReal)n, -2.0 * (j + 1));
    tail_[j] = (zeta[j] - partial) * std::pow(w1, -2.0 * (j + 1));
  }
  PetscFunctionReturn(0);
}

// B T = T/(2w) [[Ks/2, D - Kc/2], [-(D + Kc/2), -Ks/2]] (header), D = K0 - w^2 with
// lu_[1]'s shift, so that with Kc = Ks = 0 it is exactly the averaged n = 1 term;
// Kc and Ks scaled by the weight (header).
PetscErrorCode LinearMonodromyPC::FactorRotatingWave()
{
  PetscFunctionBeginUser;
  const int n2 = (int)(2 * N_), kl = kBandKl, ku = kBandKu, ld = kBandLd;
  const PetscReal w = 2 * PETSC_PI / T_, scale = T_ / (2 * w);
  band_.assign((size_t)ld * n2, 0.0);
  ipiv_.resize(n2);
  auto set = [&](PetscInt row, PetscInt col, PetscReal v) { band_[(size_t)(kl + ku + row - col) + (size_t)col * ld] = scale * v; };
  for (PetscInt i = 0; i < N_; i++) {
    for (PetscInt j = std::max<PetscInt>(0, i - 1); j <= std::min(N_ - 1, i + 1); j++) {
      const PetscInt b = std::min(i, j); // bond (b, b+1) holds the off-diagonal entries
      const PetscReal k0 = i == j ? diag_[i] - shift1_ : off_[b];
      const PetscReal kc = pw_ * (i == j ? kcd_[i] : kco_[b]), ks = pw_ * (i == j ? ksd_[i] : kso_[b]);
      set(2 * i, 2 * j, ks / 2);
      set(2 * i, 2 * j + 1, k0 - kc / 2);
      set(2 * i + 1, 2 * j, -(k0 + kc / 2));
      set(2 * i + 1, 2 * j + 1, -ks / 2);
    }
  }
  int info;
  dgbtrf_(&n2, &n2, &kl, &ku, band_.data(), &ld, ipiv_.data(), &info);
  PetscCheck(info >= 0, lat_->Comm(), PETSC_ERR_LIB, "LAPACK dgbtrf: argument %d illegal", -info);
  // info > 0: an exact zero pivot (the 1:1 resonance itself). Drop the correction
  // for this period rather than divide by zero; the averaged part stays.
  if (info > 0) {
    PetscCall(PetscInfo(NULL, "-nnm_mf_pc parametric: rotating-wave block singular at pivot %d, correction off for T = %g\n", info, (double)T_));
    band_.clear();
  }
  PetscFunctionReturn(0);
}

// cu_, cv_ = S^-1 [(B T)^-1 - (B0 T)^-1] S [ru; rv], S = diag(I, I/w), whole chain.
void LinearMonodromyPC::ApplyRotatingWave(const PetscReal *ru, const PetscReal *rv)
{
  const int n2 = (int)(2 * N_), kl = kBandKl, ku = kBandKu, ld = kBandLd, one = 1;
  const PetscReal w = 2 * PETSC_PI / T_;
  rhs2_.resize(n2);
  for (PetscInt i = 0; i < N_; i++) {
    rhs2_[2 * i] = ru[i];
    rhs2_[2 * i + 1] = rv[i] / w;
  }
  int info;
  dgbtrs_("N", &n2, &kl, &ku, &one, band_.data(), &ld, ipiv_.data(), rhs2_.data(), &n2, &info, 1);
  // (B0 T)^-1 = (2w/T) [[0, -D^-1], [D^-1, 0]]
  const PetscReal c = 2 * w / T_;
  for (PetscInt i = 0; i < N_; i++) {
    cu_[i] = rv[i] / w;
    cv_[i] = ru[i];
  }
  lu_[1].Solve(cu_.data());
  lu_[1].Solve(cv_.data());
  for (PetscInt i = 0; i < N_; i++) {
    const PetscReal ya = rhs2_[2 * i] + c * cu_[i], yb = rhs2_[2 * i + 1] - c * cv_[i];
    cu_[i] = ya;
    cv_[i] = w * yb;
  }
}

void LinearMonodromyPC::MultK(const PetscReal *x, PetscReal *y) const
{
  for (PetscInt i = 0; i < N_; i++) {
    PetscReal s = diag_[i] * x[i];
    if (i > 0) s += off_[i - 1] * x[i - 1];
    if (i + 1 < N_) s += off_[i] * x[i + 1];
    y[i] = s;
  }
}

// y = g(K) r = (2/T) K^{-1} r + (4/T) [sum_{n=1}^{nmax} (K - w_n^2)^{-1} r - (s1 + K (s2 + K (s3 + K s4))) r]
void LinearMonodromyPC::ApplyG(const PetscReal *r, PetscReal *y)
{
  PetscReal *t = t1_.data(), *h = t2_.data();
  const PetscInt n = N_;
  // tail, by Horner
  for (PetscInt i = 0; i < n; i++) t[i] = tail_[3] * r[i];
  for (int j = 2; j >= 0; j--) {
    MultK(t, h);
    for (PetscInt i = 0; i < n; i++) t[i] = h[i] + tail_[j] * r[i];
  }
  for (PetscInt i = 0; i < n; i++) y[i] = -t[i];
  for (size_t k = 1; k < lu_.size(); k++) {
    std::copy(r, r + n, t);
    lu_[k].Solve(t);
    for (PetscInt i = 0; i < n; i++) y[i] += t[i];
  }
  std::copy(r, r + n, t);
  lu_[0].Solve(t);
  for (PetscInt i = 0; i < n; i++) y[i] = (4 / T_) * y[i] + (2 / T_) * t[i];
}

PetscErrorCode LinearMonodromyPC::Apply(Vec r, Vec x)
{
  const PetscScalar *ra;
  PetscScalar *xa;
  MPI_Comm comm = lat_->Comm();
  const PetscInt m = lat_->OwnedCount(), s = lat_->OwnedStart();
  PetscFunctionBeginUser;
  PetscCheck(T_ > 0, comm, PETSC_ERR_ORDER, "linear monodromy preconditioner: SetPeriod before Apply");
  PetscCall(VecGetArrayRead(r, &ra)); // owned [u | v]
  PetscCallMPI(MPI_Allgatherv(ra, (PetscMPIInt)m, MPIU_REAL, ru_.data(), counts_.data(), displs_.data(), MPIU_REAL, comm));
  PetscCallMPI(MPI_Allgatherv(ra + m, (PetscMPIInt)m, MPIU_REAL, rv_.data(), counts_.data(), displs_.data(), MPIU_REAL, comm));
  PetscCall(VecRestoreArrayRead(r, &ra));
  ApplyG(ru_.data(), gu_.data());
  ApplyG(rv_.data(), gv_.data());
  MultK(gu_.data(), t1_.data()); // K G r_u
  const bool rwa = parametric_ && !band_.empty();
  if (rwa) ApplyRotatingWave(ru_.data(), rv_.data());
  PetscCall(VecGetArray(x, &xa));
  for (PetscInt i = 0; i < m; i++) {
    xa[i] = -0.5 * ru_[s + i] - 0.5 * gv_[s + i] + (rwa ? cu_[s + i] : 0.0);
    xa[m + i] = 0.5 * t1_[s + i] - 0.5 * rv_[s + i] + (rwa ? cv_[s + i] : 0.0);
  }
  PetscCall(VecRestoreArray(x, &xa));
  PetscCall(PetscLogFlops(2.0 * (lu_.size() * 8.0 + 12) * N_));
  PetscFunctionReturn(0);
}

} // namespace nltopo
