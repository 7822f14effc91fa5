#include "bands/bloch.hpp"
#include <cmath>
#include <array>
#include <random>

namespace nltopo {

BandEdges InfiniteBandEdges(const LatticeParams &p)
{
  const PetscReal kh = p.KHat(), s = p.K1() + p.K2(), d = std::abs(p.K1() - p.K2());
  return {std::sqrt(std::max<PetscReal>(kh - s, 0)), std::sqrt(kh - d), std::sqrt(kh + d), std::sqrt(kh + s)};
}

void BlochVector(PetscReal k_intra, PetscReal k_inter, int band, PetscReal q, Complex v[2])
{
  const Complex h = -(k_intra + k_inter * std::exp(Complex(0, -q)));
  const PetscReal a = std::abs(h);
  const Complex ph = a > 0 ? std::conj(h) / a : Complex(1, 0);
  const PetscReal r = 1 / std::sqrt(2.0);
  v[0] = r;
  v[1] = (band == 0 ? -r : r) * ph; // D v = (k_hat -+ |h|) v
}

PetscReal WrapPhase(PetscReal a)
{
  const PetscReal two_pi = 2 * PETSC_PI;
  PetscReal w = std::fmod(a + PETSC_PI / 2, two_pi);
  if (w < 0) w += two_pi;
  w -= PETSC_PI / 2;
  return std::abs(w) < 1e-14 ? 0.0 : w; // no "-0.000000" from round-off of an exact 0
}

PetscReal ZakPhase(PetscReal k_intra, PetscReal k_inter, int band, PetscInt nq, unsigned gauge_seed)
{
  std::mt19937 rng(gauge_seed);
  std::uniform_real_distribution<PetscReal> phase(0, 2 * PETSC_PI);
  const PetscInt n = 2 * nq; // q_n = n pi / nq, n = -nq .. nq-1
  std::vector<std::array<Complex, 2>> u(n);
  for (PetscInt k = 0; k < n; k++) {
    Complex v[2];
    BlochVector(k_intra, k_inter, band, (k - nq) * PETSC_PI / nq, v);
    const Complex g = gauge_seed ? std::exp(Complex(0, phase(rng))) : Complex(1, 0);
    u[k] = {g * v[0], g * v[1]};
  }
  PetscReal theta = 0;
  for (PetscInt k = 0; k < n; k++) {
    const auto &a = u[k], &b = u[(k + 1) % n];
    theta -= std::arg(std::conj(a[0]) * b[0] + std::conj(a[1]) * b[1]); // -Im ln(.)
  }
  return WrapPhase(theta);
}

BlochResult ComputeBloch(const LatticeParams &p, PetscInt nq)
{
  BlochResult r;
  const PetscReal kh = p.KHat(), k1 = p.K1(), k2 = p.K2();
  for (PetscInt k = 0; k < nq; k++) {
    const PetscReal q = -PETSC_PI + 2 * PETSC_PI * k / (nq - 1);
    const PetscReal a = std::abs(k2 + k1 * std::exp(Complex(0, q)));
    r.q.push_back(q);
    r.omega_acoustic.push_back(std::sqrt(std::max<PetscReal>(kh - a, 0)));
    r.omega_optical.push_back(std::sqrt(kh + a));
  }
  for (int band = 0; band < 2; band++) {
    r.zak_left[band] = ZakPhase(k2, k1, band, nq);
    r.zak_right[band] = ZakPhase(k1, k2, band, nq);
  }
  return r;
}

} // namespace nltopo
