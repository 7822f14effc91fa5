// -study continuation: NNM branches from linear modes by pseudo-arclength
// continuation of periodic orbits (orbits/); /continuation/<branch> of outputs.md.
#include "studies/nnm_setup.hpp"
#include "core/gather.hpp"
#include "core/log.hpp"
#include "core/options_audit.hpp"
#include "core/signals.hpp"
#include "io/input.hpp"
#include "io/output.hpp"
#include "io/run_options.hpp"
#include "io/schema.hpp"
#include "orbits/continuation.hpp"
#include "stability/bifurcation_locator.hpp"
#include "stability/branch_switch.hpp"
#include "stability/codim2.hpp"
#include "stability/floquet_hooks.hpp"
#include "studies/checkpoint_hook.hpp"
#include "studies/continuation_choices.hpp"
#include "studies/continuation_record.hpp"
#include "studies/event_orbit.hpp"
#include "studies/registry.hpp"
#include "studies/study.hpp"
#include <cmath>
#include <memory>

namespace nltopo {

namespace {

// The branch being continued, live: what a checkpoint or an interrupt writes
// of it, and the counters its cost is measured from.
struct LiveBranch {
  std::string label, parent; // parent: the branch point or period doubling a -cont_switch branch starts from
  PetscReal omega = 0;
  Branch b;
  PetscInt j0 = 0, r0 = 0, p0 = 0, k0 = 0;
  PetscLogDouble b0 = 0;
  PetscInt period_multiple = 1; // 2: the family born at a period doubling (its orbits last two of the parent's periods)
};

// -cont_resume: a branch as the earlier output holds it.
struct Resume {
  std::string label;
  PetscReal omega = 0;
  Branch b;
  FloquetColumns f;
  bool found = false;
};

class ContinuationStudy : public Study {
protected:
  PetscErrorCode ReadOptions() override
  {
    PetscFunctionBeginUser;
    PetscCall(nnm_.ReadOptions(comm_));
    PetscCall(ReadStudyChoices(comm_, &ch_));
    // declared even without -floquet: they belong to this study
    if (declaring_ || ch_.floquet) PetscCall(FloquetOptionsFromOptions(comm_, &flo_));
    if (declaring_ || (ch_.floquet && ch_.floquet_mf)) PetscCall(FloquetMfOptionsFromOptions(comm_, &fmo_));
    fk_ = !ch_.floquet ? FloquetKind::None : ch_.floquet_mf ? FloquetKind::MatrixFree : FloquetKind::Dense;
    PetscCall(BifurcationOptionsFromOptions(comm_, (PetscBool)(fk_ == FloquetKind::Dense), &bo_));
    PetscCall(SwitchOptionsFromOptions(
        comm_, !declaring_, [&](const std::string &b) { return AmongBranches(b); }, &switches_, &switch_step_));
    PetscCheck(switches_.empty() || declaring_ || bo_.enabled, comm_, PETSC_ERR_USER,
               "-cont_switch needs -cont_bifurcations (on with -floquet): the branch points and period doublings are its events");
    PetscCall(Codim2OptionsFromOptions(comm_, &c2o_, &c2spec_));
    if (!declaring_ && c2spec_.Given()) PetscCall(CheckCodim2());
    if (!declaring_ && ch_.resume)
      PetscCall(CheckResumeOptions(comm_, ch_.resume_file, name_, "-cont_resume")); // the same physics and numerics, or one line naming the first difference
    PetscFunctionReturn(0);
  }
  PetscErrorCode DeclareSolvers(MPI_Comm comm) override
  {
    PetscFunctionBeginUser;
    PetscCall(nnm_.DeclareSolvers(comm));
    PetscCall(DeclareEPS(comm, "floquet_"));
    PetscCall(DeclareEPS(comm, "floquet_mf_"));
    PetscFunctionReturn(0);
  }
  PetscErrorCode CheckResources() override
  {
    PetscFunctionBeginUser;
    PetscCall(nnm_.CheckResources(comm_));
    if (fk_ == FloquetKind::MatrixFree) PetscCall(CheckDenseMonodromyMemory(comm_, nnm_.lp.N(), fmo_));
    PetscFunctionReturn(0);
  }
  // -cont_resume of the -output file itself, or of its partial output, replaces it (no -output_overwrite needed).
  PetscErrorCode OutputPath(std::string *path) override
  {
    PetscFunctionBeginUser;
    PetscCall(OutputPathFromOptions(
        comm_, name_, path, [&](const std::string &p) { return ch_.resume && (SameFile(p, ch_.resume_file) || SameFile(PartialPath(p), ch_.resume_file)); },
        "-cont_resume {}"));
    PetscFunctionReturn(0);
  }
  PetscErrorCode Build() override
  {
    PetscFunctionBeginUser;
    PetscCall(nnm_.Build(comm_, "-study continuation"));
    PetscCall(CheckDistinctBranches(nnm_.lat, nnm_.modes, ch_)); // a branch listed twice is refused before any is continued
    PetscCall(DMCreateGlobalVector(nnm_.lat.SiteDM(), u_.out()));
    hook_ = std::make_unique<FloquetHook>(nnm_.flow, flo_);
    mf_hook_ = std::make_unique<FloquetMfHook>(nnm_.flow, flo_, fmo_);
    if (bo_.enabled) PetscCall(locator_.Setup(nnm_.shoot, flo_, bo_));
    locator_.SetProgress(nnm_.co.progress);
    n2_ = 2 * nnm_.lat.N();
    if (fk_ != FloquetKind::None) PetscCall(KreinSpectrumSetup(nnm_.lat, &krein_)); // the Krein resonance map's linear frequencies (O(N), once)
    PetscFunctionReturn(0);
  }
  PetscErrorCode Solve() override
  {
    PetscFunctionBeginUser;
    PetscCall(PetscPrintf(comm_, "nltopo continuation: N = %" PetscInt_FMT ", %" PetscInt_FMT " branch(es), E %g .. %g, Jacobian %s\n", nnm_.lat.N(), ch_.nb,
                          (double)nnm_.co.energy_min, (double)nnm_.co.energy_max, nnm_.so.jacobian == ShootingJacobian::Dense ? "dense" : "mf"));
    if (fk_ == FloquetKind::MatrixFree) PetscCall(mf_hook_->Announce());
    // -cont_resume: every branch read before the first checkpoint may replace the file
    resumes_.resize(ch_.nb);
    for (PetscInt k = 0; k < ch_.nb && ch_.resume; k++) {
      PetscReal omega;
      std::string label;
      PetscCall(BranchStart(nnm_.lat, nnm_.modes, ch_.names[k], u_, &omega, &label));
      resumes_[k].label = label, resumes_[k].omega = omega;
      PetscCall(ReadResume(comm_, ch_.resume_file, label, fk_, n2_, fmo_.nev, &resumes_[k].b, &resumes_[k].f, &resumes_[k].found, mf_hook_->Route()));
    }
    for (PetscInt k = 0; k < ch_.nb; k++) PetscCall(ContinueOne(k));
    PetscCall(WarnUnusedSwitches(comm_, switches_));
    PetscFunctionReturn(0);
  }
  PetscErrorCode Write(PetscViewer v) override
  {
    PetscFunctionBeginUser;
    PetscCall(WriteBandEdges(v, "/continuation", InfiniteBandEdges(nnm_.lat.Params())));
    for (const BranchRecord &r : done_) PetscCall(WriteRecord(v, r, fk_, n2_, fmo_.nev));
    PetscFunctionReturn(0);
  }

private:
  // Whether branch is one of -cont_branch (by its name or its label, k or mode<k>).
  bool AmongBranches(const std::string &branch) const
  {
    for (PetscInt k = 0; k < ch_.nb; k++)
      if (SwitchNames(branch, ch_.names[k])) return true;
    return false;
  }
  PointHook *FloquetPointHook()
  {
    return fk_ == FloquetKind::None ? nullptr : fk_ == FloquetKind::MatrixFree ? static_cast<PointHook *>(mf_hook_.get()) : hook_.get();
  }
  // The record of a branch from its live data (also mid-branch, for a checkpoint).
  // (b by value: the final record moves the branch in, a checkpoint copies it).
  BranchRecord Snapshot(const LiveBranch &cur, Branch b) const
  {
    const Shooting &shoot = nnm_.shoot;
    BranchRecord r;
    PetscLogDouble now;
    PetscTime(&now);
    r.label = cur.label, r.parent = cur.parent, r.omega = cur.omega, r.b = std::move(b), r.seconds = now - cur.b0, r.period_multiple = cur.period_multiple;
    r.jac = shoot.JacobianEvaluations() - cur.j0, r.res = shoot.ResidualEvaluations() - cur.r0, r.tan = shoot.TangentProducts() - cur.p0,
    r.kry = shoot.KrylovIterations() - cur.k0;
    if (fk_ != FloquetKind::None) r.f = fk_ == FloquetKind::MatrixFree ? mf_hook_->c : hook_->c;
    r.krein = &krein_;
    return r;
  }
  // The clock and the solver counters a branch's cost is measured from.
  void StartClock(LiveBranch *cur) const
  {
    const Shooting &shoot = nnm_.shoot;
    PetscTime(&cur->b0);
    cur->j0 = shoot.JacobianEvaluations(), cur->r0 = shoot.ResidualEvaluations(), cur->p0 = shoot.TangentProducts(), cur->k0 = shoot.KrylovIterations();
  }
  // <output>.partial.h5 with the branches done and this one so far, complete = 0.
  PetscErrorCode WritePartial(const LiveBranch &cur, const char *reason)
  {
    OutputFile f;
    PetscFunctionBeginUser;
    PetscCall(PetscLogStagePush(Log().write));
    PetscCall(f.Open(comm_, PartialPath(path_), "checkpoint."));
    PetscCall(WriteBandEdges(f.Viewer(), "/continuation", InfiniteBandEdges(nnm_.lat.Params())));
    for (const BranchRecord &r : done_) PetscCall(WriteRecord(f.Viewer(), r, fk_, n2_, fmo_.nev));
    if (!cur.b.energy.empty()) {
      BranchRecord rec = Snapshot(cur, cur.b);
      rec.b.stop_reason = reason;
      PetscCall(WriteRecord(f.Viewer(), rec, fk_, n2_, fmo_.nev));
    }
    // The -cont_branch entries of a -cont_resume not continued yet, as read:
    // the partial output this run may replace keeps their points (their
    // events are located again when they are continued).
    for (const Resume &r : resumes_) {
      bool written = !r.found || r.label == cur.label;
      for (const BranchRecord &d : done_) written = written || d.label == r.label;
      if (written) continue;
      BranchRecord rec;
      rec.label = r.label, rec.omega = r.omega, rec.b = r.b, rec.f = r.f;
      rec.krein = &krein_;
      PetscCall(WriteRecord(f.Viewer(), rec, fk_, n2_, fmo_.nev));
    }
    PetscCall(f.Commit(name_, Elapsed(), false));
    PetscCall(PetscLogStagePop());
    PetscFunctionReturn(0);
  }
  // Branch cur from start (a resume or a switched family's first two points;
  // none: from its linear mode in u_), its orbits through floquet, with
  // checkpoints; a stop signal writes the partial file and fails. Then its
  // events and the families -cont_switch starts on it.
  PetscErrorCode Continue(LiveBranch &cur, const std::string &name, PointHook *floquet, const ContinuationOptions &co, const Branch *start, size_t kept)
  {
    PetscLogDouble b1;
    PetscFunctionBeginUser;
    CheckpointHook ck(comm_, floquet, ch_.checkpoint_seconds, [&]() -> PetscErrorCode {
      PetscFunctionBeginUser;
      PetscCall(WritePartial(cur, "checkpoint: the run was still going"));
      PetscCall(PetscPrintf(comm_, "  [%s] checkpoint: %zu points written to %s\n", cur.label.c_str(), cur.b.energy.size(), PartialPath(path_).c_str()));
      PetscFunctionReturn(0);
    });
    const bool mode = cur.parent.empty(); // a -cont_branch entry: from its linear mode unless resumed
    const PetscErrorCode ic =
        ContinueBranch(nnm_.shoot, mode ? u_.get() : nullptr, mode ? 2 * PETSC_PI / cur.omega : 0, co, cur.label.c_str(), &cur.b, &ck, start);
    if (IsInterrupt(ic)) PetscCall(Interrupted(cur, "")); // the points so far are the checkpoint a -cont_resume continues bit for bit
    PetscCall(ic);
    PetscCall(PetscTime(&b1));
    PetscCall(Finish(cur, b1, cur.b.energy.size() - kept)); // seconds and costs cover this run's points
    const PetscErrorCode i2 = Codim2From(name, cur.label);
    if (IsInterrupt(i2)) PetscCall(Interrupted(LiveBranch{cur.label, "", 0, Branch()}, "while following its -cont_codim2 curve"));
    PetscCall(i2);
    PetscCall(SwitchFrom(name, cur.label));
    PetscFunctionReturn(0);
  }
  // Branch k of -cont_branch from its linear mode (or its -cont_resume points).
  PetscErrorCode ContinueOne(PetscInt k)
  {
    LiveBranch cur;
    PetscFunctionBeginUser;
    PetscCall(BranchStart(nnm_.lat, nnm_.modes, ch_.names[k], u_, &cur.omega, &cur.label));
    StartClock(&cur);
    hook_->Clear();
    mf_hook_->Clear();
    const Branch &rb = resumes_[k].b;
    const bool resumed = resumes_[k].found && rb.energy.size() >= 2;
    if (resumed && fk_ != FloquetKind::None) (fk_ == FloquetKind::MatrixFree ? mf_hook_->c : hook_->c) = resumes_[k].f;
    if (resumed && fk_ == FloquetKind::MatrixFree) mf_hook_->c.route = mf_hook_->Route();
    if (ch_.resume && !resumed)
      PetscCall(PetscPrintf(comm_, "  [%s] -cont_resume %s: fewer than 2 points of this branch there, starting afresh\n", cur.label.c_str(), ch_.resume_file));
    PetscCall(Continue(cur, ch_.names[k], FloquetPointHook(), nnm_.co, resumed ? &rb : nullptr, resumed ? rb.energy.size() : 0));
    PetscFunctionReturn(0);
  }

