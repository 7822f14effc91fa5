#include "orbits/continuation.hpp"
#include "core/gather.hpp"
#include "core/signals.hpp"
#include "diagnostics/mcr.hpp"
#include <cmath>

namespace nltopo {

PetscErrorCode ContinuationOptionsFromOptions(MPI_Comm comm, ContinuationOptions *o)
{
  PetscFunctionBeginUser;
  PetscOptionsBegin(comm, "cont_", "NNM continuation", NULL);
  PetscCall(PetscOptionsReal("-energy_min", "Energy of the first orbit (near the linear mode)", NULL, o->energy_min, &o->energy_min, NULL));
  PetscCall(PetscOptionsReal("-energy_max", "Stop when the energy exceeds this", NULL, o->energy_max, &o->energy_max, NULL));
  PetscCall(PetscOptionsInt("-max_points", "Stop after this many orbits", NULL, o->max_points, &o->max_points, NULL));
  PetscCall(PetscOptionsReal("-omega_max", "Stop once the frequency exceeds this (0: no limit)", NULL, o->omega_max, &o->omega_max, NULL));
  PetscCall(PetscOptionsReal("-mcr_min",
                             "Stop once the orbit's mode concentration ratio falls below this: the mode has spread into the lattice (0: no limit)",
                             NULL, o->mcr_min, &o->mcr_min, NULL));
  PetscCall(PetscOptionsReal("-max_change", "Largest relative change of the orbit z0 per step", NULL, o->max_change, &o->max_change, NULL));
  PetscCall(PetscOptionsReal("-ds_min", "Step collapse: stop when the step falls below this times ||z0||", NULL, o->ds_min, &o->ds_min, NULL));
  PetscCall(PetscOptionsInt("-newton_target", "Newton iterations per point that the step size aims at", NULL, o->newton_target, &o->newton_target, NULL));
  PetscCall(PetscOptionsReal("-interaction_corr", "Flag a modal interaction when consecutive shapes correlate less than this", NULL,
                             o->interaction_corr, &o->interaction_corr, NULL));
  PetscCall(PetscOptionsBool("-verbose", "Print one line per continuation point", NULL, o->verbose, &o->verbose, NULL));
  PetscOptionsEnd();
  PetscCheck(o->energy_min >= 1e-12 && o->energy_max <= 1e12 && o->energy_min < o->energy_max, comm, PETSC_ERR_USER,
             "-cont_energy_min and -cont_energy_max must satisfy 1e-12 <= min < max <= 1e12, got %g and %g", (double)o->energy_min, (double)o->energy_max);
  PetscCheck(o->max_points >= 1 && o->max_points <= 1000000, comm, PETSC_ERR_USER, "-cont_max_points must lie in [1, 1e6], got %" PetscInt_FMT, o->max_points);
  PetscCheck(o->omega_max >= 0 && o->omega_max <= 1e3, comm, PETSC_ERR_USER, "-cont_omega_max must lie in [0, 1e3] (0: no limit), got %g", (double)o->omega_max);
  PetscCheck(o->ds_min > 0 && o->ds_min < 1, comm, PETSC_ERR_USER, "-cont_ds_min must lie in (0, 1), got %g", (double)o->ds_min);
  PetscCheck(o->newton_target >= 1 && o->newton_target <= 100, comm, PETSC_ERR_USER, "-cont_newton_target must lie in [1, 100], got %" PetscInt_FMT,
             o->newton_target);
  PetscCheck(o->interaction_corr >= 0 && o->interaction_corr <= 1, comm, PETSC_ERR_USER, "-cont_interaction_corr must lie in [0, 1], got %g",
             (double)o->interaction_corr);
  PetscCheck(o->max_change > 0 && o->max_change < 1, comm, PETSC_ERR_USER, "-cont_max_change must lie in (0, 1), got %g", (double)o->max_change);
  PetscCheck(o->mcr_min >= 0 && o->mcr_min < 1, comm, PETSC_ERR_USER, "-cont_mcr_min must lie in [0, 1), got %g", (double)o->mcr_min);
  PetscFunctionReturn(0);
}

namespace {

// Correlation of the displacement parts of two states, and the norm of the first's u.
PetscErrorCode ShapeCorrelation(const Lattice &lat, Vec a, Vec b, PetscReal *corr)
{
  const PetscScalar *x, *y;
  const PetscInt m = lat.OwnedCount();
  PetscReal loc[3] = {0, 0, 0}, g[3];
  PetscFunctionBeginUser;
  PetscCall(VecGetArrayRead(a, &x));
  PetscCall(VecGetArrayRead(b, &y));
  for (PetscInt k = 0; k < m; k++) {
    loc[0] += x[k] * y[k];
    loc[1] += x[k] * x[k];
    loc[2] += y[k] * y[k];
  }
  PetscCall(VecRestoreArrayRead(b, &y));
  PetscCall(VecRestoreArrayRead(a, &x));
  PetscCall(MPIU_Allreduce(loc, g, 3, MPIU_REAL, MPIU_SUM, lat.Comm()));
  *corr = (g[1] > 0 && g[2] > 0) ? std::abs(g[0]) / std::sqrt(g[1] * g[2]) : 0;
  PetscFunctionReturn(0);
}

// The resume state after a point: the tangent t (natural order on rank 0) and ds.
PetscErrorCode StoreNextStep(const Lattice &lat, Shooting &shoot, Vec t, Vec tz, PetscReal ds, Branch *b)
{
  PetscReal dT, dbeta;
  std::vector<PetscReal> row;
  PetscFunctionBeginUser;
  PetscCall(shoot.Unpack(t, tz, &dT, &dbeta));
  PetscCall(AppendStateRow(lat, tz, &row));
  if (!row.empty()) {
    row.push_back(dT);
    row.push_back(dbeta);
  }
  b->next_tangent = std::move(row);
  b->next_ds = ds;
  PetscFunctionReturn(0);
}

// X0 = the first orbit of branch b (z0 rows on rank 0), *far its largest distance
// from the other orbits, and *closed whether its last step passes X0 (PassesFirst's
// test: the branch stopped because the family closed).
PetscErrorCode FirstOrbit(const Lattice &lat, Shooting &shoot, const Branch &b, Vec X0, PetscReal *far, bool *closed)
{
  const PetscInt n2 = 2 * lat.N(), np = (PetscInt)b.energy.size();
  std::vector<PetscReal> row(n2);
  PetscMPIInt rank;
  OwnedVec z;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(lat.Comm(), &rank));
  PetscReal state[2] = {0, 0}; // far, closed
  if (rank == 0) {
    // X_j - X_i over (z0, T, beta)
    auto diff = [&](PetscInt j, PetscInt i, PetscInt k) {
      return k < n2 ? b.z0[j * n2 + k] - b.z0[i * n2 + k] : k == n2 ? b.period[j] - b.period[i] : b.beta[j] - b.beta[i];
    };
    std::copy(b.z0.begin(), b.z0.begin() + n2, row.begin());
    for (PetscInt j = 1; j < np; j++) {
      PetscReal d2 = 0, dd = 0, wd = 0;
      for (PetscInt k = 0; k < n2 + 2; k++) d2 += diff(j, 0, k) * diff(j, 0, k);
      if (j == np - 1 && np >= 3) { // the last step, as PassesFirst sees it
        for (PetscInt k = 0; k < n2 + 2; k++) dd += diff(j, j - 1, k) * diff(j, j - 1, k), wd += diff(0, j - 1, k) * diff(j, j - 1, k);
        PetscReal ww = 0;
        for (PetscInt k = 0; k < n2 + 2; k++) ww += diff(0, j - 1, k) * diff(0, j - 1, k);
        const PetscReal t = dd > 0 ? std::min(std::max(wd / dd, (PetscReal)0), (PetscReal)1) : 0;
        state[1] = dd > 0 && state[0] > 4 * std::sqrt(dd) && ww - 2 * t * wd + t * t * dd <= 0.01 * dd;
      }
      state[0] = std::max(state[0], std::sqrt(d2));
    }
  }
  PetscCallMPI(MPI_Bcast(row.data(), (PetscMPIInt)n2, MPIU_REAL, 0, lat.Comm()));
  PetscCallMPI(MPI_Bcast(state, 2, MPIU_REAL, 0, lat.Comm()));
  *far = state[0], *closed = state[1] != 0;
  PetscCall(lat.CreateStateVector(z.out()));
  PetscCall(StateFromRow(lat, row.data(), z));
  PetscCall(shoot.Pack(z, b.period[0], b.beta[0], X0));
  PetscFunctionReturn(0);
}

// Whether the step d = X - Xprev passes X0 (within a tenth of its length) after the
// branch has been farther than 4 steps from it; *far is then updated with |X - X0|.
// w, d: work vectors.
PetscErrorCode PassesFirst(Vec X0, Vec Xprev, Vec X, Vec w, Vec d, PetscReal *far, bool *closed)
{
  PetscReal dd, wd, ww, dx;
  PetscFunctionBeginUser;
  PetscCall(VecWAXPY(w, -1.0, X0, X));
  PetscCall(VecNorm(w, NORM_2, &dx));
  PetscCall(VecWAXPY(d, -1.0, Xprev, X));
  PetscCall(VecWAXPY(w, -1.0, Xprev, X0));
  PetscCall(VecDot(d, d, &dd));
  PetscCall(VecDot(w, d, &wd));
  PetscCall(VecDot(w, w, &ww));
  const PetscReal t = dd > 0 ? std::min(std::max(wd / dd, (PetscReal)0), (PetscReal)1) : 0; // the point of the step nearest X0
  const PetscReal dist2 = ww - 2 * t * wd + t * t * dd;                                      // |X0 - Xprev - t d|^2
  *closed = dd > 0 && *far > 4 * std::sqrt(dd) && dist2 <= 0.01 * dd;
  *far = std::max(*far, dx);
  PetscFunctionReturn(0);
}

} // namespace

