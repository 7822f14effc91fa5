// -study continuation: NNM branches from linear modes by pseudo-arclength
// continuation of periodic orbits (orbits/); /continuation/<branch> of outputs.md.
#include "studies/nnm_setup.hpp"
#include "core/log.hpp"
#include "core/options_audit.hpp"
#include "core/signals.hpp"
#include "io/input.hpp"
#include "io/output.hpp"
#include "io/run_options.hpp"
#include "io/schema.hpp"
#include "orbits/continuation.hpp"
#include "stability/floquet.hpp"
#include "stability/floquet_mf.hpp"
#include "studies/continuation_record.hpp"
#include "studies/registry.hpp"
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <functional>

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
// matrix-free (stability/floquet_mf.hpp); no Krein signatures or instability kind.
class FloquetMfHook : public PointHook {
public:
  FloquetMfHook(PeriodicFlow &flow, const FloquetOptions &o, const FloquetMfOptions &mo) : flow_(flow), opt_(o), mopt_(mo) {}
  PetscErrorCode Point(Vec z0, PetscReal T, PetscReal beta, Vec dz0) override
  {
    LeadingMultipliers r;
    PetscFunctionBeginUser;
    PetscCall(FloquetLeading(flow_, z0, T, flow_.FloquetBeta(beta), mopt_, &r, &warm_, dz0));
    c.re.insert(c.re.end(), r.re.begin(), r.re.end());
    c.im.insert(c.im.end(), r.im.begin(), r.im.end());
    c.max_modulus.push_back(r.max_modulus);
    c.stable.push_back(r.max_modulus <= 1 + opt_.tol); // NaN (a multiplier did not converge): not shown stable, 0
    c.products += r.products;
    if (r.converged < mopt_.nev) {
      c.unconverged++;
      PetscCall(PetscPrintf(flow_.Lat().Comm(), "  matrix-free Floquet: %" PetscInt_FMT " of %" PetscInt_FMT " multipliers converged at omega %.6f (written as NaN; raise -floquet_mf_eps_max_it)\n",
                            r.converged, mopt_.nev, (double)(2 * PETSC_PI / T)));
    }
    PetscFunctionReturn(0);
  }
  void Clear() { c = FloquetColumns(), warm_.clear(); }
  FloquetColumns c;

private:
  PeriodicFlow &flow_;
  FloquetOptions opt_;
  FloquetMfOptions mopt_;
  std::vector<OwnedVec> warm_; // the previous orbit's eigenvectors: the next solve's initial space
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
                             "With -floquet: only the -floquet_mf_nev leading multipliers, matrix-free (long lattices; no Krein signatures)", NULL,
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

} // namespace

PetscErrorCode ContinuationStudyOptions(MPI_Comm comm)
{
  NnmSetup nnm;
  StudyChoices ch;
  FloquetOptions flo;
  FloquetMfOptions fmo;
  PetscFunctionBeginUser;
  PetscCall(nnm.DeclareOptions(comm));
  PetscCall(ReadStudyChoices(comm, &ch));
  PetscCall(FloquetOptionsFromOptions(comm, &flo)); // read even without -floquet: they belong to this study
  PetscCall(FloquetMfOptionsFromOptions(comm, &fmo));
  PetscCall(DeclareEPS(comm, "floquet_"));
  PetscCall(DeclareEPS(comm, "floquet_mf_"));
  PetscCall(DeclareOutputOptions(comm, "continuation"));
  PetscFunctionReturn(0);
}