  // A stop signal while branch cur is under way (doing: "" while its points
  // are continued, else what): every earlier branch and this one's recorded
  // points, with the step to take next, go to the partial output; returns
  // the silent stop error.
  PetscErrorCode Interrupted(const LiveBranch &cur, const char *doing)
  {
    const char *sn = SignalName(StopSignalSeen());
    const Branch &b = cur.b;
    PetscFunctionBeginUser;
    PetscCheck(!done_.empty() || !b.energy.empty(), comm_, PETSC_ERR_SIG, "interrupted by %s before the first orbit of branch %s; no output written", sn,
               cur.label.c_str());
    const std::string reason = std::string("interrupted by ") + sn + (*doing ? std::string(" ") + doing : "") +
                               (cur.parent.empty() ? ": -cont_resume continues it" : ": -cont_resume with the same -cont_switch continues it");
    PetscCall(WritePartial(cur, reason.c_str()));
    SETERRQ(comm_, PETSC_ERR_SIG,
            "interrupted by %s%s%s after %zu points of branch %s (last E = %g); partial output %s (complete = 0); -cont_resume %s continues it", sn,
            *doing ? " " : "", doing, b.energy.size(), cur.label.c_str(), b.energy.empty() ? 0.0 : (double)b.energy.back(), PartialPath(path_).c_str(),
            PartialPath(path_).c_str());
  }

