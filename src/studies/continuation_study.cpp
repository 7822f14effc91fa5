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
#include "stability/floquet.hpp"
#include "stability/bifurcation_locator.hpp"
#include "stability/branch_switch.hpp"
#include "stability/floquet_mf.hpp"
#include "studies/continuation_record.hpp"
#include "studies/registry.hpp"
#include "studies/study.hpp"
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <memory>

namespace nltopo {

namespace {

// Starting shape and linear frequency of a branch given by name or mode index.
PetscErrorCode BranchStart(const Lattice &lat, const LinearModes &modes, const char *name, Vec u, PetscReal *omega, std::string *label)
{
  const NamedModes &nm = modes.Named();
  MPI_Comm comm = lat.Comm();
  PetscInt j = -1;
  PetscFunctionBeginUser;
  *label = name;
  if (!std::strcmp(name, "insulated")) {
    PetscCheck(modes.Insulated(), comm, PETSC_ERR_USER, "-cont_branch insulated: this layout has no insulated mode");
    PetscCall(VecCopy(modes.Insulated(), u));
    *omega = nm.insulated_omega;
    PetscFunctionReturn(0);
  }
  if (!std::strcmp(name, "interface")) j = nm.interface;
  else if (!std::strcmp(name, "acoustic_top")) j = nm.acoustic_top;
  else if (!std::strcmp(name, "optical_bottom")) j = nm.optical_bottom;
  else if (!std::strcmp(name, "optical_top")) j = nm.optical_top;
  else {
    const char *s = !std::strncmp(name, "mode", 4) ? name + 4 : name;
    char *end;
    const long k = std::strtol(s, &end, 10);
    PetscCheck(*s && !*end, comm, PETSC_ERR_USER,
               "-cont_branch %s: not one of insulated, interface, acoustic_top, optical_bottom, optical_top, mode<k> or an index", name);
    j = (PetscInt)k;
    *label = "mode" + std::to_string(k);
  }
  PetscCheck(j >= 0 && j < (PetscInt)modes.Omega().size(), comm, PETSC_ERR_USER, "-cont_branch %s: no such linear mode in this lattice", name);
  PetscCall(modes.CopyMode(j, u));
  *omega = modes.Omega()[j];
  PetscFunctionReturn(0);
}

// Floquet multipliers, Krein signatures and stability of every orbit of a branch.
class FloquetHook : public PointHook {
public:
  FloquetHook(PeriodicFlow &flow, const FloquetOptions &o) : flow_(flow), opt_(o) {}
  PetscErrorCode Point(Vec z0, PetscReal T, PetscReal beta, Vec dz0) override
  {
    FloquetResult r;
    PetscFunctionBeginUser;
    if (!S_) {
      PetscCall(flow_.CreateSensitivityMatrix(S_.out()));
      PetscCall(VecDuplicate(z0, zT_.out()));
    }
    PetscCall(flow_.IntegrateWithMonodromy(z0, T, flow_.FloquetBeta(beta), zT_, S_)); // at the converged orbit
    PetscCall(FloquetAnalysis(flow_.Lat(), S_, opt_, &r));
    c.re.insert(c.re.end(), r.re.begin(), r.re.end());
    c.im.insert(c.im.end(), r.im.begin(), r.im.end());
    c.krein.insert(c.krein.end(), r.krein.begin(), r.krein.end());
    c.edge.insert(c.edge.end(), r.edge.begin(), r.edge.end());
    c.max_modulus.push_back(r.max_modulus);
    c.det_error.push_back(r.det_error);
    c.stable.push_back(r.stable);
    c.instability.push_back(r.instability);
    PetscFunctionReturn(0);
  }
  void Clear() { c = FloquetColumns(); }
  FloquetColumns c;

private:
  PeriodicFlow &flow_;
  FloquetOptions opt_;
  OwnedMat S_;
  OwnedVec zT_;
};

// Long lattices: the -floquet_mf_nev leading multipliers of every orbit,
// matrix-free (stability/floquet_mf.hpp), or from the dense monodromy where
// 2N <= -floquet_mf_dense_max (then with their Krein signatures and the
// leading instability's class; -1 and 0 matrix-free). The
// `stable` column holds the route's verdict: only the dense route can say
// "stable" (1); the matrix-free one says "unstable" (0) or "not decided" (-1).
class FloquetMfHook : public PointHook {
public:
  FloquetMfHook(PeriodicFlow &flow, const FloquetOptions &o, const FloquetMfOptions &mo) : flow_(flow), opt_(o), mopt_(mo) {}
  bool Dense() const { return 2 * flow_.Lat().N() <= mopt_.dense_max; }
  PetscErrorCode Point(Vec z0, PetscReal T, PetscReal beta, Vec dz0) override
  {
    LeadingMultipliers r;
    const MPI_Comm comm = flow_.Lat().Comm();
    PetscFunctionBeginUser;
    if (Dense()) {
      if (!S_) {
        PetscCall(flow_.CreateSensitivityMatrix(S_.out()));
        PetscCall(VecDuplicate(z0, zT_.out()));
      }
      PetscCall(flow_.IntegrateWithMonodromy(z0, T, flow_.FloquetBeta(beta), zT_, S_));
      PetscCall(FloquetLeadingDense(flow_.Lat(), S_, mopt_.nev, opt_, &r));
    } else {
      PetscCall(FloquetLeading(flow_, z0, T, flow_.FloquetBeta(beta), mopt_, &r, &warm_, dz0));
      r.verdict = MatrixFreeVerdict(r, opt_.tol);
    }
    c.re.insert(c.re.end(), r.re.begin(), r.re.end());
    c.im.insert(c.im.end(), r.im.begin(), r.im.end());
    c.max_modulus.push_back(r.max_modulus);
    c.stable.push_back(r.verdict);
    r.krein.resize(mopt_.nev, 0); // matrix-free: not computed
    c.krein.insert(c.krein.end(), r.krein.begin(), r.krein.end());
    c.instability.push_back(r.instability);
    c.products += r.products;
    c.route = Route();
    if (r.converged < mopt_.nev && !Dense()) {
      c.unconverged++;
      PetscCall(PetscPrintf(comm, "  matrix-free Floquet: %" PetscInt_FMT " of %" PetscInt_FMT " multipliers converged at omega %.6f%s (written as NaN; raise -floquet_mf_eps_max_it or -floquet_mf_eps_ncv)\n",
                            r.converged, mopt_.nev, (double)(2 * PETSC_PI / T), r.spurious ? ", spurious Ritz values rejected by their true residual" : ""));
    }
    PetscFunctionReturn(0);
  }
  const char *Route() const { return Dense() ? "dense" : "matrix-free"; }
  void Clear() { c = FloquetColumns(), c.route = Route(), warm_.clear(); }
  FloquetColumns c;

private:
  PeriodicFlow &flow_;
  FloquetOptions opt_;
  FloquetMfOptions mopt_;
  std::vector<OwnedVec> warm_; // the previous orbit's eigenvectors: the next solve's initial space
  OwnedMat S_;                 // the dense route's sensitivity matrix
  OwnedVec zT_;
};

// Forwards every orbit to the Floquet hook (if any), then, every
// -cont_checkpoint_seconds, writes the -output file with what is done so far
// (complete = 0), so that a long run that is killed keeps its points.
class CheckpointHook : public PointHook {
public:
  CheckpointHook(MPI_Comm comm, PointHook *inner, PetscReal every, std::function<PetscErrorCode()> write)
    : comm_(comm), inner_(inner), every_(every), write_(std::move(write)) { PetscTime(&last_); }
  PetscErrorCode Point(Vec z0, PetscReal T, PetscReal beta, Vec dz0) override
  {
    PetscFunctionBeginUser;
    if (inner_) PetscCall(inner_->Point(z0, T, beta, dz0));
    if (every_ <= 0) PetscFunctionReturn(0);
    PetscLogDouble now;
    PetscCall(PetscTime(&now));
    int due = now - last_ >= every_;
    PetscCallMPI(MPI_Bcast(&due, 1, MPI_INT, 0, comm_)); // rank 0's clock decides for all
    if (!due) PetscFunctionReturn(0);
    PetscCall(write_());
    PetscCall(PetscTime(&last_));
    PetscFunctionReturn(0);
  }

private:
  MPI_Comm comm_;
  PointHook *inner_;
  PetscReal every_;
  std::function<PetscErrorCode()> write_;
  PetscLogDouble last_ = 0;
};

// The study's own choices: Floquet on/off, the branches, checkpoints, resume.
struct StudyChoices {
  PetscBool floquet = PETSC_FALSE, floquet_mf = PETSC_FALSE;
  char *names[16] = {};
  PetscInt nb = 16;
  PetscReal checkpoint_seconds = 0;
  char resume_file[PETSC_MAX_PATH_LEN] = "";
  PetscBool resume = PETSC_FALSE;
  ~StudyChoices()
  {
    for (char *n : names) PetscFree(n);
  }
};

PetscErrorCode ReadStudyChoices(MPI_Comm comm, StudyChoices *c)
{
  PetscBool set;
  PetscFunctionBeginUser;
  PetscOptionsBegin(comm, NULL, "Floquet stability along the branches", NULL);
  PetscCall(PetscOptionsBool("-floquet", "Add Floquet multipliers, Krein signatures and stability to every orbit (-floquet_* options)", NULL, c->floquet,
                             &c->floquet, NULL));
  PetscCall(PetscOptionsBool("-floquet_mf",
                             "With -floquet: only the -floquet_mf_nev leading multiplier pairs (long lattices): from the dense monodromy up to 2N = "
                             "-floquet_mf_dense_max, matrix-free beyond (no stable verdict there)", NULL,
                             c->floquet_mf, &c->floquet_mf, NULL));
  PetscOptionsEnd();
  PetscOptionsBegin(comm, "cont_", "NNM branches", NULL);
  PetscCall(PetscOptionsStringArray("-branch", "Comma-separated branches: insulated, interface, acoustic_top, optical_bottom, optical_top, mode<k> or k",
                                    NULL, c->names, &c->nb, &set));
  PetscCall(PetscOptionsReal("-checkpoint_seconds",
                             "Write -output with the points so far (root attribute complete = 0) at most this often, so that a killed run keeps them "
                             "(0: only at the end)",
                             NULL, c->checkpoint_seconds, &c->checkpoint_seconds, NULL));
  PetscCall(PetscOptionsString("-resume",
                               "Continue the branches of this earlier -output (complete or a checkpoint) from their last points, keeping their "
                               "points; branches it lacks start afresh",
                               NULL, c->resume_file, c->resume_file, sizeof(c->resume_file), &c->resume));
  PetscOptionsEnd();
  PetscCheck(c->checkpoint_seconds >= 0 && c->checkpoint_seconds <= 1e7, comm, PETSC_ERR_USER, "-cont_checkpoint_seconds must lie in [0, 1e7], got %g",
             (double)c->checkpoint_seconds);
  if (!set) {
    PetscCall(PetscStrallocpy("insulated", &c->names[0]));
    c->nb = 1;
  }
  PetscCheck(c->nb >= 1, comm, PETSC_ERR_USER, "-cont_branch needs at least one branch name");
  PetscFunctionReturn(0);
}

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
    PetscCall(SwitchOptions());
    if (!declaring_ && ch_.resume) PetscCall(CheckResumeOptions(comm_, ch_.resume_file, name_, "-cont_resume")); // the same physics and numerics, or one line naming the first difference
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
  // -cont_resume of the -output file itself replaces it (no -output_overwrite needed).
  PetscErrorCode OutputPath(std::string *path) override
  {
    PetscFunctionBeginUser;
    PetscCall(OutputPathFromOptions(comm_, name_, path, [&](const std::string &p) { return ch_.resume && SameFile(p, ch_.resume_file); }));
    PetscFunctionReturn(0);
  }
  PetscErrorCode Build() override
  {
    PetscFunctionBeginUser;
    PetscCall(nnm_.Build(comm_, "-study continuation"));
    PetscCall(DMCreateGlobalVector(nnm_.lat.SiteDM(), u_.out()));
    hook_ = std::make_unique<FloquetHook>(nnm_.flow, flo_);
    mf_hook_ = std::make_unique<FloquetMfHook>(nnm_.flow, flo_, fmo_);
    if (bo_.enabled) PetscCall(locator_.Setup(nnm_.shoot, flo_, bo_));
    n2_ = 2 * nnm_.lat.N();
    PetscFunctionReturn(0);
  }
  PetscErrorCode Solve() override
  {
    PetscFunctionBeginUser;
    PetscCall(PetscPrintf(comm_, "nltopo continuation: N = %" PetscInt_FMT ", %" PetscInt_FMT " branch(es), E %g .. %g, Jacobian %s\n", nnm_.lat.N(), ch_.nb,
                          (double)nnm_.co.energy_min, (double)nnm_.co.energy_max, nnm_.so.jacobian == ShootingJacobian::Dense ? "dense" : "mf"));
    if (fk_ == FloquetKind::MatrixFree) {
      if (mf_hook_->Dense())
        PetscCall(PetscPrintf(comm_, "  Floquet: the dense monodromy (2N = %" PetscInt_FMT " <= -floquet_mf_dense_max %" PetscInt_FMT "): every multiplier, a stability verdict per orbit, cost ~(2N)^3\n",
                              n2_, fmo_.dense_max));
      else
        PetscCall(PetscPrintf(comm_, "  Floquet: matrix-free (2N = %" PetscInt_FMT " > -floquet_mf_dense_max %" PetscInt_FMT "): an orbit is unstable or not decided, never stable\n", n2_,
                              fmo_.dense_max));
    }
    // -cont_resume: every branch read before the first checkpoint may replace the file
    resumes_.resize(ch_.nb);
    for (PetscInt k = 0; k < ch_.nb && ch_.resume; k++) {
      PetscReal omega;
      std::string label;
      PetscCall(BranchStart(nnm_.lat, nnm_.modes, ch_.names[k], u_, &omega, &label));
      PetscCall(ReadResume(comm_, ch_.resume_file, label, fk_, n2_, fmo_.nev, &resumes_[k].b, &resumes_[k].f, &resumes_[k].found, mf_hook_->Route()));
    }
    for (PetscInt k = 0; k < ch_.nb; k++) PetscCall(ContinueOne(k));
    for (const Switch &sw : switches_) {
      if (sw.used) continue;
      PetscCheck(!AmongBranches(sw.branch), comm_, PETSC_ERR_USER, "-cont_switch %s:%" PetscInt_FMT ": no branch %s among -cont_branch", sw.branch.c_str(), sw.event,
                 sw.branch.c_str());
      // a family of another switch that was not followed (a numerical failure, warned about) or has another name
      PetscCall(PetscPrintf(comm_, "  warning: -cont_switch %s:%" PetscInt_FMT ": no branch %s was followed (its switch failed, or its event started a family of another name, e.g. _pd<k> at a period doubling); not switched\n",
                            sw.branch.c_str(), sw.event, sw.branch.c_str()));
    }
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
  // Whether -cont_switch's branch names the -cont_branch entry name (as given, or as its label mode<k> for k)
  static bool SwitchNames(const std::string &branch, const std::string &name)
  {
    return branch == name || branch == "mode" + name || "mode" + branch == name;
  }
  // The switch a switched family's label comes from: <b>_bp<k>_plus, <b>_bp<k>_minus or <b>_pd<k> -> (b, k).
  static bool SwitchedFrom(const std::string &label, std::string *branch, PetscInt *event)
  {
    for (const char *tag : {"_bp", "_pd"}) {
      const size_t pos = label.rfind(tag);
      if (pos == std::string::npos || pos == 0) continue;
      size_t end = pos + 3;
      while (end < label.size() && end < pos + 9 && std::isdigit((unsigned char)label[end])) end++;
      const std::string tail = label.substr(end);
      if (end == pos + 3 || !(tag[1] == 'b' ? tail == "_plus" || tail == "_minus" : tail.empty())) continue;
      *branch = label.substr(0, pos);
      *event = (PetscInt)std::stol(label.substr(pos + 3, end - pos - 3));
      return true;
    }
    return false;
  }
  // Whether branch is one of -cont_branch (by its name or its label, k or mode<k>).
  bool AmongBranches(const std::string &branch) const
  {
    for (PetscInt k = 0; k < ch_.nb; k++)
      if (SwitchNames(branch, ch_.names[k])) return true;
    return false;
  }
  // Whether branch will be continued: one of -cont_branch, or the family of another -cont_switch event of such a branch.
  bool Followed(const std::string &branch, int depth = 0) const
  {
    std::string parent;
    PetscInt ev;
    if (AmongBranches(branch)) return true;
    if (depth > 16 || !SwitchedFrom(branch, &parent, &ev)) return false;
    for (const Switch &o : switches_)
      if (SwitchNames(o.branch, parent) && o.event == ev) return Followed(o.branch, depth + 1);
    return false;
  }
  PetscErrorCode SwitchOptions()
  {
    char *list[16] = {};
    PetscInt n = 16;
    PetscBool set;
    PetscFunctionBeginUser;
    PetscOptionsBegin(comm_, "cont_", "Branch switching", NULL);
    PetscCall(PetscOptionsStringArray("-switch",
                                      "Follow the families born at these located branch points (on both sides of the critical eigenvector) or period "
                                      "doublings (the doubled-period family), <branch>:<event index> (the event list of -cont_bifurcations)",
                                      NULL, list, &n, &set));
    PetscCall(PetscOptionsReal("-switch_step", "The first orbit of a switched family: this times |z*| along the critical eigenvector from the branch point", NULL,
                               switch_step_, &switch_step_, NULL));
    PetscOptionsEnd();
    PetscCheck(switch_step_ > 0 && switch_step_ < 1, comm_, PETSC_ERR_USER, "-cont_switch_step must lie in (0, 1), got %g", (double)switch_step_);
    switches_.clear();
    for (PetscInt i = 0; set && i < n; i++) {
      const std::string item = list[i];
      PetscCall(PetscFree(list[i]));
      const size_t colon = item.rfind(':');
      char *end = nullptr;
      const long ev = colon == std::string::npos ? -1 : std::strtol(item.c_str() + colon + 1, &end, 10);
      PetscCheck(colon != std::string::npos && colon > 0 && end && !*end && ev >= 0 && ev < 1000000 && end != item.c_str() + colon + 1, comm_, PETSC_ERR_USER,
                 "-cont_switch %s: expected <branch>:<event index>, e.g. insulated:12", item.c_str());
      for (const Switch &o : switches_)
        PetscCheck(!(SwitchNames(o.branch, item.substr(0, colon)) && o.event == ev), comm_, PETSC_ERR_USER, "-cont_switch %s: given twice", item.c_str());
      switches_.push_back({item.substr(0, colon), (PetscInt)ev});
    }
    // each on a branch of -cont_branch, or on the family another switch starts
    // (insulated:34,insulated_bp34_plus:7 at N = 22: the period doubling of a switched family)
    for (const Switch &sw : switches_)
      PetscCheck(declaring_ || Followed(sw.branch), comm_, PETSC_ERR_USER,
                 "-cont_switch %s:%" PetscInt_FMT ": no branch %s among -cont_branch or the families of the other -cont_switch events", sw.branch.c_str(), sw.event,
                 sw.branch.c_str());
    PetscCheck(switches_.empty() || declaring_ || bo_.enabled, comm_, PETSC_ERR_USER,
               "-cont_switch needs -cont_bifurcations (on with -floquet): the branch points and period doublings are its events");
    PetscFunctionReturn(0);
  }
  PointHook *FloquetPointHook() { return fk_ == FloquetKind::None ? nullptr : fk_ == FloquetKind::MatrixFree ? static_cast<PointHook *>(mf_hook_.get()) : hook_.get(); }
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
    return r;
  }
  // -output with the branches done and this one so far, complete = 0.
  PetscErrorCode WritePartial(const LiveBranch &cur, const char *reason)
  {
    OutputFile f;
    PetscFunctionBeginUser;
    PetscCall(PetscLogStagePush(Log().write));
    PetscCall(f.Open(comm_, path_, "checkpoint."));
    PetscCall(WriteBandEdges(f.Viewer(), "/continuation", InfiniteBandEdges(nnm_.lat.Params())));
    for (const BranchRecord &r : done_) PetscCall(WriteRecord(f.Viewer(), r, fk_, n2_, fmo_.nev));
    if (!cur.b.energy.empty()) {
      BranchRecord rec = Snapshot(cur, cur.b);
      rec.b.stop_reason = reason;
      PetscCall(WriteRecord(f.Viewer(), rec, fk_, n2_, fmo_.nev));
    }
    PetscCall(f.Commit(name_, Elapsed(), false));
    PetscCall(PetscLogStagePop());
    PetscFunctionReturn(0);
  }
  // Branch k from its start (or its -cont_resume points) to the end, with
  // checkpoints; a stop signal writes the partial file and fails.
  PetscErrorCode ContinueOne(PetscInt k)
  {
    Shooting &shoot = nnm_.shoot;
    LiveBranch cur;
    PetscLogDouble b1;
    PetscFunctionBeginUser;
    PetscCall(BranchStart(nnm_.lat, nnm_.modes, ch_.names[k], u_, &cur.omega, &cur.label));
    const std::string &label = cur.label;
    Branch &b = cur.b;
    PetscCall(PetscTime(&cur.b0));
    cur.j0 = shoot.JacobianEvaluations(), cur.r0 = shoot.ResidualEvaluations(), cur.p0 = shoot.TangentProducts(), cur.k0 = shoot.KrylovIterations();
    hook_->Clear();
    mf_hook_->Clear();
    Branch &rb = resumes_[k].b;
    const bool resumed = resumes_[k].found && rb.energy.size() >= 2;
    if (resumed && fk_ != FloquetKind::None) (fk_ == FloquetKind::MatrixFree ? mf_hook_->c : hook_->c) = resumes_[k].f;
    if (resumed && fk_ == FloquetKind::MatrixFree) mf_hook_->c.route = mf_hook_->Route();
    if (ch_.resume && !resumed)
      PetscCall(PetscPrintf(comm_, "  [%s] -cont_resume %s: fewer than 2 points of this branch there, starting afresh\n", label.c_str(), ch_.resume_file));
    CheckpointHook ck(comm_, FloquetPointHook(), ch_.checkpoint_seconds, [&]() -> PetscErrorCode {
      PetscFunctionBeginUser;
      PetscCall(WritePartial(cur, "checkpoint: the run was still going"));
      PetscCall(PetscPrintf(comm_, "  [%s] checkpoint: %zu points written to %s\n", label.c_str(), b.energy.size(), path_.c_str()));
      PetscFunctionReturn(0);
    });
    const PetscErrorCode ic = ContinueBranch(shoot, u_, 2 * PETSC_PI / cur.omega, nnm_.co, label.c_str(), &b, &ck, resumed ? &rb : nullptr);
    if (IsInterrupt(ic)) PetscCall(Interrupted(cur, "")); // the points so far are the checkpoint a -cont_resume continues bit for bit
    PetscCall(ic);
    PetscCall(PetscTime(&b1));
    const size_t nnew = b.energy.size() - (resumed ? rb.energy.size() : 0); // seconds and costs cover this run's points
    PetscCall(Finish(cur, b1, nnew));
    PetscCall(SwitchFrom(ch_.names[k], label));
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
    SETERRQ(comm_, PETSC_ERR_SIG, "interrupted by %s%s%s after %zu points of branch %s (last E = %g); partial output %s (complete = 0); -cont_resume %s continues it", sn,
            *doing ? " " : "", doing, b.energy.size(), cur.label.c_str(), b.energy.empty() ? 0.0 : (double)b.energy.back(), path_.c_str(), path_.c_str());
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
    if (fk_ != FloquetKind::None) {
      const FloquetColumns &f = d.f;
      PetscInt ns = 0, nu = 0;
      for (PetscInt s : f.stable) ns += s == kStable, nu += s == kUndecided;
      PetscCall(PetscPrintf(comm_, "  [%s] Floquet%s: %" PetscInt_FMT " of %zu orbits stable (|mu| <= 1 + %g)", label.c_str(),
                            fk_ != FloquetKind::MatrixFree ? "" : mf_hook_->Dense() ? " (-floquet_mf, dense: 2N <= -floquet_mf_dense_max)" : " (matrix-free, leading pairs)",
                            ns, f.stable.size(), (double)flo_.tol));
      if (fk_ == FloquetKind::MatrixFree) {
        if (!mf_hook_->Dense())
          PetscCall(PetscPrintf(comm_, ", %" PetscInt_FMT " not decided (a complex quadruplet cannot be excluded matrix-free), %" PetscInt_FMT " monodromy products",
                                nu, f.products));
      } else {
        PetscReal dmax = 0;
        for (PetscReal x : f.det_error) dmax = std::max(dmax, x); // NaN (resumed from an older file) ignored
        PetscCall(PetscPrintf(comm_, ", max |det M - 1| = %.1e", (double)dmax));
      }
      PetscCall(PetscPrintf(comm_, "\n"));
    }
    PetscCall(PetscPrintf(comm_, "  [%s] %.2f s, %.3f s per new point\n", label.c_str(), (double)(b1 - cur.b0), (double)(b1 - cur.b0) / std::max<size_t>(nnew, 1)));
    PetscFunctionReturn(0);
  }