// Appends z in natural [u, v] order to rank 0's row store.
PetscErrorCode AppendStateRow(const Lattice &lat, Vec z, std::vector<PetscReal> *rows)
{
  std::vector<PetscReal> all;
  PetscFunctionBeginUser;
  PetscCall(GatherVec(z, false, &all));
  if (!all.empty()) {
    const PetscInt N = lat.N();
    const size_t off = rows->size();
    rows->resize(off + 2 * N);
    for (PetscInt i = 0; i < N; i++) {
      (*rows)[off + i] = all[lat.StateIndexU(i)];
      (*rows)[off + N + i] = all[lat.StateIndexV(i)];
    }
  }
  PetscFunctionReturn(0);
}

// z from a natural row [u_1..u_N, v_1..v_N] held by every rank.
PetscErrorCode StateFromRow(const Lattice &lat, const PetscReal *row, Vec z)
{
  const PetscInt N = lat.N();
  PetscFunctionBeginUser;
  for (PetscInt i = lat.OwnedStart(); i < lat.OwnedStart() + lat.OwnedCount(); i++) {
    PetscCall(VecSetValue(z, lat.StateIndexU(i), row[i], INSERT_VALUES));
    PetscCall(VecSetValue(z, lat.StateIndexV(i), row[N + i], INSERT_VALUES));
  }
  PetscCall(VecAssemblyBegin(z));
  PetscCall(VecAssemblyEnd(z));
  PetscFunctionReturn(0);
}

