#include "effects/lattice_effects.hpp"
#include "core/option_table.hpp"
#include <algorithm>

namespace nltopo {

namespace {

// Sites xs .. xs+xm-1 of a chain of N, and the interior ones (both neighbours exist).
struct Range {
  PetscInt N, xs, xe, lo, hi;
  explicit Range(const Lattice &lat)
      : N(lat.N()), xs(lat.OwnedStart()), xe(lat.OwnedStart() + lat.OwnedCount()), lo(std::max<PetscInt>(xs, 1)), hi(std::min(xe, N - 1))
  {
  }
};

// a = -K u: a stencil over the springs that assemble K.
class LinearCoupling : public Effect {
public:
  explicit LinearCoupling(const Lattice &lat) : r_(lat), kb_(lat.BondSprings()), kd_(lat.DiagonalSprings()) {}
  const char *Name() const override { return "linear"; }
  const char *LogName() const override { return "RhsLinear"; }
  std::string EnabledBy() const override { return "the lattice (-lattice_k, -lattice_gamma, -lattice_gamma0)"; }
  bool Conservative() const override { return true; }
  PetscLogDouble FlopsPerSite() const override { return 5; }

  bool SetAcceleration(PetscReal, const PetscScalar *u, const PetscScalar *, PetscScalar *a) const override
  {
    const PetscReal *kb = kb_, *kd = kd_;
    for (PetscInt i = r_.lo; i < r_.hi; i++) a[i] = kb[i - 1] * u[i - 1] - kd[i] * u[i] + kb[i] * u[i + 1];
    if (r_.xs == 0) a[0] = -kd[0] * u[0] + (r_.N > 1 ? kb[0] * u[1] : 0.0);
    if (r_.xe == r_.N && r_.N > 1) a[r_.N - 1] = kb[r_.N - 2] * u[r_.N - 2] - kd[r_.N - 1] * u[r_.N - 1];
    return true;
  }
  void AddAcceleration(PetscReal, const PetscScalar *u, const PetscScalar *, PetscScalar *a) const override
  {
    const PetscReal *kb = kb_, *kd = kd_; // kb is 0 outside the chain
    for (PetscInt i = r_.xs; i < r_.xe; i++) a[i] += (i > 0 ? kb[i - 1] * u[i - 1] : 0.0) - kd[i] * u[i] + (i < r_.N - 1 ? kb[i] * u[i + 1] : 0.0);
  }
  void AddStiffness(const PetscScalar *, PetscScalar *kd, PetscScalar *kb) const override
  {
    for (PetscInt i = r_.xs; i < r_.xe; i++) kd[i] += kd_[i];
    for (PetscInt b = std::max<PetscInt>(r_.xs - 1, 0); b < std::min(r_.xe, r_.N - 1); b++) kb[b] -= kb_[b];
  }
  void AddEnergy(const PetscScalar *u, EnergyParts *e) const override
  {
    // 1/2 u.K u: the diagonal, and the two off-diagonal entries of each bond
    // b (b, b+1) on the owner of site b. The sums in vector lanes (a scalar
    // sum is bound by the add latency; the lanes reassociate it).
    const PetscReal *kb = kb_, *kd = kd_;
    const PetscInt bhi = std::min(r_.xe, r_.N - 1);
    PetscReal lin = 0;
#pragma omp simd reduction(+ : lin)
    for (PetscInt i = r_.xs; i < r_.xe; i++) lin += kd[i] * u[i] * u[i];
#pragma omp simd reduction(+ : lin)
    for (PetscInt b = r_.xs; b < bhi; b++) lin -= 2 * kb[b] * u[b] * u[b + 1];
    e->linear += 0.5 * lin;
  }

private:
  Range r_;
  const PetscReal *kb_, *kd_;
};

// Bond b pulls site b back and site b+1 forward with F_b = Gamma_b d^3,
// d = u_b - u_{b+1}, on the stiff bonds (model.md); V_b = Gamma_b d^4 / 4.
class CubicBonds : public Effect {
public:
  explicit CubicBonds(const Lattice &lat) : r_(lat)
  {
    const LatticeParams &p = lat.Params();
    gb_.assign(r_.xe - r_.xs + 1, 0.0); // bonds xs-1 .. xs+xm-1, 0 off the stiff bonds and outside the chain
    for (PetscInt b = std::max<PetscInt>(r_.xs - 1, 0); b < std::min(r_.xe, r_.N - 1); b++)
      if (p.Stiff(b)) gb_[b - r_.xs + 1] = p.Gamma;
    g_ = gb_.data() - r_.xs + 1;
    gamma_ = p.Gamma;
  }
  const char *Name() const override { return "cubic"; }
  const char *LogName() const override { return "RhsCubic"; }
  std::string EnabledBy() const override { return OptionText("-lattice_cubic", gamma_); }
  bool Conservative() const override { return true; }
  PetscLogDouble FlopsPerSite() const override { return 10; }