  // The branch just continued into done_: its events (-cont_bifurcations), the
  // Floquet summary and the time per new point.
  PetscErrorCode Finish(LiveBranch &cur, PetscLogDouble b1, size_t nnew)
  {
    const std::string &label = cur.label;
    PetscFunctionBeginUser;
    BranchRecord rec;
    if (bo_.enabled) { // (the location's solves count in the branch's cost)
      const PetscErrorCode il = LocateEvents(cur.b, label, cur.parent.empty() ? 0 : 1, &rec);
      if (IsInterrupt(il)) PetscCall(Interrupted(cur, "while locating its bifurcations")); // the branch is whole: a resume locates them again
      PetscCall(il);
    }
    done_.push_back(Snapshot(cur, std::move(cur.b)));
    BranchRecord &d = done_.back();
    d.seconds = b1 - cur.b0;
    d.located = rec.located, d.events = std::move(rec.events);
    d.bif_tol = rec.bif_tol, d.bif_seconds = rec.bif_seconds, d.bif_probes = rec.bif_probes;
    if (fk_ != FloquetKind::None) PetscCall(PrintFloquetSummary(comm_, label, d.f, flo_.tol, fk_ == FloquetKind::MatrixFree ? mf_hook_->RouteKind() : FloquetRoute::Full, &d.b.energy));
    if (fk_ != FloquetKind::None && !d.b.energy.empty()) { // the Krein resonance map in one line
      const KreinMap km = ComputeKreinMap(krein_, d.omega, d.b.energy, d.b.period);
      PetscCall(PetscPrintf(comm_, "  [%s] %s\n", label.c_str(), KreinMapSummary(km, krein_.bands, d.b.energy, d.b.period).c_str()));
    }
    PetscCall(
        PetscPrintf(comm_, "  [%s] %.2f s, %.3f s per new point\n", label.c_str(), (double)(b1 - cur.b0), (double)(b1 - cur.b0) / std::max<size_t>(nnew, 1)));
    PetscFunctionReturn(0);
  }

