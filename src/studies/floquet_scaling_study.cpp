// -study floquet_scaling: does a Floquet instability persist as the lattice
// grows? One branch (-scaling_branch) continued, as -study continuation does
// (ContinueBranch with the -floquet_mf hook on its dense route), at each
// -scaling_cells; per energy window (-scaling_energy_windows) the envelope,
// the largest |mu| - 1 over the window's orbits, against N fitted as C N^-p
// (stability/envelope_fit.hpp). /floquet_scaling of outputs.md;
// docs/studies/floquet_scaling.md.
#include "studies/nnm_setup.hpp"
#include "core/errors.hpp"
#include "core/option_table.hpp"
#include "core/options_audit.hpp"
#include "core/signals.hpp"
#include "io/output.hpp"
#include "io/schema.hpp"
#include "orbits/continuation.hpp"
#include "stability/envelope_fit.hpp"
#include "stability/floquet_hooks.hpp"
#include "studies/continuation_choices.hpp"
#include "studies/registry.hpp"
#include "studies/study.hpp"
#include <algorithm>
#include <cmath>
#include <memory>

namespace nltopo {

namespace {

struct ScalingOptions {
  std::vector<PetscReal> cells{5, 10};
  std::vector<PetscReal> windows{0, 1, 2};
  std::string branch = "insulated";
  PetscReal persist_exponent = 0.5;
  PetscInt instability_class = 0; // 0: any; 1-3: only orbits whose leading instability has this class
};

const auto &kScalingTable = DeclareOptionTable<ScalingOptions>(
    "scaling_", "Scaling of Floquet instabilities with N (one branch at several lattice sizes, dense Floquet route)", [](OptionTable<ScalingOptions> &t) {
      t.RealList("cells", &ScalingOptions::cells, 16, Closed(1, 1e6),
                 "Cells per side of each lattice (N = 4 cells + 2 on the interface layout), ascending integers; each needs the dense Floquet route "
                 "(2N <= -floquet_mf_dense_max)")
          .RealList("energy_windows", &ScalingOptions::windows, 32, Closed(0, 1e12),
                    "Energy window edges e0 < e1 < ...: the envelope of |mu| - 1 is fitted per window [e_k, e_k+1)")
          .String("branch", &ScalingOptions::branch, "The branch continued at each size, named as in -cont_branch (insulated, interface, ..., mode<k>)")
          .Real("persist_exponent", &ScalingOptions::persist_exponent, Closed(0, 10),
                "A window's instability persists when its envelope exponent p (|mu| - 1 ~ C N^-p) is below this, and is a finite-size effect at or "
                "above it (0: no decay; 1: the 1/N of two extended band pairs)")
          .Int("class", &ScalingOptions::instability_class, Closed(0, 3),
               "Envelope of one instability class only: 1 B-B, 2 B-E, 3 E-E (the leading pair's class; an orbit whose leading instability has "
               "another class counts as stable for it); 0 any");
    });

PetscErrorCode ScalingOptionsFromOptions(MPI_Comm comm, ScalingOptions *o)
{
  PetscFunctionBeginUser;
  PetscCall(kScalingTable.Read(comm, o));
  PetscCheck(!o->cells.empty(), comm, PETSC_ERR_USER, "-scaling_cells needs at least one size");
  for (size_t k = 0; k < o->cells.size(); k++) {
    PetscCheck(o->cells[k] == std::floor(o->cells[k]), comm, PETSC_ERR_USER, "-scaling_cells %g: cells per side are integers", (double)o->cells[k]);
    PetscCheck(k == 0 || o->cells[k] > o->cells[k - 1], comm, PETSC_ERR_USER, "-scaling_cells must ascend, got %" PetscInt_FMT " after %" PetscInt_FMT,
               (PetscInt)o->cells[k], (PetscInt)o->cells[k - 1]);
  }
  PetscCheck(o->windows.size() >= 2, comm, PETSC_ERR_USER, "-scaling_energy_windows needs at least two edges (one window), got %zu", o->windows.size());
  for (size_t k = 1; k < o->windows.size(); k++)
    PetscCheck(o->windows[k] > o->windows[k - 1], comm, PETSC_ERR_USER, "-scaling_energy_windows must ascend, got %g after %g", (double)o->windows[k],
               (double)o->windows[k - 1]);
  PetscFunctionReturn(0);
}

// One size's branch: the columns /floquet_scaling/cells<c> holds.
struct SizeRun {
  PetscInt cells = 0, N = 0;
  Branch b;
  FloquetColumns f;
  PetscReal seconds = 0;
};

class FloquetScalingStudy : public Study {
protected:
  PetscErrorCode ReadOptions() override
  {
    PetscFunctionBeginUser;
    PetscCall(base_.ReadOptions(comm_));
    if (!declaring_) PetscCall(RejectGivenOptions(comm_, {"-lattice_cells"}, "-study floquet_scaling (-scaling_cells)"));
    PetscCall(FloquetOptionsFromOptions(comm_, &flo_));
    PetscCall(FloquetMfOptionsFromOptions(comm_, &fmo_));
    PetscCall(ScalingOptionsFromOptions(comm_, &so_));
    if (!declaring_)
      for (PetscReal c : so_.cells) {
        LatticeParams lp = base_.lp;
        lp.cells = (PetscInt)c;
        PetscCheck(2 * lp.N() <= fmo_.dense_max, comm_, PETSC_ERR_USER,
                   "-scaling_cells %" PetscInt_FMT ": 2N = %" PetscInt_FMT " > -floquet_mf_dense_max %" PetscInt_FMT
                   ": the scaling needs every multiplier (the dense route); raise -floquet_mf_dense_max or take fewer cells",
                   lp.cells, 2 * lp.N(), fmo_.dense_max);
      }
    PetscFunctionReturn(0);
  }
  PetscErrorCode DeclareSolvers(MPI_Comm comm) override
  {
    PetscFunctionBeginUser;
    PetscCall(base_.DeclareSolvers(comm));
    PetscFunctionReturn(0);
  }
  PetscErrorCode CheckResources() override
  {
    PetscFunctionBeginUser;
    for (PetscReal c : so_.cells) { // the largest lattice decides; each is checked
      NnmSetup s;
      Adopt(&s, (PetscInt)c);
      PetscCall(s.CheckResources(comm_));
      PetscCall(CheckDenseMonodromyMemory(comm_, s.lp.N(), fmo_));
    }
    PetscFunctionReturn(0);
  }
  PetscErrorCode Build() override { return 0; } // each size is built in Solve, one at a time
  PetscErrorCode Solve() override
  {
    PetscFunctionBeginUser;
    PetscCall(PetscPrintf(comm_, "nltopo floquet_scaling: branch %s at %zu sizes, E %g .. %g, %zu energy windows\n", so_.branch.c_str(), so_.cells.size(),
                          (double)base_.co.energy_min, (double)base_.co.energy_max, so_.windows.size() - 1));
    for (PetscReal c : so_.cells) {
      const PetscErrorCode ierr = RunSize((PetscInt)c);
      if (IsInterrupt(ierr)) PetscFunctionReturn(ierr); // the sizes done are kept (Interrupted)
      PetscCall(ierr);
    }
    PetscCall(FitWindows());
    PetscFunctionReturn(0);
  }
  bool Interrupted(Interruption *it) const override
  {
    it->partial = !runs_.empty();
    it->where = "after " + std::to_string(runs_.size()) + " of " + std::to_string(so_.cells.size()) + " sizes";
    return true;
  }
  PetscErrorCode Write(PetscViewer v) override
  {
    PetscFunctionBeginUser;
    PetscCall(WriteAttr(v, "/floquet_scaling", "branch", so_.branch.c_str()));
    PetscCall(WriteAttr(v, "/floquet_scaling", "sizes_done", (PetscInt)runs_.size()));
    PetscCall(WriteAttr(v, "/floquet_scaling", "persist_exponent", so_.persist_exponent));
    PetscCall(WriteAttr(v, "/floquet_scaling", "floquet_tol", flo_.tol));
    PetscCall(WriteAttr(v, "/floquet_scaling", "class", so_.instability_class));
    for (const SizeRun &r : runs_) PetscCall(WriteSize(v, r));
    if (fitted_) PetscCall(WriteWindows(v));
    PetscFunctionReturn(0);
  }

private:
  // s takes the options read into base_, with cells per side.
  void Adopt(NnmSetup *s, PetscInt cells) const
  {
    s->lp = base_.lp, s->mo = base_.mo, s->fo = base_.fo, s->so = base_.so, s->co = base_.co;
    s->lp.cells = cells;
  }
  // The branch at one size, continued with the dense Floquet route's hook.
  PetscErrorCode RunSize(PetscInt cells)
  {
    PetscLogDouble t0, t1;
    OwnedVec u;
    PetscReal omega;
    std::string label;
    PetscFunctionBeginUser;
    PetscCall(PetscTime(&t0));
    auto s = std::make_unique<NnmSetup>();
    Adopt(s.get(), cells);
    PetscCall(s->Build(comm_, "-study floquet_scaling"));
    PetscCall(DMCreateGlobalVector(s->lat.SiteDM(), u.out()));
    PetscCall(BranchStart(s->lat, s->modes, so_.branch.c_str(), u, &omega, &label));
    FloquetMfHook hook(s->flow, flo_, fmo_);
    hook.Clear();
    PetscCall(PetscPrintf(comm_, "  [%s, N = %" PetscInt_FMT "]\n", label.c_str(), s->lat.N()));
    PetscCall(hook.Announce());
    SizeRun r;
    r.cells = cells, r.N = s->lat.N();
    const PetscErrorCode ic = ContinueBranch(s->shoot, u, 2 * PETSC_PI / omega, s->co, label.c_str(), &r.b, &hook);
    if (IsInterrupt(ic)) PetscFunctionReturn(ic); // this size is incomplete: left out
    PetscCall(ic);
    PetscCall(PetscTime(&t1));
    r.f = hook.c, r.seconds = t1 - t0;
    r.b.z0.clear(); // the orbits themselves are -study continuation's; only the columns are kept
    PetscCall(PrintFloquetSummary(comm_, label + ", N = " + std::to_string(r.N), r.f, flo_.tol, hook.RouteKind()));
    runs_.push_back(std::move(r));
    PetscFunctionReturn(0);
  }
  // The moduli the envelope takes (-scaling_class c > 0: an orbit whose leading
  // instability has another class counts as |mu| = 1, stable for class c).
  std::vector<PetscReal> ClassModulus(const FloquetColumns &f) const
  {
    std::vector<PetscReal> m = f.max_modulus;
    for (size_t i = 0; i < m.size() && so_.instability_class > 0; i++)
      if (f.instability[i] > 0 && f.instability[i] != so_.instability_class) m[i] = 1;
    return m;
  }
  // Per window: the envelope at each N and its fit, printed.
  PetscErrorCode FitWindows()
  {
    PetscFunctionBeginUser;
    const size_t nw = so_.windows.size() - 1, nn = runs_.size();
    std::vector<PetscReal> N;
    for (const SizeRun &r : runs_) N.push_back((PetscReal)r.N);
    env_.assign(nw * nn, NAN), env_energy_.assign(nw * nn, NAN), env_class_.assign(nw * nn, -1);
    fits_.clear();
    for (size_t w = 0; w < nw; w++) {
      std::vector<PetscReal> e(nn);
      for (size_t k = 0; k < nn; k++) {
        const SizeRun &r = runs_[k];
        const PetscInt i = WindowMaximum(r.b.energy, ClassModulus(r.f), so_.windows[w], so_.windows[w + 1], &e[k]);
        env_[w * nn + k] = e[k];
        if (i >= 0) env_energy_[w * nn + k] = r.b.energy[i], env_class_[w * nn + k] = e[k] > flo_.tol ? r.f.instability[i] : 0;
      }
      fits_.push_back(FitEnvelope(N, e, flo_.tol, so_.persist_exponent));
      const EnvelopeFit &f = fits_.back();
      PetscCall(PetscPrintf(comm_, "  window E in [%g, %g): p = %.3f, C = %.3g, R^2 = %.3f, residual %.2g, %" PetscInt_FMT " of %zu sizes unstable: %s\n",
                            (double)so_.windows[w], (double)so_.windows[w + 1], (double)f.p, (double)f.C, (double)f.r2, (double)f.residual, f.npoints, nn,
                            ScalingVerdictName(f.verdict)));
    }
    fitted_ = true;
    PetscFunctionReturn(0);
  }
  PetscErrorCode WriteSize(PetscViewer v, const SizeRun &r) const
  {
    const std::string g = "/floquet_scaling/cells" + std::to_string(r.cells);
    PetscFunctionBeginUser;
    PetscCall(WriteArray(v, g.c_str(), "energy", r.b.energy));
    PetscCall(WriteArray(v, g.c_str(), "omega", r.b.omega));
    PetscCall(WriteArray(v, g.c_str(), "max_modulus", r.f.max_modulus));
    PetscCall(WriteIntArray(v, g.c_str(), "stable", r.f.stable));
    PetscCall(WriteIntArray(v, g.c_str(), "instability", r.f.instability));
    PetscCall(WriteArray(v, g.c_str(), "leading_participation", r.f.leading_participation));
    PetscCall(WriteArray(v, g.c_str(), "leading_edge_share", r.f.leading_edge));
    PetscCall(WriteAttr(v, g.c_str(), "N", r.N));
    PetscCall(WriteAttr(v, g.c_str(), "cells", r.cells));
    PetscCall(WriteAttr(v, g.c_str(), "points", (PetscInt)r.b.energy.size()));
    PetscCall(WriteAttr(v, g.c_str(), "stop_reason", r.b.stop_reason.c_str()));
    PetscCall(WriteAttr(v, g.c_str(), "seconds", r.seconds));
    PetscFunctionReturn(0);
  }
  PetscErrorCode WriteWindows(PetscViewer v) const
  {
    const char *g = "/floquet_scaling/windows";
    const PetscInt nw = (PetscInt)fits_.size(), nn = (PetscInt)runs_.size();
    std::vector<PetscReal> lo(so_.windows.begin(), so_.windows.end() - 1), hi(so_.windows.begin() + 1, so_.windows.end()), N;
    std::vector<PetscReal> p, C, r2, res, se;
    std::vector<PetscInt> np, verdict;
    PetscFunctionBeginUser;
    for (const SizeRun &r : runs_) N.push_back((PetscReal)r.N);
    for (const EnvelopeFit &f : fits_)
      p.push_back(f.p), C.push_back(f.C), r2.push_back(f.r2), res.push_back(f.residual), se.push_back(f.p_stderr), np.push_back(f.npoints),
          verdict.push_back(f.verdict);
    PetscCall(WriteArray(v, g, "energy_lo", lo));
    PetscCall(WriteArray(v, g, "energy_hi", hi));
    PetscCall(WriteArray(v, g, "N", N));
    PetscCall(WriteArrayND(v, g, "envelope", env_, {nw, nn}));
    PetscCall(WriteArrayND(v, g, "envelope_energy", env_energy_, {nw, nn}));
    PetscCall(WriteIntArray(v, g, "envelope_instability", env_class_, nn, true));
    PetscCall(WriteArray(v, g, "exponent", p));
    PetscCall(WriteArray(v, g, "prefactor", C));
    PetscCall(WriteArray(v, g, "r2", r2));
    PetscCall(WriteArray(v, g, "residual", res));
    PetscCall(WriteArray(v, g, "exponent_stderr", se));
    PetscCall(WriteIntArray(v, g, "npoints", np));
    PetscCall(WriteIntArray(v, g, "verdict", verdict));
    PetscFunctionReturn(0);
  }

