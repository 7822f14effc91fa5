// -study perturb: robustness of the insulated mode to random spring
// perturbations (paper, "Robustness to perturbations"), as ensembles. For each
// kind (chiral, achiral), level delta and realisation (seed), the lattice's
// linear insulated frequency and the MCR of forced runs at the interface site
// at the unperturbed insulated NNM's frequency omega(E*) for every E* of the
// grid. Runs spread over the ranks (each realisation on one rank, all its
// energies). Output: /perturb/<kind> of outputs.md.
#include "bands/linear_modes.hpp"
#include "core/errors.hpp"
#include "core/log.hpp"
#include "core/option_table.hpp"
#include "core/options_audit.hpp"
#include "core/signals.hpp"
#include "core/work_queue.hpp"
#include "io/input.hpp"
#include "io/output.hpp"
#include "studies/forced_scene.hpp"
#include "studies/grid_axis.hpp"
#include "studies/nnm_setup.hpp"
#include "studies/registry.hpp"
#include "studies/study.hpp"
#include "timeint/simulation.hpp"
#include <algorithm>
#include <cmath>

namespace nltopo {

namespace {

struct PerturbOptions {
  std::vector<PetscReal> delta{0, 0.01, 0.025, 0.05, 0.1, 0.25};
  std::vector<std::string> kind_names{"chiral", "achiral"}; // -perturb_kinds, as given
  std::vector<Perturbation> kinds{Perturbation::Chiral, Perturbation::Achiral};
  // the energy grid (-perturb_energy_*: studies/grid_axis.hpp), made from its fields after the table's Read
  PetscReal energy_min = 1e-2, energy_max = 1e2;
  PetscInt energy_n = 9;
  AxisSpacing energy_spacing = AxisSpacing::Log;
  std::vector<PetscReal> energy_list, energy;
  PetscInt ensemble = 16, seed0 = 1;
  std::string fep;
};

// omega(E) on the insulated branch, linear in log E between stored orbits.
PetscReal BranchOmega(const std::vector<PetscReal> &E, const std::vector<PetscReal> &w, PetscReal e)
{
  if (e <= E.front()) return w.front();
  for (size_t k = 1; k < E.size(); k++)
    if (E[k] >= e) {
      const PetscReal s = std::log(e / E[k - 1]) / std::log(E[k] / E[k - 1]);
      return w[k - 1] + s * (w[k] - w[k - 1]);
    }
  return w.back();
}

// The linear insulated frequency of a (perturbed) lattice: among the eigenpairs
// in the middle 60 % of the gap (omega^2 within 0.3 (k_hat - |k1 - k2|..k_hat +
// |k1 - k2|) of k_hat, away from band-edge modes that disorder may localise), the
// one with the largest weight within 10 sites of the interface site.
PetscErrorCode InsulatedOmega(const Lattice &lat, const LinearModes &modes, PetscReal *w)
{
  PetscFunctionBeginUser;
  const PetscInt m = lat.Params().InterfaceSite(), N = lat.N();
  const PetscReal kh = lat.Params().KHat(), gap = std::abs(lat.Params().K1() - lat.Params().K2());
  const PetscReal lo = std::sqrt(kh - 0.6 * gap), hi = std::sqrt(kh + 0.6 * gap);
  PetscReal best = -1;
  *w = NAN;
  for (size_t j = 0; j < modes.Omega().size(); j++) {
    if (modes.Omega()[j] < lo || modes.Omega()[j] > hi) continue;
    const PetscScalar *a;
    PetscCall(VecGetArrayRead(modes.Mode((PetscInt)j), &a)); // serial lattice: all sites
    PetscReal s = 0;
    for (PetscInt i = std::max<PetscInt>(0, m - 10); i <= std::min(N - 1, m + 10); i++) s += a[i] * a[i];
    PetscCall(VecRestoreArrayRead(modes.Mode((PetscInt)j), &a));
    if (s > best) best = s, *w = modes.Omega()[j];
  }
  PetscFunctionReturn(0);
}

const GridAxisFields<PerturbOptions> kEnergyAxis = {"energy",
                                                    &PerturbOptions::energy_min,
                                                    &PerturbOptions::energy_max,
                                                    &PerturbOptions::energy_n,
                                                    &PerturbOptions::energy_spacing,
                                                    &PerturbOptions::energy_list};

const auto &kPerturbTable = DeclareOptionTable<PerturbOptions>("perturb_", "Perturbation ensembles", [](OptionTable<PerturbOptions> &t) {
  t.RealList("delta_list", &PerturbOptions::delta, 64, RightOpen(0, 0.5), "Perturbation levels delta (mean |relative spring change|)")
      .Int("ensemble", &PerturbOptions::ensemble, Closed(1, 100000), "Realisations (seeds) per perturbation level")
      .Int("seed", &PerturbOptions::seed0, Closed(PETSC_MIN_INT, PETSC_MAX_INT), "Seed of the first realisation (realisation r uses seed + r)");
  GridAxisRows(t, kEnergyAxis);
  t.StringList("kinds", &PerturbOptions::kind_names, 2, "Perturbation kinds: chiral, achiral");
  t.String("fep", &PerturbOptions::fep, "Continuation file with /continuation/insulated (omega(E) of the insulated NNM); default: computed here")
      .Default("computed here");
});

// The -perturb_ block (the study sets the spring perturbation, omega_ext and E* itself).
PetscErrorCode PerturbOptionsFromOptions(MPI_Comm comm, PerturbOptions *po)
{
  std::vector<PetscBool> set;
  PetscFunctionBeginUser;
  PetscCall(RejectGivenOptions(comm, {"-sim_progress", "-sim_sample_dt"}, "-study perturb (no progress lines or samples per run)"));
  PetscCall(kPerturbTable.Read(comm, po, &set));
  PetscCheck(!kPerturbTable.Given(set, "delta_list") || !po->delta.empty(), comm, PETSC_ERR_USER, "-perturb_delta_list is empty");
  PetscCheck(!po->kind_names.empty(), comm, PETSC_ERR_USER, "-perturb_kinds is empty (chiral, achiral)");
  po->kinds.clear();
  for (const std::string &k : po->kind_names) {
    PetscCheck(k == "chiral" || k == "achiral", comm, PETSC_ERR_USER, "-perturb_kinds: unknown kind %s (chiral, achiral)", k.c_str());
    po->kinds.push_back(k == "chiral" ? Perturbation::Chiral : Perturbation::Achiral);
  }
  PetscCall(GridAxisFromTable(comm, "perturb_", kPerturbTable, set, *po, kEnergyAxis, &po->energy));
  PetscFunctionReturn(0);
}

// omega(E) of the unperturbed insulated NNM from a continuation file: rank 0
// reads; a missing or unreadable file fails every rank with its one line.
PetscErrorCode ReadInsulatedBranch(MPI_Comm comm, const char *fep, std::vector<PetscReal> *bE, std::vector<PetscReal> *bw)
{
  PetscMPIInt rank;
  PetscInt n = 0;
  char msg[512] = "";
  PetscFunctionBeginUser;
  PetscCallMPI(MPI_Comm_rank(comm, &rank));
  if (!rank) {
    PetscErrorCode ierr = 0;
    char why[480];
    PetscCall(CaptureError(
        [&]() -> PetscErrorCode {
          PetscFunctionBeginUser;
          PetscCall(ReadDoubles(fep, "/continuation/insulated/energy", bE));
          PetscCall(ReadDoubles(fep, "/continuation/insulated/omega", bw));
          PetscFunctionReturn(0);
        },
        &ierr, why, sizeof(why)));
    if (ierr) PetscCall(PetscSNPrintf(msg, sizeof(msg), "-perturb_fep %s: %s", fep, why));
    n = ierr ? -1 : (PetscInt)bE->size();
    if (!ierr && bE->size() != bw->size()) {
      PetscCall(PetscSNPrintf(msg, sizeof(msg), "-perturb_fep %s: /continuation/insulated energy and omega differ in length", fep));
      n = -1;
    }
  }
  PetscCallMPI(MPI_Bcast(&n, 1, MPIU_INT, 0, comm));
  PetscCallMPI(MPI_Bcast(msg, sizeof(msg), MPI_CHAR, 0, comm));
  PetscCheck(n >= 0, comm, PETSC_ERR_FILE_READ, "%s", msg);
  bE->resize(n), bw->resize(n);
  PetscCallMPI(MPI_Bcast(bE->data(), n, MPIU_REAL, 0, comm));
  PetscCallMPI(MPI_Bcast(bw->data(), n, MPIU_REAL, 0, comm));
  PetscFunctionReturn(0);
}

// omega(E) of the unperturbed insulated NNM, continued here up to 1.2 Emax.
PetscErrorCode ContinueInsulatedBranch(MPI_Comm comm, NnmSetup *nnm, PetscReal Emax, std::vector<PetscReal> *bE, std::vector<PetscReal> *bw)
{
  PetscFunctionBeginUser;
  PetscCall(nnm->Build(comm, "-study perturb"));
  PetscCheck(nnm->modes.Insulated(), comm, PETSC_ERR_USER, "-study perturb follows the insulated mode, and this lattice has none: %s",
             NoInsulatedModeReason(nnm->lp).c_str());
  PetscBool verbose_given; // the branch is quiet unless -cont_verbose asks otherwise
  PetscCall(PetscOptionsHasName(NULL, NULL, "-cont_verbose", &verbose_given));
  if (!verbose_given) nnm->co.verbose = PETSC_FALSE;
  nnm->co.energy_max = 1.2 * Emax; // (-cont_energy_max is refused: ReadOptions)
  Branch b;
  const PetscErrorCode ib = ContinueBranch(nnm->shoot, nnm->modes.Insulated(), 2 * PETSC_PI / nnm->modes.Named().insulated_omega, nnm->co, "insulated", &b);
  PetscCheck(!IsInterrupt(ib), comm, PETSC_ERR_SIG, "interrupted by %s while continuing the insulated branch, before the first forced run; no output written",
             SignalName(StopSignalSeen()));
  PetscCall(ib);
  *bE = b.energy, *bw = b.omega;
  PetscFunctionReturn(0);
}

// One item (kind, level, realisation): [insulated omega, MCR at every energy].
PetscErrorCode Realisation(const PerturbOptions &po, const LatticeParams &base, const LinearModesOptions &mo, const ToneBurstOptions &fo,
                           const SimulationOptions &sim, const std::vector<PetscReal> &wext, PetscInt it, PetscReal *row)
{
  const PetscInt nd = (PetscInt)po.delta.size(), ns = po.ensemble, ne = (PetscInt)po.energy.size();
  PetscFunctionBeginUser;
  const PetscInt k = it / (nd * ns), d = (it / ns) % nd, r = it % ns;
  LatticeParams lp = base;
  lp.perturbation = po.kinds[k];
  lp.delta = po.delta[d];
  lp.seed = po.seed0 + r;
  Lattice lat;
  LinearModes modes;
  PetscCall(lat.Setup(PETSC_COMM_SELF, lp));
  PetscCall(modes.Compute(lat, mo));
  PetscCall(InsulatedOmega(lat, modes, &row[0]));
  for (PetscInt e = 0; e < ne; e++) {
    ToneBurstOptions pf = fo;
    pf.omega = wext[e];
    pf.energy = po.energy[e];
    ToneBurst burst;
    SimulationResult sr;
    PetscInt resc;
    PetscCall(RunForced(lat, &modes, pf, sim, NULL, &burst, &sr, &resc));
    row[1 + e] = sr.reached ? sr.mcr : NAN; // a run that never reached E* is not scored
  }
  PetscFunctionReturn(0);
}

// Kind k's datasets from the items' rows, mcr (nd x ne x ns) and insulated
// omega (nd x ns), and its table: MCR mean +- std per level and energy over
// the realisations done (ran: per item, 0 not run; an interrupted study's
// table says how many a row has, and a row with none has no numbers).
PetscErrorCode Tabulate(MPI_Comm comm, const PerturbOptions &po, PetscReal khat, const std::vector<PetscReal> &res, const std::vector<PetscInt> &ran, PetscInt k,
                        std::vector<PetscReal> *mcr, std::vector<PetscReal> *win)
{
  const PetscInt nd = (PetscInt)po.delta.size(), ne = (PetscInt)po.energy.size(), ns = po.ensemble;
  const PetscInt missing = (PetscInt)std::count(ran.begin() + k * nd * ns, ran.begin() + (k + 1) * nd * ns, 0);
  PetscFunctionBeginUser;
  mcr->assign((size_t)nd * ne * ns, 0), win->assign((size_t)nd * ns, 0);
  if (missing)
    PetscCall(PetscPrintf(comm, "  %s: partial result: %" PetscInt_FMT " of %" PetscInt_FMT " realisations not done (interrupted); each row covers those it has\n",
                          PerturbationName(po.kinds[k]), missing, nd * ns));
  PetscCall(PetscPrintf(comm, "  %s: MCR mean +- std over %" PetscInt_FMT " realisations (rows delta, columns E*), and the linear insulated omega\n",
                        PerturbationName(po.kinds[k]), ns));
  PetscCall(PetscPrintf(comm, "    delta \\ E*"));
  for (PetscInt e = 0; e < ne; e++) PetscCall(PetscPrintf(comm, " %13.3g", (double)po.energy[e]));
  PetscCall(PetscPrintf(comm, "   omega_ins mean (max |dev from sqrt 3|)\n"));
  for (PetscInt d = 0; d < nd; d++) {
    PetscReal wsum = 0, wdev = 0;
    PetscInt nrun = 0;
    for (PetscInt r = 0; r < ns; r++) {
      const PetscReal *row = &res[(size_t)((k * nd + d) * ns + r) * (1 + ne)];
      (*win)[d * ns + r] = row[0];
      for (PetscInt e = 0; e < ne; e++) (*mcr)[((size_t)d * ne + e) * ns + r] = row[1 + e];
      if (!ran[(k * nd + d) * ns + r]) continue; // not run: NaN, in no statistic
      nrun++;
      wsum += row[0];
      wdev = std::max(wdev, (PetscReal)std::abs(row[0] - std::sqrt(khat)));
    }
    PetscCall(PetscPrintf(comm, "    %9.4g ", (double)po.delta[d]));
    for (PetscInt e = 0; e < ne; e++) {
      PetscReal s = 0, s2 = 0;
      PetscInt c = 0;
      for (PetscInt r = 0; r < ns; r++) {
        const PetscReal x = (*mcr)[((size_t)d * ne + e) * ns + r];
        if (std::isfinite(x)) s += x, s2 += x * x, c++;
      }
      const PetscReal mean = c ? s / c : NAN, sd = c > 1 ? std::sqrt(std::max<PetscReal>(0, (s2 - c * mean * mean) / (c - 1))) : 0;
      if (c) PetscCall(PetscPrintf(comm, " %6.3f+-%5.3f", (double)mean, (double)sd));
      else PetscCall(PetscPrintf(comm, " %13s", nrun ? "not reached" : "not run")); // no number from runs that gave none
    }
    PetscCall(PetscPrintf(comm, "   %.10f (%.2e)", (double)(nrun ? wsum / nrun : NAN), (double)(nrun ? wdev : NAN)));
    if (nrun < ns) PetscCall(PetscPrintf(comm, "   (%" PetscInt_FMT " of %" PetscInt_FMT " realisations done)", nrun, ns));
    PetscCall(PetscPrintf(comm, "\n"));
  }
  PetscFunctionReturn(0);
}

class PerturbStudy : public Study {
protected:
  PetscErrorCode ReadOptions() override
  {
    PetscFunctionBeginUser;
    // What the options must not combine to is the run's check: declaring_ (-help,
    // the options audit) reads every block whatever they say.
    if (!declaring_) {
      PetscCall(RejectGivenOptions(comm_, {"-lattice_perturbation", "-lattice_delta", "-lattice_seed", "-force_omega", "-force_energy"},
                                   "-study perturb (-perturb_kinds, -perturb_delta_list, -perturb_ensemble, -perturb_energy_*)"));
      PetscCall(RejectGivenOptions(comm_, {"-cont_energy_max"}, "-study perturb (the insulated branch is continued to 1.2 x the largest -perturb_energy_*)"));
    }
    PetscCall(nnm_.ReadOptions(comm_));
    PetscCheck(declaring_ || nnm_.lp.layout == Layout::Interface, comm_, PETSC_ERR_USER,
               "-study perturb follows the insulated mode: -lattice_layout must be interface");
    PetscCall(PerturbOptionsFromOptions(comm_, &po_));
    sc_.lp = nnm_.lp; // the scene's lattice is the NNM's, perturbed per realisation
    PetscCall(sc_.ReadOptions(comm_, declaring_, false, ForcedScene::Modes::Always, NULL));
    sc_.sim.progress = 0;
    sc_.sim.sample_dt = 0;
    PetscFunctionReturn(0);
  }
  PetscErrorCode DeclareSolvers(MPI_Comm comm) override
  {
    PetscFunctionBeginUser;
    PetscCall(nnm_.DeclareSolvers(comm));
    PetscCall(DeclareTS(comm, "sim_")); // -linear_eps_*: NnmSetup's
    PetscFunctionReturn(0);
  }
  PetscErrorCode CheckResources() override
  {
    PetscFunctionBeginUser;
    if (po_.fep.empty()) PetscCall(nnm_.CheckResources(comm_)); // the insulated branch, continued here
    PetscCall(sc_.CheckResources(PETSC_COMM_SELF));             // every realisation: a lattice and its modes on one rank
    PetscFunctionReturn(0);
  }
  // omega(E) of the unperturbed insulated NNM (from -perturb_fep, or continued here), omega_ext at every E*.
  PetscErrorCode Build() override
  {
    std::vector<PetscReal> bE, bw;
    PetscFunctionBeginUser;
    const PetscReal Emax = *std::max_element(po_.energy.begin(), po_.energy.end()), Emin = *std::min_element(po_.energy.begin(), po_.energy.end());
    // (computed here: the branch starts at -cont_energy_min, known before it is continued)
    PetscCheck(!po_.fep.empty() || Emin >= nnm_.co.energy_min * (1 - 1e-6), comm_, PETSC_ERR_USER,
               "-study perturb: E* = %g lies below the insulated branch's first orbit (E = %g, -cont_energy_min): its omega(E) is not known there", (double)Emin,
               (double)nnm_.co.energy_min);
    if (!po_.fep.empty()) PetscCall(ReadInsulatedBranch(comm_, po_.fep.c_str(), &bE, &bw));
    else PetscCall(ContinueInsulatedBranch(comm_, &nnm_, Emax, &bE, &bw));
    PetscCheck(bE.size() >= 2 && bE.back() >= Emax * (1 - 1e-9), comm_, PETSC_ERR_USER,
               "-study perturb: the insulated branch reaches E = %g only, below -perturb_energy_max %g", bE.empty() ? 0.0 : (double)bE.back(), (double)Emax);
    // omega(E) below the branch's first orbit is not known: refused, not read as that orbit's
    PetscCheck(Emin >= bE.front() * (1 - 1e-6), comm_, PETSC_ERR_USER,
               "-study perturb: E* = %g lies below the insulated branch's first orbit (E = %g%s): its omega(E) is not known there", (double)Emin,
               (double)bE.front(), po_.fep.empty() ? ", -cont_energy_min" : ", in -perturb_fep");
    for (PetscReal e : po_.energy) wext_.push_back(BranchOmega(bE, bw, e));
    PetscCall(PetscPrintf(comm_,
                          "nltopo perturb: %" PetscInt_FMT " kind(s) x %" PetscInt_FMT " levels x %" PetscInt_FMT " realisations x %" PetscInt_FMT
                          " energies = %" PetscInt_FMT " forced runs, N = %" PetscInt_FMT "\n",
                          Kinds(), Levels(), po_.ensemble, Energies(), Items() * Energies(), nnm_.lp.N()));
    PetscFunctionReturn(0);
  }
  PetscErrorCode Solve() override
  {
    const PetscInt ne = Energies(), items = Items();
    std::vector<PetscReal> res;
    PetscFunctionBeginUser;
    auto item = [&](PetscInt it, PetscReal *row) { return Realisation(po_, nnm_.lp, nnm_.mo, sc_.fo, sc_.sim, wext_, it, row); };
    const PetscErrorCode irun = RunDistributed(comm_, items, 1 + ne, item, &res, &ran_);
    if (!IsInterrupt(irun)) PetscCall(irun);                                 // a stop signal: the realisations done are written, complete = 0
    if (!std::count(ran_.begin(), ran_.end(), 1)) PetscFunctionReturn(irun); // interrupted before any: nothing to tabulate
    for (PetscInt it = 0; it < items; it++)
      if (!ran_[it]) std::fill(res.begin() + it * (1 + ne), res.begin() + (it + 1) * (1 + ne), NAN); // not run
    mcr_.resize(Kinds()), win_.resize(Kinds());
    for (PetscInt k = 0; k < Kinds(); k++) PetscCall(Tabulate(comm_, po_, nnm_.lp.KHat(), res, ran_, k, &mcr_[k], &win_[k]));
    PetscFunctionReturn(irun);
  }
  bool Interrupted(Interruption *it) const override
  {
    const PetscInt nran = (PetscInt)std::count(ran_.begin(), ran_.end(), 1);
    if (!nran) *it = {false, "before the first realisation ended", ""};
    else *it = {true, "between realisations (" + std::to_string(nran) + " of " + std::to_string(Items()) + " done)", ""};
    return true;
  }
  PetscErrorCode Write(PetscViewer v) override
  {
    const PetscInt nd = Levels(), ne = Energies(), ns = po_.ensemble;
    PetscFunctionBeginUser;
    for (PetscInt k = 0; k < Kinds(); k++) {
      const std::string g = std::string("/perturb/") + PerturbationName(po_.kinds[k]);
      PetscCall(WriteArray(v, g.c_str(), "delta", po_.delta));
      PetscCall(WriteArray(v, g.c_str(), "energy", po_.energy));
      PetscCall(WriteArray(v, g.c_str(), "omega_ext", wext_));
      PetscCall(WriteArrayND(v, g.c_str(), "mcr", mcr_[k], {nd, ne, ns}));
      PetscCall(WriteArrayND(v, g.c_str(), "insulated_omega", win_[k], {nd, ns}));
      PetscCall(WriteIntArray(v, g.c_str(), "done", std::vector<PetscInt>(ran_.begin() + k * nd * ns, ran_.begin() + (k + 1) * nd * ns),
                              ns)); // nd x ns; 0: not run (stop signal)
      PetscCall(WriteAttr(v, g.c_str(), "seed_first", po_.seed0));
      PetscCall(WriteAttr(v, g.c_str(), "rule",
                          "springs change by k delta_b, delta_b uniform in (-2 delta, 2 delta) (docs/model.md); realisation r uses seed seed_first + r"));
    }
    PetscFunctionReturn(0);
  }

private:
  PetscInt Kinds() const { return (PetscInt)po_.kinds.size(); }
  PetscInt Levels() const { return (PetscInt)po_.delta.size(); }
  PetscInt Energies() const { return (PetscInt)po_.energy.size(); }
  PetscInt Items() const { return Kinds() * Levels() * po_.ensemble; } // (kind, level, realisation)