  void AddAcceleration(PetscReal, const PetscScalar *u, const PetscScalar *, PetscScalar *a) const override
  {
    // a_i += F_{i-1} - F_i. Each bond's force is formed by both its sites, so
    // the loop has no branch and vectorises.
    const PetscReal *gb = g_;
    for (PetscInt i = r_.lo; i < r_.hi; i++) {
      const PetscScalar dl = u[i - 1] - u[i], dr = u[i] - u[i + 1];
      a[i] += gb[i - 1] * dl * dl * dl - gb[i] * dr * dr * dr;
    }
    if (r_.xs == 0 && r_.N > 1) {
      const PetscScalar d = u[0] - u[1];
      a[0] -= gb[0] * d * d * d;
    }
    if (r_.xe == r_.N && r_.N > 1) {
      const PetscScalar d = u[r_.N - 2] - u[r_.N - 1];
      a[r_.N - 1] += gb[r_.N - 2] * d * d * d;
    }
  }
  void AddStiffness(const PetscScalar *u, PetscScalar *kd, PetscScalar *kb) const override
  {
    if (!u) return; // no stiffness at rest
    // Bond b adds s (e_b - e_{b+1})(e_b - e_{b+1})^T, s = 3 Gamma_b d^2.
    for (PetscInt b = std::max<PetscInt>(r_.xs - 1, 0); b < std::min(r_.xe, r_.N - 1); b++) {
      const PetscScalar d = u[b] - u[b + 1], s = 3 * g_[b] * d * d;
      kb[b] -= s;
      if (b >= r_.xs) kd[b] += s;
      if (b + 1 < r_.xe) kd[b + 1] += s;
    }
  }
  void AddEnergy(const PetscScalar *u, EnergyParts *e) const override
  {
    const PetscReal *gb = g_;
    const PetscInt bhi = std::min(r_.xe, r_.N - 1);
    PetscReal quart = 0;
#pragma omp simd reduction(+ : quart)
    for (PetscInt b = r_.xs; b < bhi; b++) {
      const PetscScalar d = u[b] - u[b + 1], d2 = d * d;
      quart += gb[b] * d2 * d2;
    }
    e->quartic += 0.25 * quart;
  }

private:
  Range r_;
  std::vector<PetscReal> gb_;
  const PetscReal *g_;
  PetscReal gamma_;
};

} // namespace

std::unique_ptr<Effect> CreateLinearCoupling(const Lattice &lat) { return std::make_unique<LinearCoupling>(lat); }

// model.md's cubic coefficient Gamma. Its option is -lattice_cubic, not
// "-lattice_Gamma": PETSc option names are case-insensitive, so that name IS
// -lattice_gamma (docs/errors.md, "Option names").
static const auto &kCubicTable = DeclareOptionTable<LatticeParams>("lattice_", "Cubic bonds", [](OptionTable<LatticeParams> &t) {
  t.Real("cubic", &LatticeParams::Gamma, Closed(-1e6, 1e6), "Cubic coefficient Gamma on every stiff bond (0 = linear lattice)");
});

PetscErrorCode CubicBondsOptionsFromOptions(MPI_Comm comm, LatticeParams *p) { return kCubicTable.Read(comm, p); }

std::unique_ptr<Effect> CreateCubicBonds(const Lattice &lat)
{
  if (lat.Params().Gamma == 0.0) return nullptr;
  return std::make_unique<CubicBonds>(lat);
}

} // namespace nltopo