PetscErrorCode ContinuationStudy(MPI_Comm comm)
{
  NnmSetup nnm;
  std::string path;
  OutputFile out;
  PetscLogDouble t_start, t_end;
  PetscFunctionBeginUser;
  PetscCall(PetscTime(&t_start));
  PetscCall(LogRegister());
  PetscCall(PetscLogStagePush(Log().setup));
  PetscCall(nnm.ReadOptions(comm));
  StudyChoices ch;
  PetscCall(ReadStudyChoices(comm, &ch));
  const PetscBool floquet = ch.floquet, floquet_mf = ch.floquet_mf;
  FloquetOptions flo;
  FloquetMfOptions fmo;
  if (floquet) PetscCall(FloquetOptionsFromOptions(comm, &flo));
  if (floquet && floquet_mf) PetscCall(FloquetMfOptionsFromOptions(comm, &fmo));
  char **names = ch.names;
  const PetscInt nb = ch.nb;
  const PetscReal checkpoint_seconds = ch.checkpoint_seconds;
  const char *resume_file = ch.resume_file;
  const PetscBool resume = ch.resume;
  if (resume) PetscCall(CheckResumeOptions(comm, resume_file, "continuation", "-cont_resume")); // the same physics and numerics, or one line naming the first difference
  PetscCall(OutputPathFromOptions(comm, "continuation", &path, [&](const std::string &p) { return resume && SameFile(p, resume_file); }));
  PetscCall(out.Open(comm, path));
  PetscCall(nnm.Build(comm, "-study continuation"));
  Lattice &lat = nnm.lat;
  LinearModes &modes = nnm.modes;
  PeriodicFlow &flow = nnm.flow;
  Shooting &shoot = nnm.shoot;
  const ShootingOptions &so = nnm.so;
  ContinuationOptions &co = nnm.co;
  PetscCall(PetscLogStagePop());

  PetscCall(PetscPrintf(comm, "nltopo continuation: N = %" PetscInt_FMT ", %" PetscInt_FMT " branch(es), E %g .. %g, Jacobian %s\n", lat.N(), nb,
                        (double)co.energy_min, (double)co.energy_max, so.jacobian == ShootingJacobian::Dense ? "dense" : "mf"));
  OwnedVec u;
  PetscCall(DMCreateGlobalVector(lat.SiteDM(), u.out()));
  FloquetHook hook(flow, flo);
  FloquetMfHook mf_hook(flow, flo, fmo);
  const FloquetKind fk = !floquet ? FloquetKind::None : floquet_mf ? FloquetKind::MatrixFree : FloquetKind::Dense;
  PointHook *floquet_hook = fk == FloquetKind::None ? nullptr : fk == FloquetKind::MatrixFree ? static_cast<PointHook *>(&mf_hook) : &hook;
  const PetscInt n2 = 2 * lat.N();
  std::vector<BranchRecord> done;
  // The record of a branch from its live data (also mid-branch, for a checkpoint).
  // (b by value: the final record moves the branch in, a checkpoint copies it).
  auto snapshot = [&](const std::string &label, PetscReal omega, Branch b, PetscInt j0, PetscInt r0, PetscInt p0, PetscInt k0, PetscLogDouble b0) {
    BranchRecord r;
    PetscLogDouble now;
    PetscTime(&now);
    r.label = label, r.omega = omega, r.b = std::move(b), r.seconds = now - b0;
    r.jac = shoot.JacobianEvaluations() - j0, r.res = shoot.ResidualEvaluations() - r0, r.tan = shoot.TangentProducts() - p0,
    r.kry = shoot.KrylovIterations() - k0;
    if (fk != FloquetKind::None) r.f = fk == FloquetKind::MatrixFree ? mf_hook.c : hook.c;
    return r;
  };
  // -cont_resume: every branch read before the first checkpoint may replace the file
  struct Resume {
    Branch b;
    FloquetColumns f;
    bool found = false;
  };
  std::vector<Resume> resumes(nb);
  for (PetscInt k = 0; k < nb && resume; k++) {
    PetscReal omega;
    std::string label;
    PetscCall(BranchStart(lat, modes, names[k], u, &omega, &label));
    PetscCall(ReadResume(comm, resume_file, label, fk, n2, fmo.nev, &resumes[k].b, &resumes[k].f, &resumes[k].found));
  }
  for (PetscInt k = 0; k < nb; k++) {
    PetscReal omega = 0;
    std::string label;
    Branch b;
    PetscLogDouble b0, b1;
    PetscCall(BranchStart(lat, modes, names[k], u, &omega, &label));
    PetscCall(PetscTime(&b0));
    PetscCall(PetscLogStagePush(Log().solve));
    const PetscInt j0 = shoot.JacobianEvaluations(), r0 = shoot.ResidualEvaluations(), p0 = shoot.TangentProducts(), k0 = shoot.KrylovIterations();
    hook.Clear();
    mf_hook.Clear();
    Branch &rb = resumes[k].b;
    const bool resumed = resumes[k].found && rb.energy.size() >= 2;
    if (resumed && fk != FloquetKind::None) (fk == FloquetKind::MatrixFree ? mf_hook.c : hook.c) = resumes[k].f;
    if (resume && !resumed)
      PetscCall(PetscPrintf(comm, "  [%s] -cont_resume %s: fewer than 2 points of this branch there, starting afresh\n", label.c_str(), resume_file));
    // -output with the branches done and this one so far, complete = 0.
    auto write_partial = [&](const char *reason) -> PetscErrorCode {
      OutputFile f;
      PetscLogDouble now;
      PetscFunctionBeginUser;
      PetscCall(PetscLogStagePush(Log().write));
      PetscCall(f.Open(comm, path, "checkpoint."));
      PetscCall(WriteBandEdges(f.Viewer(), "/continuation", InfiniteBandEdges(lat.Params())));
      for (const BranchRecord &r : done) PetscCall(WriteRecord(f.Viewer(), r, fk, n2, fmo.nev));
      if (!b.energy.empty()) {
        BranchRecord cur = snapshot(label, omega, b, j0, r0, p0, k0, b0);
        cur.b.stop_reason = reason;
        PetscCall(WriteRecord(f.Viewer(), cur, fk, n2, fmo.nev));
      }
      PetscCall(PetscTime(&now));
      PetscCall(f.Commit("continuation", now - t_start, false));
      PetscCall(PetscLogStagePop());
      PetscFunctionReturn(0);
    };
    CheckpointHook ck(comm, floquet_hook, checkpoint_seconds, [&]() -> PetscErrorCode {
      PetscFunctionBeginUser;
      PetscCall(write_partial("checkpoint: the run was still going"));
      PetscCall(PetscPrintf(comm, "  [%s] checkpoint: %zu points written to %s\n", label.c_str(), b.energy.size(), path.c_str()));
      PetscFunctionReturn(0);
    });
    const PetscErrorCode ic = ContinueBranch(shoot, u, 2 * PETSC_PI / omega, co, label.c_str(), &b, &ck, resumed ? &rb : nullptr);
    PetscCall(PetscLogStagePop());
    if (IsInterrupt(ic)) {
      // A stop signal during the solve of the next point: the points so far
      // (every earlier branch, this one's recorded points with the step to
      // take next) are the checkpoint a -cont_resume continues bit for bit.
      const char *sn = SignalName(StopSignalSeen());
      PetscCheck(!done.empty() || !b.energy.empty(), comm, PETSC_ERR_SIG, "interrupted by %s before the first orbit of branch %s; no output written", sn,
                 label.c_str());
      const std::string reason = std::string("interrupted by ") + sn + ": -cont_resume continues it";
      PetscCall(write_partial(reason.c_str()));
      for (PetscInt j = 0; j < nb; j++) PetscCall(PetscFree(names[j]));
      SETERRQ(comm, PETSC_ERR_SIG, "interrupted by %s after %zu points of branch %s (last E = %g); partial output %s (complete = 0); -cont_resume %s continues it", sn,
              b.energy.size(), label.c_str(), b.energy.empty() ? 0.0 : (double)b.energy.back(), path.c_str(), path.c_str());
    }
    PetscCall(ic);
    PetscCall(PetscTime(&b1));
    const size_t npts = b.energy.size();
    done.push_back(snapshot(label, omega, std::move(b), j0, r0, p0, k0, b0));
    done.back().seconds = b1 - b0;
    if (fk != FloquetKind::None) {
      const FloquetColumns &f = done.back().f;
      PetscInt ns = 0;
      for (PetscInt s : f.stable) ns += s;
      PetscCall(PetscPrintf(comm, "  [%s] Floquet%s: %" PetscInt_FMT " of %zu orbits stable (|mu| <= 1 + %g)", label.c_str(),
                            fk == FloquetKind::MatrixFree ? " (matrix-free, leading pairs)" : "", ns, f.stable.size(), (double)flo.tol));
      if (fk == FloquetKind::MatrixFree) PetscCall(PetscPrintf(comm, ", %" PetscInt_FMT " monodromy products", f.products));
      else {
        PetscReal dmax = 0;
        for (PetscReal d : f.det_error) dmax = std::max(dmax, d); // NaN (resumed from an older file) ignored
        PetscCall(PetscPrintf(comm, ", max |det M - 1| = %.1e", (double)dmax));
      }
      PetscCall(PetscPrintf(comm, "\n"));
    }
    const size_t nnew = npts - (resumed ? rb.energy.size() : 0); // seconds and costs cover this run's points
    PetscCall(PetscPrintf(comm, "  [%s] %.2f s, %.3f s per new point\n", label.c_str(), (double)(b1 - b0), (double)(b1 - b0) / std::max<size_t>(nnew, 1)));
  }
  PetscCall(PetscLogStagePush(Log().write));
  PetscCall(WriteBandEdges(out.Viewer(), "/continuation", InfiniteBandEdges(lat.Params())));
  for (const BranchRecord &r : done) PetscCall(WriteRecord(out.Viewer(), r, fk, n2, fmo.nev));
  PetscCall(PetscLogStagePop());
  PetscCall(PetscTime(&t_end));
  PetscCall(out.Commit("continuation", t_end - t_start));
  PetscCall(PetscPrintf(comm, "  wrote %s\n", path.c_str()));
  PetscFunctionReturn(0);
}

} // namespace nltopo