  // -cont_codim2 before anything is computed: a located event (-cont_bifurcations) of a
  // -cont_branch entry or of a family -cont_switch starts (period doublings occur only there), the dense shooting Jacobian, the run's p within the bounds.
  PetscErrorCode CheckCodim2()
  {
    PetscFunctionBeginUser;
    PetscCheck(bo_.enabled, comm_, PETSC_ERR_USER, "-cont_codim2 needs -cont_bifurcations (on with -floquet): it continues a located event");
    PetscCheck(WillBeFollowed(switches_, c2spec_.branch, [&](const std::string &b) { return AmongBranches(b); }), comm_, PETSC_ERR_USER,
               "-cont_codim2 %s: no branch %s among -cont_branch or the families of -cont_switch", c2spec_.text.c_str(), c2spec_.branch.c_str());
    PetscCheck(nnm_.so.jacobian == ShootingJacobian::Dense, comm_, PETSC_ERR_USER,
               "-cont_codim2 needs -nnm_jacobian dense (its test function factors the shooting Jacobian)");
    const PetscReal p = Codim2ParameterValue(nnm_.lp, c2o_.parameter);
    PetscCheck(p >= c2o_.pmin && p <= c2o_.pmax, comm_, PETSC_ERR_USER,
               "-cont_codim2 %s: the run's %s %g lies outside [-cont_codim2_min %g, -cont_codim2_max %g]", c2spec_.text.c_str(),
               Codim2ParameterOption(c2o_.parameter), (double)p, (double)c2o_.pmin, (double)c2o_.pmax);
    PetscFunctionReturn(0);
  }
  // -cont_codim2: the curve of the asked event of the branch just done (given as
  // name, recorded as label) into its record, while the locator holds the branch.
  PetscErrorCode Codim2From(const std::string &name, const std::string &label)
  {
    PetscInt k;
    bool found;
    Codim2Start st;
    Codim2Curve c;
    PetscFunctionBeginUser;
    if (!c2spec_.Given() || !SwitchNames(c2spec_.branch, name)) PetscFunctionReturn(0);
    BranchRecord &d = done_.back();
    PetscCall(SelectEventNearest(comm_, "-cont_codim2", c2spec_.text, c2spec_.kind, c2spec_.omega, d.events, label, &k));
    const BifurcationEvent e = d.events[k];
    PetscCall(EventOrbit(comm_, locator_, nnm_, e, &st, &found));
    PetscCheck(found, comm_, PETSC_ERR_NOT_CONVERGED, "-cont_codim2 %s: the orbit of event %" PetscInt_FMT " (omega %g) was not found again",
               c2spec_.text.c_str(), k, (double)e.omega);
    PetscCall(ContinueCodim2(comm_, nnm_.lp, nnm_.fo, nnm_.so, flo_, nnm_.flow.PeriodMultiple(), c2o_, e, k, st, label.c_str(), &c));
    d.codim2.push_back(std::move(c));
    PetscFunctionReturn(0);
  }

