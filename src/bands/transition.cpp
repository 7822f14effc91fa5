#include "bands/transition.hpp"
#include <petscblaslapack.h>
#include <algorithm>
#include <cmath>

namespace nltopo {

std::vector<PetscReal> GammaGrid(PetscReal lo, PetscReal hi, PetscInt n)
{
  std::vector<PetscReal> g(n);
  for (PetscInt i = 0; i < n; i++) g[i] = (lo * (PetscReal)(n - 1 - i) + hi * (PetscReal)i) / (PetscReal)(n - 1);
  return g;
}

PetscErrorCode FiniteSpectrum(const LatticeParams &p, std::vector<PetscReal> *omega, PetscReal *lambda_min)
{
  std::vector<PetscReal> bonds, diag;
  PetscBLASInt n, ldz = 1, info = 0;
  PetscFunctionBeginUser;
  LatticeSprings(p, &bonds, &diag); // K(i,i) = diag[i], K(i,i+1) = -bonds[i] (Lattice::Setup)
  PetscCall(PetscBLASIntCast(p.N(), &n));
  for (PetscReal &b : bonds) b = -b;
  if (bonds.empty()) bonds.push_back(0); // N = 1: LAPACK still wants an array
  // compz "N": eigenvalues only (LAPACK's dsterf), ascending; z and work are not referenced
  PetscCallBLAS("LAPACKsteqr", LAPACKsteqr_("N", &n, diag.data(), bonds.data(), NULL, &ldz, NULL, &info));
  PetscCheck(info == 0, PETSC_COMM_SELF, PETSC_ERR_LIB, "LAPACK steqr: %s %d (N = %" PetscInt_FMT ", gamma = %g)",
             info < 0 ? "illegal argument" : "no convergence, off-diagonal elements left", (int)std::abs(info), p.N(), (double)p.gamma);
  if (lambda_min) *lambda_min = diag[0];
  omega->resize(diag.size());
  for (size_t i = 0; i < diag.size(); i++) (*omega)[i] = std::sqrt(std::max<PetscReal>(diag[i], 0));
  PetscFunctionReturn(0);
}

bool GapClosed(PetscReal k_intra, PetscReal k_inter)
{
  // |h(pi)| = |k_intra - k_inter|; below a few ulps its sign (the winding) is rounding.
  return std::abs(k_intra - k_inter) <= 8 * PETSC_MACHINE_EPSILON * std::max(std::abs(k_intra), std::abs(k_inter));
}

PetscReal ZakPhaseOrNaN(PetscReal k_intra, PetscReal k_inter, int band, PetscInt nq)
{
  return GapClosed(k_intra, k_inter) ? (PetscReal)NAN : ZakPhase(k_intra, k_inter, band, nq);
}

PetscErrorCode ComputeTransition(const LatticeParams &base, const std::vector<PetscReal> &gamma, PetscInt nq, TransitionResult *r)
{
  PetscFunctionBeginUser;
  const size_t ng = gamma.size();
  r->N = base.N();
  r->gamma = gamma;
  r->omega.assign(ng * (size_t)r->N, 0.0);
  r->zak_left.assign(2 * ng, 0.0);
  r->zak_right.assign(2 * ng, 0.0);
  r->bands_inf.assign(4 * ng, 0.0);
  r->lambda_min.assign(ng, 0.0);
  std::vector<PetscReal> w;
  for (size_t i = 0; i < ng; i++) {
    LatticeParams p = base;
    p.gamma = gamma[i];
    PetscCall(FiniteSpectrum(p, &w, &r->lambda_min[i]));
    std::copy(w.begin(), w.end(), r->omega.begin() + i * (size_t)r->N);
    const PetscReal k1 = p.K1(), k2 = p.K2(); // at gamma = +-1 one of them is 0: no division anywhere (BlochVector guards |h| = 0)
    for (int band = 0; band < 2; band++) {
      r->zak_left[2 * i + band] = ZakPhaseOrNaN(k2, k1, band, nq);
      r->zak_right[2 * i + band] = ZakPhaseOrNaN(k1, k2, band, nq);
    }
    const BandEdges be = InfiniteBandEdges(p);
    const PetscReal e[4] = {be.acoustic_bottom, be.acoustic_top, be.optical_bottom, be.optical_top};
    std::copy(e, e + 4, r->bands_inf.begin() + 4 * i);
  }
  PetscFunctionReturn(0);
}

} // namespace nltopo
