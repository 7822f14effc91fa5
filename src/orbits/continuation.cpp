#include "orbits/continuation.hpp"
#include "core/progress.hpp"
#include "core/gather.hpp"
#include "core/option_table.hpp"
#include "core/signals.hpp"
#include "diagnostics/mcr.hpp"
#include <cmath>

namespace nltopo {

// The -cont_* block of one branch's continuation. How far a branch goes
// (energy, points, frequency, MCR) is its extent: a resume may take it further.
static const auto &kContinuationTable = DeclareOptionTable<ContinuationOptions>("cont_", "NNM continuation", [](OptionTable<ContinuationOptions> &t) {
  using C = ContinuationOptions;
  t.Real("energy_min", &C::energy_min, Closed(1e-12, 1e12), "Energy of the first orbit (near the linear mode)")
      .Real("energy_max", &C::energy_max, Closed(1e-12, 1e12), "Stop when the energy exceeds this", OptionClass::Extent)
      .Int("max_points", &C::max_points, Closed(1, 1000000), "Stop after this many orbits", OptionClass::Extent)
      .Real("omega_max", &C::omega_max, Closed(0, 1e3), "Stop once the frequency exceeds this (0: no limit)", OptionClass::Extent)
      .Real("mcr_min", &C::mcr_min, RightOpen(0, 1),
            "Stop once the orbit's mode concentration ratio falls below this: the mode has spread into the lattice (0: no limit)", OptionClass::Extent)
      .Why("an MCR lies in [1/N, 1]")
      .Real("max_change", &C::max_change, Open(0, 1), "Largest relative change of the orbit z0 per step")
      .Real("ds_min", &C::ds_min, Open(0, 1), "Step collapse: stop when the step falls below this times ||z0||")
      .Int("newton_target", &C::newton_target, Closed(1, 100), "Newton iterations per point that the step size aims at")
      .Real("interaction_corr", &C::interaction_corr, Closed(0, 1), "Flag a modal interaction when consecutive shapes correlate less than this")
      .Why("a correlation lies in [0, 1]")
      .Bool("verbose", &C::verbose, "Print one line per continuation point", OptionClass::Bookkeeping)
      .Real("progress", &C::progress, Closed(0, 1e7),
            "Print a progress line (energy reached of -cont_energy_max, time to go; bifurcation location: segments done, events found) every this "
            "many wall seconds (0: never)",
            OptionClass::Bookkeeping);
});

PetscErrorCode ContinuationOptionsFromOptions(MPI_Comm comm, ContinuationOptions *o)
{
  PetscFunctionBeginUser;
  PetscCall(kContinuationTable.Read(comm, o));
  PetscCheck(o->energy_min < o->energy_max, comm, PETSC_ERR_USER,
             "-cont_energy_min and -cont_energy_max must satisfy 1e-12 <= min < max <= 1e12, got %g and %g", (double)o->energy_min, (double)o->energy_max);
  PetscFunctionReturn(0);
}

namespace {

// Correlation of the displacement parts of two states.
PetscErrorCode ShapeCorrelation(const Lattice &lat, Vec a, Vec b, PetscReal *corr)
{
  DisplacementSums d;
  PetscFunctionBeginUser;
  PetscCall(SumDisplacements(lat, a, b, &d));
  *corr = d.Correlation();
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
  const PetscReal dist2 = ww - 2 * t * wd + t * t * dd;                                     // |X0 - Xprev - t d|^2
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

void Branch::Append(const BranchPoint &p, const std::vector<PetscReal> &z0_row)
{
  for (const PointColumn &c : kPointColumns) {
    if (c.reals) (this->*c.reals).push_back(p.*c.real);
    else (this->*c.ints).push_back(p.*c.integer);
  }
  z0.insert(z0.end(), z0_row.begin(), z0_row.end());
}

void Branch::DropLast(PetscInt n2)
{
  for (const PointColumn &c : kPointColumns) {
    if (c.reals) (this->*c.reals).pop_back();
    else (this->*c.ints).pop_back();
  }
  if (z0.size() >= (size_t)n2) z0.resize(z0.size() - n2); // rank 0's rows
}

PetscErrorCode OrbitPoint(Shooting &shoot, Vec X, Vec z, BranchPoint *p)
{
  EnergyParts e;
  PetscReal T;
  PetscFunctionBeginUser;
  *p = BranchPoint();
  PetscCall(shoot.Unpack(X, z, &T, &p->beta));
  PetscCall(shoot.Flow().Effects().Energy(z, &e));
  PetscCall(DisplacementMcr(shoot.Flow().Lat(), z, &p->mcr));
  p->energy = e.Total();
  p->period = T;
  p->omega = 2 * PETSC_PI / T;
  PetscFunctionReturn(0);
}

PetscErrorCode AppendPoint(const Lattice &lat, Vec z, const BranchPoint &p, Branch *b)
{
  std::vector<PetscReal> row;
  PetscFunctionBeginUser;
  PetscCall(AppendStateRow(lat, z, &row));
  b->Append(p, row);
  PetscFunctionReturn(0);
}

namespace {

// Rank 0's last k orbits of b (z0 rows of 2N), on every rank.
PetscErrorCode LastRows(const Lattice &lat, const Branch &b, PetscInt k, std::vector<PetscReal> *rows)
{
  const PetscInt n = k * 2 * lat.N();
  PetscMPIInt rank;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(lat.Comm(), &rank));
  rows->assign(n, 0);
  if (rank == 0) std::copy(b.z0.end() - n, b.z0.end(), rows->begin());
  PetscCallMPI(MPI_Bcast(rows->data(), (PetscMPIInt)n, MPIU_REAL, 0, lat.Comm()));
  PetscFunctionReturn(0);
}

// One continuation of a family: where it stands (the orbit X, the tangent t,
// the step ds) and its work vectors. Start, then per point: Record, the stop
// rules, Step (predictor and corrector).
class BranchWalk {
public:
  BranchWalk(Shooting &shoot, const ContinuationOptions &o, const char *name, Branch *b, PointHook *hook)
      : shoot_(shoot), lat_(shoot.Flow().Lat()), comm_(lat_.Comm()), o_(o), name_(name), b_(b), hook_(hook)
  {
  }
  PetscErrorCode Run(Vec u_guess, PetscReal T_guess, const Branch *resume);

private:
  PetscErrorCode Start(Vec u_guess, PetscReal T_guess, const Branch *resume, bool *resumed);
  PetscErrorCode StartFromGuess(Vec u_guess, PetscReal T_guess);
  PetscErrorCode ResumeExact();
  PetscErrorCode ResumeResolving();
  PetscErrorCode Record(bool record, BranchPoint *p);
  PetscErrorCode Report(const BranchPoint &p);
  PetscErrorCode StopReason(const BranchPoint &p, const char **why);
  PetscErrorCode Step(bool *accepted);
  PetscErrorCode Correct(bool *ok);

  Shooting &shoot_;
  const Lattice &lat_;
  MPI_Comm comm_;
  const ContinuationOptions &o_;
  const char *name_;
  Branch *b_;
  PointHook *hook_;
  OwnedVec z_, zprev_, tz_, X_, Xprev_, Xpred_, t_, tprev_;
  OwnedVec X0_, w_, d_; // closed-family detection: the first orbit, work vectors
  PetscReal ds_ = 0, znorm_ = 0;
  PetscReal far_ = 0;          // the largest |X - X0| so far
  bool have_prev_ = false;     // Xprev_ holds the previous point
  bool closed_before_ = false; // a resumed branch that had stopped there
  PetscInt its_ = 0, newton_its_ = 0, kry0_ = 0;
  PetscLogDouble t_begin_ = 0; // the verbose lines print the elapsed time
  ProgressMeter progress_;
};

PetscErrorCode BranchWalk::Run(Vec u_guess, PetscReal T_guess, const Branch *resume)
{
  bool resumed;
  PetscFunctionBeginUser;
  PetscCall(Start(u_guess, T_guess, resume, &resumed));
  bool record = !resumed; // a resumed branch's last point is already recorded
  newton_its_ = its_;
  for (;;) {
    BranchPoint p;
    const char *why = nullptr;
    PetscCall(Record(record, &p));
    record = true;
    PetscCall(StopReason(p, &why));
    if (!why) {
      bool accepted;
      PetscCall(Step(&accepted));
      if (!accepted) why = "step collapse (Newton failed or the orbit changed too fast at every step size): see the last points";
    }
    if (why) {
      b_->stop_reason = why;
      break;
    }
  }
  PetscCall(PetscPrintf(comm_, "  [%s] %zu points, E %.4g .. %.4g, omega %.6f .. %.6f: %s\n", name_, b_->energy.size(), (double)b_->energy.front(),
                        (double)b_->energy.back(), (double)b_->omega.front(), (double)b_->omega.back(), b_->stop_reason.c_str()));
  PetscFunctionReturn(0);
}

// The three starts: from the guess, or from a resume branch's last orbit with
// its stored tangent and step (exact) or re-solved (files without them).
PetscErrorCode BranchWalk::Start(Vec u_guess, PetscReal T_guess, const Branch *resume, bool *resumed)
{
  PetscFunctionBeginUser;
  *resumed = resume && resume->energy.size() >= 2;
  *b_ = *resumed ? *resume : Branch();
  PetscCall(PetscTime(&t_begin_));
  progress_.Start(comm_, o_.progress);
  PetscCall(lat_.CreateStateVector(z_.out()));
  for (OwnedVec *v : {&zprev_, &tz_}) PetscCall(VecDuplicate(z_, v->out()));
  PetscCall(shoot_.CreateUnknowns(X_.out()));
  for (OwnedVec *v : {&Xprev_, &Xpred_, &t_, &tprev_, &X0_, &w_, &d_}) PetscCall(VecDuplicate(X_, v->out()));
  kry0_ = shoot_.KrylovIterations();
  if (!*resumed) {
    PetscCall(StartFromGuess(u_guess, T_guess));
    PetscFunctionReturn(0);
  }
  const PetscInt n2 = 2 * lat_.N(), np = (PetscInt)b_->energy.size();
  PetscMPIInt rank;
  PetscCallMPI(MPI_Comm_rank(comm_, &rank));
  PetscInt state[2] = {rank == 0 ? (PetscInt)b_->z0.size() : 0, rank == 0 && b_->next_tangent.size() == (size_t)(n2 + 2)}; // stored, exact
  PetscCallMPI(MPI_Bcast(state, 2, MPIU_INT, 0, comm_));
  PetscCheck(state[0] == np * n2, comm_, PETSC_ERR_USER,
             "-cont_resume: branch %s has %" PetscInt_FMT " z0 values for %" PetscInt_FMT " points of 2N = %" PetscInt_FMT, name_, state[0], np, n2);
  if (state[1]) PetscCall(ResumeExact());
  else PetscCall(ResumeResolving());
  // A closed family (e.g. one born at a period doubling that returns to it)
  // stops once it passes its first orbit again (StopReason).
  PetscCall(FirstOrbit(lat_, shoot_, *b_, X0_, &far_, &closed_before_));
  PetscFunctionReturn(0);
}

PetscErrorCode BranchWalk::StartFromGuess(Vec u_guess, PetscReal T_guess)
{
  PetscScalar *a;
  const PetscScalar *u;
  EnergyParts e;
  PetscReal T, beta;
  bool ok;
  PetscFunctionBeginUser;
  // Guess (u, v = 0) scaled to the starting energy (linear scaling: E ~ amplitude^2).
  PetscCheck(u_guess, comm_, PETSC_ERR_USER, "continuation %s: no starting shape (the linear lattice has no such mode)", name_);
  PetscCall(VecZeroEntries(z_));
  PetscCall(VecGetArray(z_, &a));
  PetscCall(VecGetArrayRead(u_guess, &u));
  PetscCall(PetscArraycpy(a, u, lat_.OwnedCount()));
  PetscCall(VecRestoreArrayRead(u_guess, &u));
  PetscCall(VecRestoreArray(z_, &a));
  PetscCall(shoot_.Flow().Effects().Energy(z_, &e));
  PetscCheck(e.Total() > 0, comm_, PETSC_ERR_USER, "continuation %s: the starting shape has zero energy", name_);
  PetscCall(VecScale(z_, std::sqrt(o_.energy_min / e.Total())));
  // The first Newton starts just off the linear period: exactly on it, M - I
  // vanishes on every other linear mode of the same frequency (the left-end
  // edge mode of model.md's "Trap", degenerate with the insulated mode to
  // rounding on long lattices), and the matrix-free Krylov solve breaks down.
  // 1e-7 is below the nonlinear shift at -cont_energy_min's usual values.
  PetscCall(shoot_.Pack(z_, T_guess * (1 - 1e-7), 0.0, X_));
  PetscCall(shoot_.SetEnergyConstraint(z_, o_.energy_min));
  PetscCall(shoot_.Solve(X_, &ok, &its_));
  PetscCheck(ok, comm_, PETSC_ERR_NOT_CONVERGED,
             "continuation %s: no periodic orbit found at -cont_energy_min %g (Newton failed after %" PetscInt_FMT " iterations)", name_, (double)o_.energy_min,
             its_);
  PetscCall(shoot_.Tangent(X_, NULL, t_));
  PetscCall(shoot_.Unpack(X_, z_, &T, &beta));
  PetscCall(VecNorm(z_, NORM_2, &znorm_));
  ds_ = o_.max_change * znorm_;
  PetscFunctionReturn(0);
}

// The last orbit as it was recorded (X = its z0, T, beta), the tangent and the
// step stored with it: the state of the run that wrote the file after that
// point, so the next steps are the ones it would have taken.
PetscErrorCode BranchWalk::ResumeExact()
{
  const PetscInt n2 = 2 * lat_.N(), np = (PetscInt)b_->energy.size();
  std::vector<PetscReal> tangent, last;
  PetscMPIInt rank;
  PetscReal T, beta;
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm_, &rank));
  tangent.assign(n2 + 2, 0);
  if (rank == 0) tangent = b_->next_tangent;
  PetscCallMPI(MPI_Bcast(tangent.data(), (PetscMPIInt)(n2 + 2), MPIU_REAL, 0, comm_));
  PetscCall(LastRows(lat_, *b_, 1, &last));
  PetscCall(StateFromRow(lat_, last.data(), z_));
  PetscCall(shoot_.Pack(z_, b_->period.back(), b_->beta.back(), X_));
  PetscCall(StateFromRow(lat_, tangent.data(), tz_));
  PetscCall(shoot_.Pack(tz_, tangent[n2], tangent[n2 + 1], t_));
  ds_ = b_->next_ds;
  PetscCallMPI(MPI_Bcast(&ds_, 1, MPIU_REAL, 0, comm_));
  its_ = b_->newton_its.back();
  PetscCall(shoot_.Unpack(X_, z_, &T, &beta));
  PetscCall(PetscPrintf(comm_, "  [%s] resumed after point %" PetscInt_FMT ": E = %.5g, omega = %.8f (stored tangent and step)\n", name_, np - 1,
                        (double)b_->energy.back(), (double)(2 * PETSC_PI / T)));
  PetscFunctionReturn(0);
}

// A file without the stored step (written before they were): re-solve the
// last orbit at its energy, take the family tangent there and a first step as
// long as the last one.
PetscErrorCode BranchWalk::ResumeResolving()
{
  const PetscInt n2 = 2 * lat_.N(), np = (PetscInt)b_->energy.size();
  std::vector<PetscReal> rows;
  PetscReal T, beta;
  bool ok;
  PetscFunctionBeginUser;
  PetscCall(LastRows(lat_, *b_, 2, &rows));
  PetscCall(StateFromRow(lat_, rows.data(), zprev_));
  PetscCall(StateFromRow(lat_, rows.data() + n2, z_));
  const PetscReal dT = b_->period[np - 1] - b_->period[np - 2];
  PetscCall(shoot_.Pack(z_, b_->period.back(), 0.0, X_));
  PetscCall(shoot_.SetEnergyConstraint(z_, b_->energy.back()));
  PetscCall(shoot_.Solve(X_, &ok, &its_));
  PetscCheck(ok, comm_, PETSC_ERR_USER,
             "-cont_resume: the last orbit of branch %s (E = %g) is not an orbit of this lattice (Newton failed after %" PetscInt_FMT
             " iterations): same -lattice_* options as the run that wrote it?",
             name_, (double)b_->energy.back(), its_);
  PetscCall(shoot_.Tangent(X_, NULL, t_));
  PetscCall(VecAXPY(zprev_, -1.0, z_));
  PetscCall(VecNorm(zprev_, NORM_2, &ds_));
  ds_ = std::sqrt(ds_ * ds_ + dT * dT);
  PetscCall(shoot_.Unpack(X_, z_, &T, &beta));
  PetscCall(VecNorm(z_, NORM_2, &znorm_));
  ds_ = std::min(ds_, o_.max_change * znorm_);
  kry0_ = shoot_.KrylovIterations();
  PetscCall(PetscPrintf(comm_, "  [%s] resumed after point %" PetscInt_FMT ": E = %.5g, omega = %.8f\n", name_, np - 1, (double)b_->energy.back(),
                        (double)(2 * PETSC_PI / T)));
  PetscFunctionReturn(0);
}

// The point at X (z <- its state) and the step a resume from it needs; with
// `record` (not for a resumed branch's last point, recorded already) appended
// to the branch and passed to the hook.
PetscErrorCode BranchWalk::Record(bool record, BranchPoint *p)
{
  PetscFunctionBeginUser;
  PetscCall(OrbitPoint(shoot_, X_, z_, p));
  const std::vector<PetscReal> prev_tangent = b_->next_tangent; // to drop this point again (below)
  const PetscReal prev_ds = b_->next_ds;
  PetscCall(StoreNextStep(lat_, shoot_, t_, tz_, ds_, b_)); // what a resume from this point needs (tz_ <- the tangent's state part)
  if (!record) PetscFunctionReturn(0);
  if (!b_->energy.empty()) PetscCall(ShapeCorrelation(lat_, zprev_, z_, &p->shape_corr));
  p->newton_its = newton_its_;
  p->krylov_its = shoot_.KrylovIterations() - kry0_;
  kry0_ = shoot_.KrylovIterations();
  PetscCall(AppendPoint(lat_, z_, *p, b_));
  if (hook_) {
    const PetscErrorCode ierr = hook_->Point(z_, p->period, p->beta, tz_);
    if (IsInterrupt(ierr)) {
      // A stop signal inside the hook (e.g. the Floquet multipliers of this
      // orbit): the point is dropped, so that the branch, its hook columns and
      // the step stored for a resume stay consistent; a resume recomputes it.
      b_->DropLast(2 * lat_.N());
      b_->next_tangent = prev_tangent;
      b_->next_ds = prev_ds;
    }
    PetscCall(ierr);
  }
  PetscCall(Report(*p));
  PetscFunctionReturn(0);
}

// A modal interaction (the shape correlation dropped), and the verbose line.
PetscErrorCode BranchWalk::Report(const BranchPoint &p)
{
  const PetscInt k = (PetscInt)b_->energy.size() - 1;
  PetscFunctionBeginUser;
  if (p.shape_corr < o_.interaction_corr) {
    b_->interactions.push_back(k);
    PetscCall(PetscPrintf(comm_, "  [%s] modal interaction at point %" PetscInt_FMT ": shape correlation %.3f, MCR %.3f -> %.3f, omega %.6f, E %.4g\n", name_,
                          k, (double)p.shape_corr, (double)b_->mcr[k - 1], (double)p.mcr, (double)p.omega, (double)p.energy));
  }
  if (b_->energy.size() > 1) { // how far towards -cont_energy_max, on a log scale from the first orbit (energies span decades)
    char what[160];
    const double e0 = b_->energy.front(), f = std::log(p.energy / e0) / std::log(o_.energy_max / e0);
    PetscCall(PetscSNPrintf(what, sizeof what, "progress: point %" PetscInt_FMT ", E %.4g of -cont_energy_max %.4g (%.0f%% on a log scale)", k,
                            (double)p.energy, (double)o_.energy_max, 100 * std::max(0.0, std::min(1.0, f))));
    PetscCall(progress_.Report(name_, what, f));
  }
  if (o_.verbose) {
    PetscLogDouble now;
    PetscCall(PetscTime(&now));
    PetscCall(PetscPrintf(
        comm_, "  [%s] %4" PetscInt_FMT "  E = %-11.5g omega = %.8f  MCR = %.4f  Newton %" PetscInt_FMT "  Krylov %" PetscInt_FMT "  |beta| = %.1e  %.0f s\n",
        name_, k, (double)p.energy, (double)p.omega, (double)p.mcr, p.newton_its, p.krylov_its, (double)std::abs(p.beta), now - t_begin_));
  }
  PetscFunctionReturn(0);
}

// The stop rules after point p, in order (*why: the stop reason, or null to go
// on); the last, the step collapse, is Step's.
PetscErrorCode BranchWalk::StopReason(const BranchPoint &p, const char **why)
{
  PetscFunctionBeginUser;
  *why = nullptr;
  if (!std::isfinite(p.energy) || !std::isfinite(p.period) || !std::isfinite(p.mcr)) { // no solve gives one: a resume state that is not finite
    *why = "the orbit is not finite (E, T or its MCR): the branch cannot go on from it";
    PetscFunctionReturn(0);
  }
  if (p.energy >= o_.energy_max) {
    *why = "reached -cont_energy_max";
    b_->reached_max = true;
    PetscFunctionReturn(0);
  }
  if (o_.omega_max > 0 && p.omega >= o_.omega_max) *why = "reached -cont_omega_max";
  else if (p.mcr < o_.mcr_min) *why = "the MCR fell below -cont_mcr_min (the mode has delocalized)";
  if (*why) PetscFunctionReturn(0);
  // A closed family would be followed round and round: it stops once a step
  // passes within a tenth of its length of the first orbit X0, after the
  // branch has been farther from X0 than 4 such steps.
  if (b_->energy.size() == 1) PetscCall(VecCopy(X_, X0_));
  bool closed = closed_before_ && !have_prev_;
  if (have_prev_) PetscCall(PassesFirst(X0_, Xprev_, X_, w_, d_, &far_, &closed));
  if (closed) *why = "the family closed: it returned to its first orbit";
  else if ((PetscInt)b_->energy.size() >= o_.max_points) *why = "reached -cont_max_points";
  else if (p.energy < 0.1 * o_.energy_min) *why = "the branch returned below -cont_energy_min";
  PetscFunctionReturn(0);
}

// The next point: predictor and corrector, halving ds on failure or too large
// a change until it falls below -cont_ds_min (*accepted false); then the
// tangent there and the next step length.
PetscErrorCode BranchWalk::Step(bool *accepted)
{
  PetscReal T, beta;
  PetscFunctionBeginUser;
  PetscCall(VecCopy(X_, Xprev_));
  have_prev_ = true;
  PetscCall(VecCopy(t_, tprev_));
  PetscCall(VecCopy(z_, zprev_));
  PetscCall(VecNorm(z_, NORM_2, &znorm_));
  bool rejected = false;
  *accepted = false;
  // The collapse test holds for a step that is not a positive finite number
  // too (a NaN orbit has a NaN norm): halving it would never end.
  auto collapsed = [&]() { return !(std::isfinite(ds_) && std::isfinite(znorm_) && ds_ > 0 && ds_ >= o_.ds_min * znorm_); };
  while (!*accepted && !collapsed()) {
    PetscCall(Correct(accepted));
    if (*accepted) break;
    ds_ *= 0.5;
    rejected = true;
  }
  if (!*accepted) PetscFunctionReturn(0);
  newton_its_ = its_;
  PetscCall(shoot_.Tangent(X_, tprev_, t_));
  // Step control: Newton effort, then the cap from the largest change of the orbit.
  // No growth right after a rejection: the larger step has just failed, and
  // growing again would alternate failing and accepted steps (inside a dense
  // band the failures are Newton stalling near a resonance, 6-12 wasted
  // iterations each; docs/long-lattices.md).
  if (its_ <= o_.newton_target - 1 && !rejected) ds_ *= 1.6;
  else if (its_ > o_.newton_target + 1) ds_ *= 0.6;
  PetscCall(shoot_.Unpack(X_, z_, &T, &beta));
  PetscCall(VecNorm(z_, NORM_2, &znorm_));
  ds_ = std::min(ds_, o_.max_change * znorm_);
  PetscFunctionReturn(0);
}

// One corrector solve from the predictor Xprev + ds tprev with the arclength
// constraint: *ok when Newton converged and the orbit changed by at most
// -cont_max_change (with a margin).
PetscErrorCode BranchWalk::Correct(bool *ok)
{
  PetscReal T, beta;
  PetscFunctionBeginUser;
  PetscCall(VecWAXPY(Xpred_, ds_, tprev_, Xprev_));
  PetscCall(VecCopy(Xpred_, X_));
  PetscCall(shoot_.SetArclengthConstraint(zprev_, tprev_, Xpred_));
  PetscCall(shoot_.Solve(X_, ok, &its_));
  const bool converged = *ok;
  if (converged) {
    PetscReal dz;
    PetscCall(shoot_.Unpack(X_, z_, &T, &beta));
    PetscCall(VecAXPY(z_, -1.0, zprev_));
    PetscCall(VecNorm(z_, NORM_2, &dz));
    *ok = dz <= o_.max_change * znorm_ * 1.5;
  }
  if (!*ok && o_.verbose)
    PetscCall(PetscPrintf(comm_, "  [%s]       step rejected (%s%s after %" PetscInt_FMT " Newton iterations): ds %.3g -> %.3g\n", name_,
                          converged ? "orbit changed by more than -cont_max_change" : "Newton failed: ", converged ? "" : shoot_.LastReason(), its_,
                          (double)ds_, (double)(0.5 * ds_)));
  PetscFunctionReturn(0);
}

} // namespace

PetscErrorCode ContinueBranch(Shooting &shoot, Vec u_guess, PetscReal T_guess, const ContinuationOptions &o, const char *name, Branch *b, PointHook *hook,
                              const Branch *resume)
{
  PetscFunctionBeginUser;
  BranchWalk walk(shoot, o, name, b, hook);
  PetscCall(walk.Run(u_guess, T_guess, resume));
  PetscFunctionReturn(0);
}

} // namespace nltopo