  // -cont_switch: the families born at the asked events of the branch just
  // done (given as name, recorded as label), each event's orbit found first
  // while done_.back() and the locator hold this branch.
  PetscErrorCode SwitchFrom(const std::string &name, const std::string &label)
  {
    std::vector<SwitchJob> jobs;
    PetscFunctionBeginUser;
    const PetscErrorCode ip = PlanSwitches(locator_, nnm_.shoot, switches_, name, label, done_.back().events, &jobs);
    if (IsInterrupt(ip)) PetscCall(Interrupted(LiveBranch{label, "", 0, Branch()}, "before switching"));
    PetscCall(ip);
    for (const SwitchJob &job : jobs) {
      // the family born at a period doubling has twice the parent's period: its orbits
      // are integrated with the parent's step size, and -cont_omega_max bounds the
      // frequency it is plotted at, period_multiple x omega
      PeriodMultipleScope multiple(nnm_.flow, nnm_.flow.PeriodMultiple() * job.plan.period_multiple); // (of a family already doubled: 4, ...)
      ContinuationOptions co = nnm_.co;
      co.omega_max /= nnm_.flow.PeriodMultiple();
      bool followed = false;
      for (PetscInt sign : {1, -1})
        if (!(job.plan.OneFamily() && followed)) PetscCall(FollowFamily(job, sign, co, &followed));
    }
    PetscFunctionReturn(0);
  }
  // The family of job on side sign (SwitchPlan: at a period doubling the
  // -phi side only if the +phi one found no orbit): from its -cont_resume
  // points, or started afresh; then continued as any branch.
  PetscErrorCode FollowFamily(const SwitchJob &job, PetscInt sign, const ContinuationOptions &co, bool *followed)
  {
    LiveBranch cur;
    Branch start;
    FloquetColumns rf;
    bool found = false, pinned;
    PetscFunctionBeginUser;
    StartClock(&cur);
    cur.label = job.plan.Label(sign), cur.omega = job.e.omega, cur.parent = job.plan.ParentAttribute(), cur.period_multiple = nnm_.flow.PeriodMultiple();
    if (ch_.resume) PetscCall(ReadResume(comm_, ch_.resume_file, cur.label, fk_, n2_, fmo_.nev, &start, &rf, &found, mf_hook_->Route()));
    const size_t kept = found && start.energy.size() >= 2 ? start.energy.size() : 0;
    if (kept) {
      hook_->c = rf;
      PetscCall(PetscPrintf(comm_, "  [%s] -cont_resume %s: %zu points of the family born at the %s %s, continued from the last\n", cur.label.c_str(),
                            ch_.resume_file, kept, job.plan.What(), cur.parent.c_str()));
    } else {
      if (ch_.resume)
        PetscCall(
            PetscPrintf(comm_, "  [%s] -cont_resume %s: fewer than 2 points of this family there, starting afresh\n", cur.label.c_str(), ch_.resume_file));
      const PetscErrorCode is = StartFamily(nnm_.shoot, job, switch_step_, sign, *hook_, &start, &pinned);
      if (IsInterrupt(is)) PetscCall(Interrupted(cur, "while switching"));
      PetscCall(is);
      if (!pinned) PetscFunctionReturn(0);
    }
    *followed = true;
    PetscCall(Continue(cur, cur.label, hook_.get(), co, &start, kept)); // then the families born on this one (-cont_switch <label>:<event>)
    PetscFunctionReturn(0);
  }