  PerturbOptions po_;
  ForcedScene sc_; // its forcing and integrator options (its lattice: nnm_'s)
  NnmSetup nnm_;
  std::vector<PetscReal> wext_;                   // omega_ext at every E*
  std::vector<PetscInt> ran_;                     // per item; 0: not run (stop signal)
  std::vector<std::vector<PetscReal>> mcr_, win_; // per kind
};

} // namespace

StudyContract PerturbStudyContract()
{
  using namespace schema_names;
  return {WithPrefixes({ForcedScene::OptionPrefixes(), NnmSetup::OptionPrefixes(), {"-perturb_"}}),
          {{"/perturb/<kind>",
            "",
            {{"delta", D, R, "nd", "1", "perturbation levels"},
             {"energy", D, R, "ne", "energy", "target energies E*"},
             {"omega_ext", D, R, "ne", "rad/time", "forcing frequencies"},
             {"mcr", D, R, "nd x ne x nens", "1", "MCR per level, energy, realisation (NaN: missed or not run)"},
             {"insulated_omega", D, R, "nd x nens", "rad/time", "linear insulated frequency per realisation"},
             {"done", D, I, "nd x nens", "1", "0: not run (stop signal)", codes::kDone},
             {"seed_first", A, I, "scalar", "1", "seed of realisation 0"},
             {"rule", A, S, "scalar", "1", "the perturbation rule"}}}}};
}

std::unique_ptr<Study> CreatePerturbStudy() { return std::make_unique<PerturbStudy>(); }

} // namespace nltopo
