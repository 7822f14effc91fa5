#include "stability/region_map.hpp"
#include "core/handle.hpp"
#include "effects/rhs.hpp"
#include "orbits/period_ts.hpp"
#include "timeint/ts_acceleration.hpp"
#include "timeint/ts_symsplit.hpp"
#include <algorithm>
#include <cmath>
#include <cstring>

namespace nltopo {

namespace {

// ---- the orbit: one integration on the whole lattice recording K_T on the region ----

// The orbit's TS (the flow's type and scheme, -nnm_ts_*) whose acceleration
// also records the tangent stiffness of the region's sites and bonds at every
// evaluation: rec[e * 2n + s] = K_T(lo + s, lo + s), rec[e * 2n + n + s] =
// K_T(lo + s, lo + s + 1), e the evaluation (0 at the start, then one after
// every drift: FSAL).
struct Recorder {
  const EffectList *fx;
  Rhs *rhs;
  const LocalizedRegion *reg;
  std::vector<PetscReal> rec, kd, kb;
  PetscInt evals = 0, capacity = 0;
};

PetscErrorCode RecorderRhs(TS, PetscReal t, Vec z, Vec f, void *ctx)
{
  PetscFunctionBeginUser;
  PetscCall(static_cast<Recorder *>(ctx)->rhs->Evaluate(t, z, f));
  PetscFunctionReturn(0);
}

PetscErrorCode RecorderAcceleration(TS, PetscReal t, Vec z, PetscScalar *a, void *ctx)
{
  Recorder &R = *static_cast<Recorder *>(ctx);
  const Lattice &lat = R.fx->Lat();
  const PetscInt xs = lat.OwnedStart(), xm = lat.OwnedCount(), n = R.reg->Sites(), lo = R.reg->lo, hi = R.reg->hi;
  const PetscScalar *u;
  Vec ul;
  PetscFunctionBeginUser;
  PetscCall(R.rhs->Acceleration(t, z, a));
  PetscCheck(R.evals < R.capacity, lat.Comm(), PETSC_ERR_PLIB, "localized Floquet: more accelerations than the scheme's stages (%" PetscInt_FMT ")",
             R.capacity);
  PetscCall(lat.GetGhostedU(z, &ul, &u));
  R.fx->Stiffness(u, R.kd.data() - xs, R.kb.data() + 1 - xs); // kd by owned site, kb by bond xs-1 .. xs+xm-1
  PetscCall(lat.RestoreGhostedU(z, &ul, &u));
  PetscReal *row = R.rec.data() + (size_t)R.evals * 2 * n;
  for (PetscInt i = std::max(lo, xs); i <= std::min(hi, xs + xm - 1); i++) {
    row[i - lo] = R.kd[i - xs];
    if (i < hi) row[n + i - lo] = R.kb[i - xs + 1]; // bond (i, i + 1), owned with site i
  }
  R.evals++;
  PetscFunctionReturn(0);
}

} // namespace

PetscErrorCode RecordStiffness(PeriodicFlow &flow, Vec z0, PetscReal T, const LocalizedRegion &reg, std::vector<PetscReal> *rec, const symsplit::Scheme **sch)
{
  const Lattice &lat = flow.Lat();
  const MPI_Comm comm = lat.Comm();
  Rhs rhs(flow.Effects());
  Recorder R{&flow.Effects(), &rhs, &reg, {}, {}, {}};
  OwnedTS ts;
  OwnedVec z;
  const char *name;
  PetscFunctionBeginUser;
  PetscCheck(flow.Symplectic(), comm, PETSC_ERR_USER,
             "-floquet_mf_which localized integrates the tangent map of the symplectic splitting: it needs -nnm_ts_type symsplit (the default)");
  PetscCall(CreatePeriodTS(comm, TSSYMSPLIT, RecorderRhs, &R, ts.out()));
  PetscCall(TSSetAcceleration(ts, RecorderAcceleration, &R));
  PetscCall(TSSetFromOptions(ts));
  PetscCall(TSSymSplitGetScheme(ts, &name));
  *sch = nullptr;
  for (const auto &s : symsplit::Schemes())
    if (!std::strcmp(s.name, name)) *sch = &s;
  PetscCheck(*sch, comm, PETSC_ERR_PLIB, "localized Floquet: unknown symsplit scheme %s", name);
  const PetscInt n = reg.Sites(), steps = flow.Steps(), stages = (PetscInt)(*sch)->drift.size();
  R.capacity = 1 + steps * stages;
  R.rec.assign((size_t)R.capacity * 2 * n, 0.0);
  R.kd.assign(lat.OwnedCount(), 0.0);
  R.kb.assign(lat.OwnedCount() + 1, 0.0);
  PetscCall(VecDuplicate(z0, z.out()));
  PetscCall(VecCopy(z0, z));
  PetscCall(SolvePeriod(ts, z, T, steps, "localized Floquet orbit"));
  PetscCheck(R.evals == R.capacity, comm, PETSC_ERR_PLIB, "localized Floquet: %" PetscInt_FMT " accelerations, %" PetscInt_FMT " expected", R.evals,
             R.capacity);
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, R.rec.data(), (PetscMPIInt)R.rec.size(), MPIU_REAL, MPI_SUM, comm)); // each entry has one owner
  *rec = std::move(R.rec);
  PetscFunctionReturn(0);
}