  // -cont_switch: the families born at the asked branch points of the branch
  // just done (given as name, recorded as label), on both sides of the critical
  // eigenvector, and at its asked period doublings (one doubled-period family each).
  PetscErrorCode SwitchFrom(const char *name, const std::string &label)
  {
    struct Job {
      std::string parent;
      BifurcationEvent e;
      OwnedVec Xs; // the orbit at the branch point, on the parent
    };
    std::vector<Job> jobs;
    PetscFunctionBeginUser;
    // Every asked event and its orbit first, while done_.back() and the locator hold this branch
    const std::vector<BifurcationEvent> ev = done_.back().events;
    for (Switch &sw : switches_) {
      if (!SwitchNames(sw.branch, name)) continue;
      sw.used = true;
      PetscCheck(sw.event < (PetscInt)ev.size(), comm_, PETSC_ERR_USER, "-cont_switch %s:%" PetscInt_FMT ": branch %s has %zu located events%s", sw.branch.c_str(),
                 sw.event, label.c_str(), ev.size(), ev.empty() ? "" : (" (0 .. " + std::to_string(ev.size() - 1) + ")").c_str());
      Job job;
      job.e = ev[sw.event];
      PetscCheck(SwitchedPeriodMultiple(job.e.kind) > 0, comm_, PETSC_ERR_USER,
                 "-cont_switch %s:%" PetscInt_FMT ": that event is a %s; branch switching follows branch points (kind 2) and period doublings (kind 3)",
                 sw.branch.c_str(), sw.event, EventKindName(job.e.kind));
      job.parent = label + ":" + std::to_string(sw.event);
      bool found = false;
      PetscCall(nnm_.shoot.CreateUnknowns(job.Xs.out()));
      // right at a branch point the shooting Jacobian is singular: a step aside if Newton fails there
      for (PetscReal aside : {0.0, -1e-6, 1e-6, -1e-4, 1e-4}) {
        const PetscErrorCode ierr = locator_.OrbitAt(job.e.point, job.e.sigma + aside, job.Xs, &found);
        if (IsInterrupt(ierr)) PetscCall(Interrupted(LiveBranch{label, "", 0, Branch()}, "before switching"));
        PetscCall(ierr);
        if (found) break;
      }
      if (!found) {
        PetscCall(PetscPrintf(comm_, "  warning: -cont_switch %s: the orbit at the branch point (omega %g) was not found again; not switched\n", job.parent.c_str(),
                              (double)job.e.omega));
        continue;
      }
      jobs.push_back(std::move(job));
    }
    for (const Job &job : jobs) {
      const BifurcationEvent &e = job.e;
      const std::string &parent = job.parent;
      const Vec Xs = job.Xs;
      // the family born at a period doubling has twice the parent's period: its orbits
      // are integrated with the parent's step size, and -cont_omega_max bounds the
      // frequency it is plotted at, period_multiple x omega
      const PetscInt m = SwitchedPeriodMultiple(e.kind);
      const bool pd = m == 2;
      const char *what = pd ? "period doubling" : "branch point";
      const std::string stem = parent.substr(0, parent.rfind(':')) + (pd ? "_pd" : "_bp") + parent.substr(parent.rfind(':') + 1);
      PeriodMultipleScope multiple(nnm_.flow, nnm_.flow.PeriodMultiple() * m); // (of a family already doubled: 4, ...)
      ContinuationOptions co = nnm_.co;
      co.omega_max /= nnm_.flow.PeriodMultiple();
      // A branch point starts a family on each side of phi. At a period doubling the
      // two sides are one family (its orbit passes z* + eps phi and, T* later,
      // z* - eps phi): the + side, the - side only if no orbit is found there.
      bool followed = false;
      for (PetscInt sign : {1, -1}) {
        if (pd && followed) break;
        LiveBranch cur;
        Branch start;
        bool pinned;
        PetscReal away;
        PetscCall(PetscTime(&cur.b0));
        cur.label = stem + (pd ? "" : sign > 0 ? "_plus" : "_minus");
        cur.omega = e.omega, cur.parent = parent, cur.period_multiple = nnm_.flow.PeriodMultiple();
        Shooting &shoot = nnm_.shoot;
        cur.j0 = shoot.JacobianEvaluations(), cur.r0 = shoot.ResidualEvaluations(), cur.p0 = shoot.TangentProducts(), cur.k0 = shoot.KrylovIterations();
        // -cont_resume: the family's points in that file (a checkpoint or an interrupted
        // run), continued from its last one as a branch of -cont_branch is
        FloquetColumns rf;
        bool found = false;
        if (ch_.resume) PetscCall(ReadResume(comm_, ch_.resume_file, cur.label, fk_, n2_, fmo_.nev, &start, &rf, &found, mf_hook_->Route()));
        const size_t kept = found && start.energy.size() >= 2 ? start.energy.size() : 0;
        if (kept) {
          followed = true;
          hook_->c = rf;
          PetscCall(PetscPrintf(comm_, "  [%s] -cont_resume %s: %zu points of the family born at the %s %s, continued from the last\n", cur.label.c_str(), ch_.resume_file,
                                kept, what, parent.c_str()));
        } else {
          if (ch_.resume) PetscCall(PetscPrintf(comm_, "  [%s] -cont_resume %s: fewer than 2 points of this family there, starting afresh\n", cur.label.c_str(), ch_.resume_file));
          const PetscErrorCode is = StartSwitchedBranch(shoot, Xs, e, switch_step_, sign, &start, &pinned, &away);
          if (IsInterrupt(is)) PetscCall(Interrupted(cur, "while switching"));
          PetscCall(is);
          if (!pinned) {
            if (pd && sign > 0)
              PetscCall(PetscPrintf(comm_, "  warning: -cont_switch %s: no orbit found %g |z*| off the period doubling along +phi (Newton failed); trying -phi (the same family)\n",
                                    parent.c_str(), (double)switch_step_));
            else
              PetscCall(PetscPrintf(comm_, "  warning: -cont_switch %s: no orbit found %g |z*| off the %s along %sits critical eigenvector (Newton failed); %s not followed, try another -cont_switch_step\n",
                                    parent.c_str(), (double)switch_step_, what, pd ? "either side of " : "", cur.label.c_str()));
            continue;
          }
          followed = true;
          PetscCall(PetscPrintf(comm_, "  [%s] from the %s %s at omega %.9f (E %.6g): first orbit at %g |z*| along %sthe critical eigenvector (%.0f %% of the step along it), E %.6g, omega %.9f%s\n",
                                cur.label.c_str(), what, parent.c_str(), (double)e.omega, (double)e.energy, (double)switch_step_, sign > 0 ? "" : "minus ", (double)(100 * away),
                                (double)start.energy[1], (double)start.omega[1], pd ? " (period ~2 T*: the FEP plots it at 2 omega, attribute period_multiple 2)" : ""));
          // the Floquet data of the two start points, as of every other
          hook_->Clear();
          OwnedVec z;
          PetscCall(nnm_.lat.CreateStateVector(z.out()));
          std::vector<PetscReal> rows = start.z0;
          PetscCall(BroadcastFromRoot(comm_, MPIU_REAL, &rows));
          for (size_t q = 0; q < 2; q++) {
            PetscCall(StateFromRow(nnm_.lat, rows.data() + q * n2_, z));
            const PetscErrorCode ih = hook_->Point(z, start.period[q], start.beta[q], z);
            if (IsInterrupt(ih)) PetscCall(Interrupted(cur, "while switching"));
            PetscCall(ih);
          }
        }
        CheckpointHook ck(comm_, hook_.get(), ch_.checkpoint_seconds, [&]() -> PetscErrorCode {
          PetscFunctionBeginUser;
          PetscCall(WritePartial(cur, "checkpoint: the run was still going"));
          PetscCall(PetscPrintf(comm_, "  [%s] checkpoint: %zu points written to %s\n", cur.label.c_str(), cur.b.energy.size(), path_.c_str()));
          PetscFunctionReturn(0);
        });
        const PetscErrorCode ic = ContinueBranch(shoot, nullptr, 0, co, cur.label.c_str(), &cur.b, &ck, &start);
        if (IsInterrupt(ic)) PetscCall(Interrupted(cur, "")); // its points so far: -cont_resume (with the same -cont_switch) continues it
        PetscCall(ic);
        PetscLogDouble b1;
        PetscCall(PetscTime(&b1));
        PetscCall(Finish(cur, b1, cur.b.energy.size() - kept));
        PetscCall(SwitchFrom(cur.label.c_str(), cur.label)); // the families born on this one (-cont_switch <label>:<event>)
      }
    }
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
    PetscCall(PetscPrintf(comm_, "  [%s] bifurcations: %zu event(s) located to %g in omega, %" PetscInt_FMT " orbits solved, %.2f s\n", label.c_str(), rec->events.size(),
                          (double)bo_.tol, rec->bif_probes, (double)(t1 - t0)));
    PetscFunctionReturn(0);
  }

  // -cont_switch <branch>:<event>
  struct Switch {
    std::string branch;
    PetscInt event = 0;
    bool used = false;
  };
  std::vector<Switch> switches_;
  PetscReal switch_step_ = 0.02;

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
};

} // namespace

std::unique_ptr<Study> CreateContinuationStudy() { return std::make_unique<ContinuationStudy>(); }

} // namespace nltopo