  NnmSetup base_; // the options; each size builds its own NnmSetup from them
  FloquetOptions flo_;
  FloquetMfOptions fmo_;
  ScalingOptions so_;
  std::vector<SizeRun> runs_;
  std::vector<PetscReal> env_, env_energy_; // nwindows x nsizes
  std::vector<PetscInt> env_class_;
  std::vector<EnvelopeFit> fits_;
  bool fitted_ = false;
};

} // namespace

StudyContract FloquetScalingStudyContract()
{
  using namespace schema_names;
  return {WithPrefixes({NnmSetup::OptionPrefixes(), {"-floquet", "-scaling_"}}),
          {{"/floquet_scaling",
            "",
            {{"branch", A, S, "scalar", "1", "-scaling_branch"},
             {"sizes_done", A, I, "scalar", "1", "lattice sizes whose branch is written (fewer than -scaling_cells: interrupted)"},
             {"persist_exponent", A, R, "scalar", "1", "-scaling_persist_exponent: the verdict's threshold on p"},
             {"floquet_tol", A, R, "scalar", "1", "-floquet_tol: an orbit is unstable beyond 1 + this"},
             {"class", A, I, "scalar", "1", "-scaling_class: the instability class the envelopes take, 0 any, 1 B-B, 2 B-E, 3 E-E"}}},
           {"/floquet_scaling/cells<c>",
            "",
            {{"energy", D, R, "npts", "energy", "total energy of each orbit of the branch at this size"},
             {"omega", D, R, "npts", "rad/time", "orbit frequency"},
             {"max_modulus", D, R, "npts", "1", "largest nontrivial |mu| (dense route)"},
             {"stable", D, I, "npts", "1", "1 if max |mu| <= 1 + tol", codes::kStable},
             {"instability", D, I, "npts", "1", "the leading instability's class, 0 stable, 1 B-B, 2 B-E, 3 E-E", codes::kInstability},
             {"leading_participation", D, R, "npts", "sites", "participation ratio of the leading eigenvector's displacement (as /continuation/<branch>)"},
             {"leading_edge_share", D, R, "npts", "1", "edge share of the leading eigenvector's displacement norm (as /continuation/<branch>)"},
             {"N", A, I, "scalar", "1", "sites"},
             {"cells", A, I, "scalar", "1", "cells per side"},
             {"points", A, I, "scalar", "1", "npts"},
             {"stop_reason", A, S, "scalar", "1", "why the branch ended"},
             {"seconds", A, R, "scalar", "s", "wall time of this size (set-up, branch, Floquet)"}}},
           {"/floquet_scaling/windows",
            "",
            {{"energy_lo", D, R, "nwin", "energy", "window's lower edge (included)"},
             {"energy_hi", D, R, "nwin", "energy", "window's upper edge (excluded)"},
             {"N", D, R, "nsizes", "1", "the sizes, ascending"},
             {"envelope", D, R, "nwin x nsizes", "1", "largest |mu| - 1 over the window's orbits at each N (of -scaling_class only when given; NaN: no orbit in the window)"},
             {"envelope_energy", D, R, "nwin x nsizes", "energy", "energy of the orbit that sets it"},
             {"envelope_instability", D, I, "nwin x nsizes", "1", "its class, 0 stable (at most tol), 1 B-B, 2 B-E, 3 E-E; -1 no orbit", codes::kInstability},
             {"exponent", D, R, "nwin", "1", "p of the least-squares fit envelope ~ C N^-p in log-log, over the N with envelope > tol (NaN: fewer than two)"},
             {"prefactor", D, R, "nwin", "1", "C"},
             {"r2", D, R, "nwin", "1", "coefficient of determination of the log-log fit (near 0 also when p is near 0: read the residual)"},
             {"residual", D, R, "nwin", "1", "root mean square of ln(envelope / (C N^-p)) over the fitted points"},
             {"exponent_stderr", D, R, "nwin", "1", "standard error of p (NaN with two points or fewer)"},
             {"npoints", D, I, "nwin", "1", "sizes fitted: those with an unstable orbit in the window"},
             {"verdict", D, I, "nwin", "1", "the window's scaling verdict", kScalingVerdictCodes}}}}};
}

std::unique_ptr<Study> CreateFloquetScalingStudy() { return std::make_unique<FloquetScalingStudy>(); }

} // namespace nltopo