// MCR of the displacement part of z (model.md's MCR on u0, the orbit at its section).
PetscErrorCode DisplacementMcr(const Lattice &lat, Vec z, PetscReal *mcr)
{
  Vec u;
  PetscFunctionBeginUser;
  PetscCall(VecGetSubVector(z, lat.PositionIS(), &u));
  PetscCall(Mcr(u, mcr));
  PetscCall(VecRestoreSubVector(z, lat.PositionIS(), &u));
  PetscFunctionReturn(0);
}

PetscErrorCode ContinueBranch(Shooting &shoot, Vec u_guess, PetscReal T_guess, const ContinuationOptions &o, const char *name, Branch *b, PointHook *hook,
                              const Branch *resume)
{
  PeriodicFlow &flow = shoot.Flow();
  const Lattice &lat = flow.Lat();
  MPI_Comm comm = lat.Comm();
  OwnedVec z, zprev, tz, X, Xprev, Xpred, t, tprev;
  PetscReal T, beta, ds;
  PetscInt its;
  bool ok;
  PetscFunctionBeginUser;
  const bool resumed = resume && resume->energy.size() >= 2;
  *b = resumed ? *resume : Branch();
  PetscLogDouble t_begin;
  PetscCall(PetscTime(&t_begin)); // the verbose lines print the elapsed time
  PetscCall(lat.CreateStateVector(z.out()));
  PetscCall(VecDuplicate(z, zprev.out()));
  PetscCall(VecDuplicate(z, tz.out()));
  PetscCall(shoot.CreateUnknowns(X.out()));
  for (OwnedVec *v : {&Xprev, &Xpred, &t, &tprev}) PetscCall(VecDuplicate(X, v->out()));
  PetscInt kry0 = shoot.KrylovIterations();
  PetscReal znorm;

  PetscInt exact = 0; // resume from the stored tangent and step (bit for bit)
  if (resumed) {
    const PetscInt N = lat.N(), np = (PetscInt)b->energy.size();
    std::vector<PetscReal> rows(4 * N);
    PetscMPIInt rank;
    PetscCallMPI(MPI_Comm_rank(comm, &rank));
    PetscInt stored = rank == 0 ? (PetscInt)b->z0.size() : 0;
    PetscCallMPI(MPI_Bcast(&stored, 1, MPIU_INT, 0, comm));
    PetscCheck(stored == np * 2 * N, comm, PETSC_ERR_USER, "-cont_resume: branch %s has %" PetscInt_FMT " z0 values for %" PetscInt_FMT " points of 2N = %" PetscInt_FMT, name,
               stored, np, 2 * N);
    if (rank == 0) std::copy(b->z0.end() - 4 * N, b->z0.end(), rows.begin());
    PetscCallMPI(MPI_Bcast(rows.data(), (PetscMPIInt)(4 * N), MPIU_REAL, 0, comm));
    exact = rank == 0 ? (PetscInt)(b->next_tangent.size() == (size_t)(2 * N + 2)) : 0;
    PetscCallMPI(MPI_Bcast(&exact, 1, MPIU_INT, 0, comm));
  }
  if (exact) {
    // The last orbit as it was recorded (X = its z0, T, beta), the tangent
    // and the step stored with it: the state of the run that wrote the file
    // after that point, so the next steps are the ones it would have taken.
    const PetscInt N = lat.N(), np = (PetscInt)b->energy.size();
    std::vector<PetscReal> row(2 * N + 2), last(2 * N);
    PetscMPIInt rank;
    PetscCallMPI(MPI_Comm_rank(comm, &rank));
    if (rank == 0) {
      std::copy(b->next_tangent.begin(), b->next_tangent.end(), row.begin());
      std::copy(b->z0.end() - 2 * N, b->z0.end(), last.begin());
    }
    PetscCallMPI(MPI_Bcast(row.data(), (PetscMPIInt)(2 * N + 2), MPIU_REAL, 0, comm));
    PetscCallMPI(MPI_Bcast(last.data(), (PetscMPIInt)(2 * N), MPIU_REAL, 0, comm));
    PetscCall(StateFromRow(lat, last.data(), z));
    PetscCall(shoot.Pack(z, b->period.back(), b->beta.back(), X));
    PetscCall(StateFromRow(lat, row.data(), tz));
    PetscCall(shoot.Pack(tz, row[2 * N], row[2 * N + 1], t));
    ds = b->next_ds;
    PetscCallMPI(MPI_Bcast(&ds, 1, MPIU_REAL, 0, comm));
    its = b->newton_its.back();
    PetscCall(shoot.Unpack(X, z, &T, &beta));
    PetscCall(PetscPrintf(comm, "  [%s] resumed after point %" PetscInt_FMT ": E = %.5g, omega = %.8f (stored tangent and step)\n", name, np - 1,
                          (double)b->energy.back(), (double)(2 * PETSC_PI / T)));
  } else if (resumed) {
    // A file without the stored step (written before they were): re-solve the
    // last orbit at its energy, take the family tangent there and a first
    // step as long as the last one.
    const PetscInt N = lat.N(), np = (PetscInt)b->energy.size();
    std::vector<PetscReal> rows(4 * N);
    PetscMPIInt rank;
    PetscCallMPI(MPI_Comm_rank(comm, &rank));
    if (rank == 0) std::copy(b->z0.end() - 4 * N, b->z0.end(), rows.begin());
    PetscCallMPI(MPI_Bcast(rows.data(), (PetscMPIInt)(4 * N), MPIU_REAL, 0, comm));
    PetscCall(StateFromRow(lat, rows.data(), zprev));
    PetscCall(StateFromRow(lat, rows.data() + 2 * N, z));
    const PetscReal dT = b->period[np - 1] - b->period[np - 2];
    PetscCall(shoot.Pack(z, b->period.back(), 0.0, X));
    PetscCall(shoot.SetEnergyConstraint(z, b->energy.back()));
    PetscCall(shoot.Solve(X, &ok, &its));
    PetscCheck(ok, comm, PETSC_ERR_USER,
               "-cont_resume: the last orbit of branch %s (E = %g) is not an orbit of this lattice (Newton failed after %" PetscInt_FMT " iterations): same -lattice_* options as the run that wrote it?",
               name, (double)b->energy.back(), its);
    PetscCall(shoot.Tangent(X, NULL, t));
    PetscCall(VecAXPY(zprev, -1.0, z));
    PetscCall(VecNorm(zprev, NORM_2, &ds));
    ds = std::sqrt(ds * ds + dT * dT);
    PetscCall(shoot.Unpack(X, z, &T, &beta));
    PetscCall(VecNorm(z, NORM_2, &znorm));
    ds = std::min(ds, o.max_change * znorm);
    kry0 = shoot.KrylovIterations();
    PetscCall(PetscPrintf(comm, "  [%s] resumed after point %" PetscInt_FMT ": E = %.5g, omega = %.8f\n", name, np - 1, (double)b->energy.back(),
                          (double)(2 * PETSC_PI / T)));
  } else {
    // Guess (u, v = 0) scaled to the starting energy (linear scaling: E ~ amplitude^2).
    PetscScalar *a;
    const PetscScalar *u;
    EnergyParts e;
    PetscCheck(u_guess, comm, PETSC_ERR_USER, "continuation %s: no starting shape (the linear lattice has no such mode)", name);
    PetscCall(VecZeroEntries(z));
    PetscCall(VecGetArray(z, &a));
    PetscCall(VecGetArrayRead(u_guess, &u));
    PetscCall(PetscArraycpy(a, u, lat.OwnedCount()));
    PetscCall(VecRestoreArrayRead(u_guess, &u));
    PetscCall(VecRestoreArray(z, &a));
    PetscCall(flow.Effects().Energy(z, &e));
    PetscCheck(e.Total() > 0, comm, PETSC_ERR_USER, "continuation %s: the starting shape has zero energy", name);
    PetscCall(VecScale(z, std::sqrt(o.energy_min / e.Total())));
    // The first Newton starts just off the linear period: exactly on it, M - I
    // vanishes on every other linear mode of the same frequency (the left-end
    // edge mode of model.md's "Trap", degenerate with the insulated mode to
    // rounding on long lattices), and the matrix-free Krylov solve breaks down.
    // 1e-7 is below the nonlinear shift at -cont_energy_min's usual values.
    PetscCall(shoot.Pack(z, T_guess * (1 - 1e-7), 0.0, X));
    PetscCall(shoot.SetEnergyConstraint(z, o.energy_min));
    PetscCall(shoot.Solve(X, &ok, &its));
    PetscCheck(ok, comm, PETSC_ERR_NOT_CONVERGED, "continuation %s: no periodic orbit found at -cont_energy_min %g (Newton failed after %" PetscInt_FMT " iterations)",
               name, (double)o.energy_min, its);
    PetscCall(shoot.Tangent(X, NULL, t));
    PetscCall(shoot.Unpack(X, z, &T, &beta));
    PetscCall(VecNorm(z, NORM_2, &znorm));
    ds = o.max_change * znorm;
  }
  bool record = !resumed; // a resumed branch's last point is already recorded
  PetscInt newton_its = its;
  // A closed family (e.g. one born at a period doubling that returns to it) would be
  // followed round and round: it stops once it passes its first orbit X0 again, a step
  // passing within a tenth of its length of X0 after the branch has been farther from
  // X0 than 4 such steps (far: the largest |X - X0| so far).
  OwnedVec X0, w, d;
  for (OwnedVec *v : {&X0, &w, &d}) PetscCall(VecDuplicate(X, v->out()));
  PetscReal far = 0;
  bool have_prev = false;     // Xprev holds the previous point
  bool closed_before = false; // a resumed branch that had stopped there
  if (resumed) PetscCall(FirstOrbit(lat, shoot, *b, X0, &far, &closed_before));
  for (;;) {
    // Record the point.
    EnergyParts e;
    PetscReal mcr, corr = 1;
    PetscCall(shoot.Unpack(X, z, &T, &beta));
    PetscCall(flow.Effects().Energy(z, &e));
    PetscCall(DisplacementMcr(lat, z, &mcr));
    if (!b->energy.empty()) PetscCall(ShapeCorrelation(lat, zprev, z, &corr));
    std::vector<PetscReal> prev_tangent = b->next_tangent; // to drop this point again (below)
    const PetscReal prev_ds = b->next_ds;
    PetscCall(StoreNextStep(lat, shoot, t, tz, ds, b)); // what a resume from this point needs
    if (record) {
      b->energy.push_back(e.Total());
      b->period.push_back(T);
      b->omega.push_back(2 * PETSC_PI / T);
      b->mcr.push_back(mcr);
      b->shape_corr.push_back(corr);
      b->beta.push_back(beta);
      b->newton_its.push_back(newton_its);
      b->krylov_its.push_back(shoot.KrylovIterations() - kry0);
      kry0 = shoot.KrylovIterations();
      PetscCall(AppendStateRow(lat, z, &b->z0));
      if (hook) {
        PetscReal dT, dbeta;
        PetscCall(shoot.Unpack(t, tz, &dT, &dbeta));
        const PetscErrorCode ierr = hook->Point(z, T, beta, tz);
        if (IsInterrupt(ierr)) {
          // A stop signal inside the hook (e.g. the Floquet multipliers of
          // this orbit): the point is dropped, so that the branch, its hook
          // columns and the step stored for a resume stay consistent; a
          // resume recomputes it.
          for (auto *v : {&b->energy, &b->period, &b->omega, &b->mcr, &b->shape_corr, &b->beta}) v->pop_back();
          b->newton_its.pop_back();
          b->krylov_its.pop_back();
          if (b->z0.size() >= (size_t)(2 * lat.N())) b->z0.resize(b->z0.size() - 2 * lat.N()); // rank 0's rows
          b->next_tangent = std::move(prev_tangent);
          b->next_ds = prev_ds;
        }
        PetscCall(ierr);
      }
      const PetscInt k = (PetscInt)b->energy.size() - 1;
      if (corr < o.interaction_corr) {
        b->interactions.push_back(k);
        PetscCall(PetscPrintf(comm, "  [%s] modal interaction at point %" PetscInt_FMT ": shape correlation %.3f, MCR %.3f -> %.3f, omega %.6f, E %.4g\n", name,
                              k, (double)corr, (double)b->mcr[k - 1], (double)mcr, (double)b->omega[k], (double)e.Total()));
      }
      if (o.verbose) {
        PetscLogDouble now;
        PetscCall(PetscTime(&now));
        PetscCall(PetscPrintf(comm, "  [%s] %4" PetscInt_FMT "  E = %-11.5g omega = %.8f  MCR = %.4f  Newton %" PetscInt_FMT "  Krylov %" PetscInt_FMT "  |beta| = %.1e  %.0f s\n",
                              name, k, (double)e.Total(), (double)(2 * PETSC_PI / T), (double)mcr, newton_its, b->krylov_its.back(), (double)std::abs(beta), now - t_begin));
      }
    }
    record = true;
    if (e.Total() >= o.energy_max) {
      b->stop_reason = "reached -cont_energy_max";
      b->reached_max = true;
      break;
    }
    if (o.omega_max > 0 && 2 * PETSC_PI / T >= o.omega_max) {
      b->stop_reason = "reached -cont_omega_max";
      break;
    }
    if (mcr < o.mcr_min) {
      b->stop_reason = "the MCR fell below -cont_mcr_min (the mode has delocalized)";
      break;
    }
    if (b->energy.size() == 1) PetscCall(VecCopy(X, X0));
    {
      bool closed = closed_before && !have_prev;
      if (have_prev) PetscCall(PassesFirst(X0, Xprev, X, w, d, &far, &closed));
      if (closed) {
        b->stop_reason = "the family closed: it returned to its first orbit";
        break;
      }
    }
    if ((PetscInt)b->energy.size() >= o.max_points) {
      b->stop_reason = "reached -cont_max_points";
      break;
    }
    if (e.Total() < 0.1 * o.energy_min) {
      b->stop_reason = "the branch returned below -cont_energy_min";
      break;
    }
    // Next point: predictor + corrector, shrinking ds on failure or too large a change.
    PetscCall(VecCopy(X, Xprev));
    have_prev = true;
    PetscCall(VecCopy(t, tprev));
    PetscCall(VecCopy(z, zprev));
    PetscCall(VecNorm(z, NORM_2, &znorm));
    bool accepted = false, rejected = false;
    while (!accepted) {
      if (ds < o.ds_min * znorm) break;
      PetscCall(VecWAXPY(Xpred, ds, tprev, Xprev));
      PetscCall(VecCopy(Xpred, X));
      PetscCall(shoot.SetArclengthConstraint(zprev, tprev, Xpred));
      PetscCall(shoot.Solve(X, &ok, &its));
      const bool converged = ok;
      if (ok) {
        PetscReal dz;
        PetscCall(shoot.Unpack(X, z, &T, &beta));
        PetscCall(VecAXPY(z, -1.0, zprev));
        PetscCall(VecNorm(z, NORM_2, &dz));
        ok = dz <= o.max_change * znorm * 1.5;
      }
      if (!ok) {
        if (o.verbose)
          PetscCall(PetscPrintf(comm, "  [%s]       step rejected (%s%s after %" PetscInt_FMT " Newton iterations): ds %.3g -> %.3g\n", name,
                                converged ? "orbit changed by more than -cont_max_change" : "Newton failed: ", converged ? "" : shoot.LastReason(), its,
                                (double)ds, (double)(0.5 * ds)));
        ds *= 0.5;
        rejected = true;
        continue;
      }
      accepted = true;
    }
    if (!accepted) {
      b->stop_reason = "step collapse (Newton failed or the orbit changed too fast at every step size): see the last points";
      break;
    }
    newton_its = its;
    PetscCall(shoot.Tangent(X, tprev, t));
    // Step control: Newton effort, then the cap from the largest change of the orbit.
    // No growth right after a rejection: the larger step has just failed, and
    // growing again would alternate failing and accepted steps (inside a dense
    // band the failures are Newton stalling near a resonance, 6-12 wasted
    // iterations each; README "Long lattices").
    if (its <= o.newton_target - 1 && !rejected) ds *= 1.6;
    else if (its > o.newton_target + 1) ds *= 0.6;
    PetscCall(shoot.Unpack(X, z, &T, &beta));
    PetscCall(VecNorm(z, NORM_2, &znorm));
    ds = std::min(ds, o.max_change * znorm);
  }
  PetscCall(PetscPrintf(comm, "  [%s] %zu points, E %.4g .. %.4g, omega %.6f .. %.6f: %s\n", name, b->energy.size(), (double)b->energy.front(),
                        (double)b->energy.back(), (double)b->omega.front(), (double)b->omega.back(), b->stop_reason.c_str()));
  PetscFunctionReturn(0);
}

} // namespace nltopo