namespace {

// ---- the damped region map, column by column ----

// Columns c0 .. c0+m-1 of the damped region map (unit start vectors in region
// layout), site-major q[s * m + j], p[s * m + j]: the splitting's kicks with
// the recorded K_T (rows stride apart), then exp(-c h) on p after every step.
void DampedColumns(const LocalizedRegion &reg, const std::vector<PetscReal> &rec, PetscInt stride, const symsplit::Scheme &sch, PetscInt steps, PetscReal T, PetscInt c0,
                   PetscInt m, std::vector<PetscReal> *q, std::vector<PetscReal> *p)
{
  const PetscInt n = reg.Sites(), stages = (PetscInt)sch.drift.size();
  const PetscReal h = T / steps;
  q->assign((size_t)n * m, 0.0), p->assign((size_t)n * m, 0.0);
  for (PetscInt j = 0; j < m; j++) {
    const PetscInt c = c0 + j;
    if (c < n) (*q)[(size_t)c * m + j] = 1;
    else (*p)[(size_t)(c - n) * m + j] = 1;
  }
  std::vector<PetscReal> fac(n);
  for (PetscInt s = 0; s < n; s++) fac[s] = std::exp(-reg.c[s] * h);
  PetscReal *Q = q->data(), *P = p->data();
  auto kick = [&](PetscInt e, PetscReal bh) {
    const PetscReal *kd = rec.data() + (size_t)e * stride, *kb = kd + n;
    for (PetscInt s = 0; s < n; s++) {
      const PetscReal l = s > 0 ? kb[s - 1] : 0, d = kd[s], r = s < n - 1 ? kb[s] : 0;
      const PetscReal *Ql = s > 0 ? Q + (s - 1) * m : Q, *Qs = Q + s * m, *Qr = s < n - 1 ? Q + (s + 1) * m : Q;
      PetscReal *Ps = P + s * m;
      for (PetscInt j = 0; j < m; j++) Ps[j] -= bh * (l * Ql[j] + d * Qs[j] + r * Qr[j]);
    }
  };
  for (PetscInt st = 0; st < steps; st++) {
    for (PetscInt k = 0; k < stages; k++) {
      kick(st * stages + k, sch.kick[k] * h);
      const PetscReal ch = sch.drift[k] * h;
      for (size_t x = 0; x < q->size(); x++) Q[x] += ch * P[x];
    }
    kick((st + 1) * stages, sch.kick[stages] * h);
    for (PetscInt s = 0; s < n; s++)
      if (fac[s] != 1)
        for (PetscInt j = 0; j < m; j++) P[s * m + j] *= fac[s];
  }
}

} // namespace

PetscErrorCode LinearStiffness(const PeriodicFlow &flow, std::vector<PetscReal> *kd, std::vector<PetscReal> *kb)
{
  const Lattice &lat = flow.Lat();
  const PetscInt N = lat.N(), xs = lat.OwnedStart(), xm = lat.OwnedCount();
  OwnedVec z;
  Vec ul;
  const PetscScalar *u;
  std::vector<PetscReal> d(xm), b(xm + 1);
  PetscFunctionBeginUser;
  PetscCall(lat.CreateStateVector(z.out()));
  PetscCall(VecZeroEntries(z));
  PetscCall(lat.GetGhostedU(z, &ul, &u));
  flow.Effects().Stiffness(u, d.data() - xs, b.data() + 1 - xs); // d by owned site, b by bond xs-1 .. xs+xm-1
  PetscCall(lat.RestoreGhostedU(z, &ul, &u));
  kd->assign(N, 0.0), kb->assign(std::max<PetscInt>(N - 1, 0), 0.0);
  for (PetscInt i = xs; i < xs + xm; i++) {
    (*kd)[i] = d[i - xs];
    if (i < N - 1) (*kb)[i] = b[i - xs + 1]; // bond (i, i + 1), owned with site i
  }
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, kd->data(), (PetscMPIInt)N, MPIU_REAL, MPI_SUM, lat.Comm()));
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, kb->data(), (PetscMPIInt)kb->size(), MPIU_REAL, MPI_SUM, lat.Comm()));
  PetscFunctionReturn(0);
}

PetscErrorCode RegionMapOnRoot(MPI_Comm comm, const LocalizedRegion &reg, const std::vector<PetscReal> &rec, PetscInt stride, const symsplit::Scheme &sch,
                               PetscInt steps, PetscReal T, std::vector<PetscReal> *a)
{
  const PetscInt n = reg.Sites(), n2 = 2 * n;
  PetscMPIInt rank, size;
  std::vector<PetscReal> q, p;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  PetscCallMPI(MPI_Comm_size(comm, &size));
  const PetscInt c0 = n2 * rank / size, c1 = n2 * (rank + 1) / size, m = c1 - c0;
  DampedColumns(reg, rec, stride, sch, steps, T, c0, m, &q, &p);
  PetscCall(PetscLogFlops(10.0 * n * m * steps * (sch.drift.size() + 1)));
  std::vector<PetscReal> mine((size_t)n2 * m); // column-major block
  for (PetscInt j = 0; j < m; j++)
    for (PetscInt s = 0; s < n; s++) mine[(size_t)j * n2 + s] = q[(size_t)s * m + j], mine[(size_t)j * n2 + n + s] = p[(size_t)s * m + j];
  std::vector<int> counts(size), displs(size);
  for (PetscMPIInt r = 0; r < size; r++) counts[r] = (int)(n2 * (n2 * (r + 1) / size - n2 * r / size)), displs[r] = (int)(n2 * (n2 * r / size));
  a->assign(rank == 0 ? (size_t)n2 * n2 : 0, 0.0);
  PetscCallMPI(MPI_Gatherv(mine.data(), (int)mine.size(), MPIU_REAL, a->data(), counts.data(), displs.data(), MPIU_REAL, 0, comm));
  PetscFunctionReturn(0);
}

} // namespace nltopo