  // -cont_bifurcations: the events of branch b into rec, from segment
  // first_segment on (1 on a switched family: its first segment starts at the
  // parent's event, whose change of stability it would report again).
  PetscErrorCode LocateEvents(const Branch &b, const std::string &label, PetscInt first_segment, BranchRecord *rec)
  {
    PetscLogDouble t0, t1;
    PetscFunctionBeginUser;
    PetscCall(PetscTime(&t0));
    const PetscInt p0 = locator_.Probes();
    PetscCall(locator_.Locate(b, hook_->c.re, hook_->c.im, hook_->c.edge, label.c_str(), &rec->events, hook_->c.krein, first_segment));
    PetscCall(PetscTime(&t1));
    rec->located = true, rec->bif_tol = bo_.tol, rec->bif_seconds = t1 - t0, rec->bif_probes = locator_.Probes() - p0;
    PetscCall(PetscPrintf(comm_, "  [%s] bifurcations: %zu event(s) located to %g in omega, %" PetscInt_FMT " orbits solved, %.2f s\n", label.c_str(),
                          rec->events.size(), (double)bo_.tol, rec->bif_probes, (double)(t1 - t0)));
    PetscFunctionReturn(0);
  }

  std::vector<SwitchSpec> switches_; // -cont_switch
  PetscReal switch_step_ = 0.02;
  Codim2Options c2o_; // -cont_codim2_*
  Codim2Spec c2spec_;

  NnmSetup nnm_;
  StudyChoices ch_;
  BifurcationOptions bo_;
  BifurcationLocator locator_;
  FloquetOptions flo_;
  FloquetMfOptions fmo_;
  FloquetKind fk_ = FloquetKind::None;
  PetscInt n2_ = 0;
  OwnedVec u_; // a branch's starting shape
  std::unique_ptr<FloquetHook> hook_;
  std::unique_ptr<FloquetMfHook> mf_hook_;
  std::vector<Resume> resumes_;
  std::vector<BranchRecord> done_;
  KreinSpectrum krein_; // the Krein resonance map's linear frequencies (with -floquet)
};

} // namespace

std::unique_ptr<Study> CreateContinuationStudy() { return std::make_unique<ContinuationStudy>(); }

} // namespace nltopo
