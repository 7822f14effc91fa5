#include "stability/growth.hpp"
#include <algorithm>
#include <cmath>

namespace nltopo {

namespace {
// The owned state at every sample (one per period) of a reference run, then
// the local squared distance of another run's samples from them (entries
// selected by keep, the same on both runs).
class TwinDistance : public SampleSink {
public:
  explicit TwinDistance(std::vector<PetscInt> keep) : keep_(std::move(keep)) {}
  PetscErrorCode Sample(PetscReal, Vec z, const EnergyParts &) override
  {
    const PetscScalar *a;
    const size_t n = keep_.size();
    PetscFunctionBeginUser;
    PetscCall(VecGetArrayRead(z, &a));
    if (recording_)
      for (PetscInt i : keep_) ref_.push_back(a[i]);
    else {
      const size_t k = dist_.size();
      PetscReal d = 0;
      if ((k + 1) * n <= ref_.size())
        for (size_t j = 0; j < n; j++) d += (a[keep_[j]] - ref_[k * n + j]) * (a[keep_[j]] - ref_[k * n + j]);
      dist_.push_back(d);
    }
    PetscCall(VecRestoreArrayRead(z, &a));
    PetscFunctionReturn(0);
  }
  void StopRecording() { recording_ = false; }
  std::vector<PetscReal> dist_;

private:
  std::vector<PetscInt> keep_;
  bool recording_ = true;
  std::vector<PetscReal> ref_;
};
} // namespace

PetscErrorCode MeasureGrowth(const EffectList &fx, const SimulationOptions &sim, Vec z, PetscReal T, Vec v, PetscInt periods, PetscReal eps,
                             GrowthMeasurement *out, const PetscInt *window)
{
  const Lattice &lat = fx.Lat();
  const PetscInt xs = lat.OwnedStart(), xm = lat.OwnedCount();
  OwnedVec zp;
  PetscReal nz, nv;
  PetscFunctionBeginUser;
  PetscCall(VecNorm(z, NORM_2, &nz));
  PetscCall(VecNorm(v, NORM_2, &nv));
  PetscCheck(nv > 0, lat.Comm(), PETSC_ERR_ARG_WRONG, "MeasureGrowth: the perturbation direction is zero");
  PetscCall(VecDuplicate(z, zp.out()));
  PetscCall(VecWAXPY(zp, eps * nz / nv, v, z));
  std::vector<PetscInt> keep; // owned entries (state layout: u part, then v part) in the window
  for (PetscInt k = 0; k < xm; k++)
    if (!window || (xs + k >= window[0] && xs + k <= window[1])) keep.push_back(k), keep.push_back(xm + k);
  std::sort(keep.begin(), keep.end());
  SimulationOptions run = sim;
  run.t_final = periods * T;
  run.sample_dt = T;
  TwinDistance twin(keep);
  SimulationResult r;
  PetscCall(Simulate(fx, run, z, &twin, &r));
  twin.StopRecording();
  PetscCall(Simulate(fx, run, zp, &twin, &r));
  std::vector<PetscReal> d(twin.dist_.size());
  PetscCall(MPIU_Allreduce(twin.dist_.data(), d.data(), (PetscMPIInt)d.size(), MPIU_REAL, MPIU_SUM, lat.Comm()));
  PetscReal sx = 0, sy = 0, sxx = 0, sxy = 0;
  PetscInt n = 0;
  for (size_t k = 0; k < d.size() && d[k] > 0 && std::sqrt(d[k]) < 1e-3 * nz; k++, n++) {
    const PetscReal y = 0.5 * std::log(d[k]);
    sx += k, sy += y, sxx += (PetscReal)k * k, sxy += k * y;
  }
  out->fitted = n;
  out->rate = n > 2 ? (n * sxy - sx * sy) / (n * sxx - sx * sx) : NAN;
  PetscFunctionReturn(0);
}

} // namespace nltopo
