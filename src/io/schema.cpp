#include "io/schema.hpp"
#include "io/output.hpp"
#include <cstdlib>
#include <cstring>

namespace nltopo {

namespace {

constexpr FieldKind D = FieldKind::Dataset, A = FieldKind::Attribute;
constexpr FieldType R = FieldType::Real, I = FieldType::Int, S = FieldType::String;

const Field kBandEdges[4] = {{"acoustic_bottom_inf", A, R, "scalar", "infinite lattice: acoustic band bottom (rad/s)"},
                             {"acoustic_top_inf", A, R, "scalar", "infinite lattice: acoustic band top"},
                             {"optical_bottom_inf", A, R, "scalar", "infinite lattice: optical band bottom"},
                             {"optical_top_inf", A, R, "scalar", "infinite lattice: optical band top"}};

std::vector<Field> WithBandEdges(std::vector<Field> f)
{
  f.insert(f.end(), std::begin(kBandEdges), std::end(kBandEdges));
  return f;
}

std::vector<Schema> Build()
{
  std::vector<Schema> s;
  s.push_back({"/", "",
               {{"study", A, S, "scalar", "the -study that wrote the file"},
                {"version", A, S, "scalar", "git describe or project version"},
                {"options", A, S, "scalar", "the full options database, to repeat the run"},
                {"wall_seconds", A, R, "scalar", "wall time of the run"},
                {"complete", A, I, "scalar", "1; 0 for a checkpoint, a running sweep or an interrupted run"}}});
  s.push_back({"/cost", "",
               {{"wall_seconds", A, R, "scalar", "wall time of the run"},
                {"<prefix>integrator", A, S, "scalar", "sim_ (forced/free runs) or nnm_ (shooting): TS type and scheme"},
                {"<prefix>accuracy", A, S, "scalar", "fixed step, or rtol and atol"},
                {"<prefix>solves", A, I, "scalar", "time integrations"},
                {"<prefix>steps", A, I, "scalar", "accepted steps"},
                {"<prefix>rejected_steps", A, I, "scalar", "rejected steps"},
                {"<prefix>force_evaluations", A, I, "scalar", "force evaluations over every rank"},
                {"<prefix>dt_min", A, R, "scalar", "smallest fixed step"},
                {"<prefix>dt_max", A, R, "scalar", "largest fixed step"},
                {"error_estimate", A, R, "scalar", "the study's own error estimate, NaN if none"},
                {"error_estimate_of", A, S, "scalar", "what error_estimate measures, none if none"}}});
  s.push_back({"/linear", "",
               {{"omega", D, R, "N", "finite-lattice frequencies, ascending"},
                {"modes", D, R, "N x N", "row j: mode j"},
                {"modes_selected", D, R, "nsel x N", "shift-invert path: the computed modes only"},
                {"insulated_mode", D, R, "N", "the insulated mode"},
                {"insulated_omega", A, R, "scalar", "frequency of the insulated mode"},
                {"interface_omega", A, R, "scalar", "frequency of the interface mode"},
                {"acoustic_top", A, R, "scalar", "finite lattice: acoustic band top"},
                {"optical_bottom", A, R, "scalar", "finite lattice: optical band bottom"},
                {"optical_top", A, R, "scalar", "finite lattice: optical band top"},
                {"interface_index", A, I, "scalar", "mode index of interface_omega (-1: none)"},
                {"acoustic_top_index", A, I, "scalar", "mode index of acoustic_top"},
                {"optical_bottom_index", A, I, "scalar", "mode index of optical_bottom"},
                {"optical_top_index", A, I, "scalar", "mode index of optical_top"},
                {"insulated_cluster", A, I, "scalar", "eigenpairs in the k_hat cluster"},
                {"insulated_residual", A, R, "scalar", "||K x - omega^2 x|| of the insulated mode"},
                {"layout", A, S, "scalar", "lattice layout"},
                {"N", A, I, "scalar", "sites"}}});
  s.push_back({"/linear/bloch", "",
               WithBandEdges({{"q", D, R, "nq", "Bloch wavenumbers"},
                              {"omega_acoustic", D, R, "nq", "acoustic band"},
                              {"omega_optical", D, R, "nq", "optical band"},
                              {"zak_left_acoustic", A, R, "scalar", "Zak phase, left cell, acoustic (wrapped to [-pi/2, 3 pi/2))"},
                              {"zak_left_optical", A, R, "scalar", "Zak phase, left cell, optical"},
                              {"zak_right_acoustic", A, R, "scalar", "Zak phase, right cell, acoustic"},
                              {"zak_right_optical", A, R, "scalar", "Zak phase, right cell, optical"}})});
  s.push_back({"/simulate", "",
               {{"t", D, R, "nt", "sample times"},
                {"energy", D, R, "nt", "total energy"},
                {"u", D, R, "nt x N", "displacements, sub-sampled (with u_stride)"},
                {"rms", D, R, "N", "RMS per site after the cut-off"},
                {"u_stride", A, I, "scalar", "-sim_store_u_stride"},
                {"mcr", A, R, "scalar", "mode confinement ratio"},
                {"t_off", A, R, "scalar", "cut-off time (-1: never)"},
                {"energy_final", A, R, "scalar", "energy at the end"},
                {"nl_ratio", A, R, "scalar", "nonlinear / linear energy"},
                {"rhs_evals", A, I, "scalar", "RHS evaluations of the run"},
                {"rhs_evals_all_attempts", A, I, "scalar", "RHS evaluations of every amplitude attempt"},
                {"steps", A, I, "scalar", "accepted steps"},
                {"rejected_steps", A, I, "scalar", "rejected steps"},
                {"energy_reached", A, I, "scalar", "1 if E* was reached"},
                {"window_start", A, R, "scalar", "start of the RMS window"},
                {"omega_ext", A, R, "scalar", "forcing frequency"},
                {"energy_star", A, R, "scalar", "target energy E*"},
                {"amplitude", A, R, "scalar", "forcing amplitude S"},
                {"amplitude_rule", A, S, "scalar", "how S was chosen"},
                {"amplitude_safety", A, R, "scalar", "-force_amplitude_safety"},
                {"amplitude_rescalings", A, I, "scalar", "repeats with a larger S (-1: E* missed)"},
                {"tau", A, R, "scalar", "burst width"},
                {"t0", A, R, "scalar", "burst centre"},
                {"solve_seconds", A, R, "scalar", "wall time of the solve"}}});
  s.push_back({"/continuation", "", WithBandEdges({})});
  s.push_back({"/continuation/<branch>", "",
               {{"energy", D, R, "npts", "total energy of each orbit"},
                {"omega", D, R, "npts", "orbit frequency"},
                {"period", D, R, "npts", "orbit period"},
                {"mcr", D, R, "npts", "MCR of u0"},
                {"newton_its", D, R, "npts", "Newton iterations"},
                {"krylov_its", D, R, "npts", "GMRES iterations (0: dense LU)"},
                {"shape_corr", D, R, "npts", "shape correlation with the previous orbit"},
                {"beta", D, R, "npts", "unfolding parameter (energy defect)"},
                {"z0", D, R, "npts x 2N", "initial state [u, v] of each orbit"},
                {"interactions", D, R, "ninter", "indices of points flagged as modal interactions"},
                {"next_tangent", D, R, "2N + 2", "family tangent after the last point (du, dv, dT, dbeta), for -cont_resume"},
                {"next_ds", D, R, "1", "the next step length, for -cont_resume"},
                {"linear_omega", A, R, "scalar", "linear frequency the branch starts from (a switched branch: the event's omega on its parent)"},
                {"parent", A, S, "scalar", "-cont_switch: the branch point or period doubling the branch starts from, <branch>:<event>; empty for a linear mode's branch"},
                {"period_multiple", A, I, "scalar", "its orbits last this many periods of the parent's orbit at the event (2: born at a period doubling; omega = 2 pi / period, plotted at period_multiple x omega); 1 otherwise"},
                {"stop_reason", A, S, "scalar", "why the branch ended"},
                {"reached_energy_max", A, I, "scalar", "1 if -cont_energy_max was reached"},
                {"points", A, I, "scalar", "npts"},
                {"jacobian_evaluations", A, I, "scalar", "shooting Jacobians"},
                {"residual_evaluations", A, I, "scalar", "shooting residuals"},
                {"tangent_products", A, I, "scalar", "tangent products"},
                {"krylov_iterations", A, I, "scalar", "GMRES iterations"},
                {"seconds", A, R, "scalar", "wall time of the branch"}}});
  s.push_back({"/continuation/<branch>", "floquet",
               {{"multipliers_re", D, R, "npts x 2N", "Floquet multipliers, real part"},
                {"multipliers_im", D, R, "npts x 2N", "Floquet multipliers, imaginary part"},
                {"krein", D, I, "npts x 2N", "Krein signature in {-1, 0, 1}"},
                {"max_modulus", D, R, "npts", "largest |mu|"},
                {"det_error", D, R, "npts", "|det M - 1|"},
                {"stable", D, I, "npts", "1 if max |mu| <= 1 + tol"},
                {"instability", D, I, "npts", "0 none, 1 B-B, 2 B-E, 3 E-E"}}});
  s.push_back({"/continuation/<branch>/bifurcations", "",
               {{"kind", D, I, "nevents", "1 energy fold, 2 branch point (+1), 3 period doubling (-1), 4 Krein collision, 5 Hamiltonian-Hopf, 6 internal resonance"},
                {"energy", D, R, "nevents", "energy at the located event (middle of the final bracket)"},
                {"omega", D, R, "nevents", "frequency at the located event"},
                {"s", D, R, "nevents", "arclength from the first point, |dX| summed over (z0, T, beta)"},
                {"multiplier_re", D, R, "nevents", "the critical multiplier just off the circle, real part (fold: 1)"},
                {"multiplier_im", D, R, "nevents", "the critical multiplier, imaginary part (upper half plane)"},
                {"krein", D, I, "nevents x 2", "Krein signatures of the colliding pairs' upper-half-plane members on the circle side (+1/-1: the pair's two members)"},
                {"vector", D, R, "nevents x 2N", "the critical eigenvector of M [u, v], unit norm, phase turned real (fold: the family tangent)"},
                {"direction", D, I, "nevents", "+1: an instability begins along the branch (fold: E maximum), -1: it ends (fold: E minimum)"},
                {"point", D, I, "nevents", "the continuation point the event follows"},
                {"instability", D, I, "nevents", "localisation of the critical eigenvector: 1 B-B, 2 B-E, 3 E-E (0: fold)"},
                {"omega_bracket", D, R, "nevents", "width in omega of the final bracket"},
                {"resonance", D, I, "nevents x 2", "internal resonance (kind 6): p, q of the root of unity exp(2 pi i p/q) crossed; 0 0 otherwise"},
                {"tol", A, R, "scalar", "-cont_bif_tol"},
                {"probes", A, I, "scalar", "orbits solved to locate the events"},
                {"seconds", A, R, "scalar", "wall time of the location"}}});
  s.push_back({"/continuation/<branch>", "floquet_mf",
               {{"multipliers_re", D, R, "npts x nev", "leading multipliers (|mu| >= 1 of each pair), real part; NaN: not converged, rejected by its true residual, or fewer pairs than nev"},
                {"multipliers_im", D, R, "npts x nev", "leading multipliers, imaginary part"},
                {"max_modulus", D, R, "npts", "largest |mu| (NaN: not converged)"},
                {"krein", D, I, "npts x nev", "Krein signatures of the leading multipliers as in the dense route (dense route only; 0 matrix-free)"},
                {"instability", D, I, "npts", "the leading instability's class, 0 stable, 1 B-B, 2 B-E, 3 E-E (dense route only); -1 not computed (matrix-free)"},
                {"stable", D, I, "npts", "1 stable (dense route only), 0 unstable (a multiplier beyond 1 + tol), -1 not decided (matrix-free: a complex quadruplet cannot be excluded)"},
                {"floquet_products", A, I, "scalar", "monodromy products (tangent integrations; the dense route: 2N columns per orbit)"},
                {"floquet_unconverged", A, I, "scalar", "orbits with unconverged multipliers"},
                {"floquet_undecided", A, I, "scalar", "orbits with stable = -1"},
                {"floquet_route", A, S, "scalar", "dense (2N <= -floquet_mf_dense_max) or matrix-free"}}});
  s.push_back({"/sweep", "",
               WithBandEdges({{"omega", D, R, "no", "forcing frequencies"},
                              {"energy", D, R, "ne", "target energies E*"},
                              // per point, in the order of the journal (studies/sweep_store.cpp): reals, then ints
                              {"mcr", D, R, "ne x no", "MCR"},
                              {"t_off", D, R, "ne x no", "cut-off time (-1: never)"},
                              {"kcorr", D, R, "ne x no", "0-1 test K (NaN without -sweep_kcorr)"},
                              {"nl_ratio", D, R, "ne x no", "nonlinear / linear energy"},
                              {"amplitude", D, R, "ne x no", "forcing amplitude S"},
                              {"energy_final", D, R, "ne x no", "energy at the end"},
                              {"seconds", D, R, "ne x no", "wall time of the point"},
                              {"mcr_error", D, R, "ne x no", "estimated relative MCR error (-sweep_mcr_tol)"},
                              {"mcr_spread", D, R, "ne x no", "MCR spread over the twins where unpredictable, else 0"},
                              {"reached", D, I, "ne x no", "1 if E* was reached"},
                              {"rescalings", D, I, "ne x no", "amplitude repeats"},
                              {"rhs_evals", D, I, "ne x no", "RHS evaluations of every attempt"},
                              {"steps", D, I, "ne x no", "accepted steps"},
                              {"failed", D, I, "ne x no", "1 if the run stopped with an error"},
                              {"predictable", D, I, "ne x no", "1, 0, or -1 without -sweep_mcr_tol"},
                              {"mcr_runs", D, I, "ne x no", "integrations spent on the point"},
                              {"done", D, I, "ne x no", "1 if the point is computed"},
                              {"points_done", A, I, "scalar", "points computed so far"},
                              {"points_computed", A, I, "scalar", "points computed by this invocation"},
                              {"kcorr_computed", A, I, "scalar", "1 with -sweep_kcorr"},
                              {"mcr_tol", A, R, "scalar", "-sweep_mcr_tol (0: off)"},
                              {"kcorr_nc", A, I, "scalar", "-kcorr_nc"},
                              {"kcorr_sample_dt", A, R, "scalar", "-kcorr_sample_dt"},
                              {"kcorr_rms_fraction", A, R, "scalar", "-kcorr_rms_fraction"},
                              {"kcorr_record", A, R, "scalar", "-kcorr_record"},
                              {"kcorr_lags", A, I, "scalar", "-kcorr_lags"},
                              {"amplitude_rule", A, S, "scalar", "how S was chosen"},
                              {"force_eta", D, R, "N", "forcing profile eta per site, the same at every point (S scales it)"},
                              {"insulated_mode", D, R, "N", "linear insulated mode, the exponential profile's fit target (absent without one)"},
                              {"force_exp_a", A, R, "scalar", "-force_profile exponential: fitted a of eta_n = a e^{b |n - m|} (-1)^{n/2}"},
                              {"force_exp_b", A, R, "scalar", "-force_profile exponential: fitted b (per site)"}})});
  s.push_back({"/zak", "",
               {{"energy", D, R, "ne", "target energies E*"},
                {"phi0_mean", D, R, "ne", "phi_0, mean over cells and windows"},
                {"phi0_median", D, R, "ne", "phi_0, median"},
                {"phipi_mean", D, R, "ne", "phi_pi, mean"},
                {"phipi_median", D, R, "ne", "phi_pi, median"},
                {"theta_mean", D, R, "ne", "phi_pi - phi_0 of the means"},
                {"theta_median", D, R, "ne", "phi_pi - phi_0 of the medians"},
                {"phi0_window_median", D, R, "ne x nwin", "phi_0 median per window"},
                {"phipi_window_median", D, R, "ne x nwin", "phi_pi median per window"},
                {"mcr0", D, R, "ne", "MCR of the mu = 0 run"},
                {"mcrpi", D, R, "ne", "MCR of the mu = pi run"},
                {"reached", D, I, "ne x 2", "1 if E* was reached (mu = 0, pi)"},
                {"done", D, I, "ne x 2", "0: not run (stop signal)"},
                {"energy_threshold", A, R, "scalar", "lowest E where phi_0, phi_pi stop being distinct (-1: never)"},
                {"energy_last_distinct", A, R, "scalar", "highest E below it still distinct"},
                {"omega0", A, R, "scalar", "frequency of the mu = 0 edge mode"},
                {"omegapi", A, R, "scalar", "frequency of the mu = pi edge mode"},
                {"mode0", A, I, "scalar", "linear mode index (0-based, ascending omega) of the mu = 0 edge: the runs' -force_mode_index"},
                {"modepi", A, I, "scalar", "linear mode index of the mu = pi edge"},
                {"samples_per_period", A, I, "scalar", "-zak_samples_per_period"},
                {"theta_tol", A, R, "scalar", "-zak_theta_tol"},
                {"threshold_rule", A, S, "scalar", "the threshold's definition"}}});
  s.push_back({"/perturb/<kind>", "",
               {{"delta", D, R, "nd", "perturbation levels"},
                {"energy", D, R, "ne", "target energies E*"},
                {"omega_ext", D, R, "ne", "forcing frequencies"},
                {"mcr", D, R, "nd x ne x nens", "MCR per level, energy, realisation (NaN: missed or not run)"},
                {"insulated_omega", D, R, "nd x nens", "linear insulated frequency per realisation"},
                {"done", D, I, "nd x nens", "0: not run (stop signal)"},
                {"seed_first", A, I, "scalar", "seed of realisation 0"},
                {"rule", A, S, "scalar", "the perturbation rule"}}});
  s.push_back({"/stability", "", {{"cases_done", A, I, "scalar", "cases written"}}});
  s.push_back({"/stability/case<k>", "",
               {{"t", D, R, "nt", "sample times"},
                {"corr", D, R, "nt", "shape correlation with the NNM"},
                {"mcr", D, R, "nt", "MCR"},
                {"energy", D, R, "nt", "energy"},
                {"multipliers_re", D, R, "2N", "Floquet multipliers, real part"},
                {"multipliers_im", D, R, "2N", "Floquet multipliers, imaginary part"},
                {"omega_target", A, R, "scalar", "-stability_omega"},
                {"omega", A, R, "scalar", "orbit frequency"},
                {"energy", A, R, "scalar", "orbit energy"},
                {"period", A, R, "scalar", "orbit period"},
                {"max_modulus", A, R, "scalar", "largest |mu|"},
                {"floquet_stable", A, I, "scalar", "1 if Floquet-stable"},
                {"instability", A, I, "scalar", "0 none, 1 B-B, 2 B-E, 3 E-E"},
                {"persisted", A, I, "scalar", "1 if the shape persisted"},
                {"corr_tail_min", A, R, "scalar", "min shape correlation over the last 10 %"},
                {"energy_drift", A, R, "scalar", "relative energy drift"}}});
  s.push_back({"/workprecision", "",
               {{"config", D, S, "nc", "the solver configuration as options"},
                {"method", D, S, "nc", "method name"},
                {"accuracy", D, S, "nc", "accuracy setting"},
                {"wall_seconds", D, R, "nc", "median wall time"},
                {"rhs_evals", D, I, "nc", "RHS evaluations"},
                {"steps", D, I, "nc", "accepted steps"},
                {"rejected_steps", D, I, "nc", "rejected steps"},
                {"error_<observable>", D, R, "nc", "relative error against the reference"},
                {"spread_<observable>", A, R, "scalar", "predictability floor"},
                {"reference_change_<observable>", A, R, "scalar", "change between the last two references"},
                {"reference_<observable>", A, R, "scalar", "the reference's value"},
                {"scene", A, S, "scalar", "simulate or shooting"},
                {"reference", A, S, "scalar", "the reference configuration"},
                {"reference_converged", A, I, "scalar", "1 if the reference converged"},
                {"reference_wall_seconds", A, R, "scalar", "wall time of the reference"},
                {"lyapunov", A, R, "scalar", "finite-time Lyapunov estimate (1/s)"},
                {"twins", A, I, "scalar", "-wp_twins"},
                {"twin_eps", A, R, "scalar", "-wp_twin_eps"},
                {"repeats", A, I, "scalar", "-wp_repeats"},
                {"nnm_energy", A, R, "scalar", "shooting scene: orbit energy"},
                {"amplitude", A, R, "scalar", "simulate scene: forcing amplitude"},
                {"omega_ext", A, R, "scalar", "simulate scene: forcing frequency"},
                {"energy_star", A, R, "scalar", "simulate scene: E*"}}});
  s.push_back({"/linear/transition", "",
               {{"gamma", D, R, "ng", "dimerisation values of -linear_gamma_list"},
                {"omega", D, R, "ng x N", "finite-lattice frequencies at each gamma, ascending"},
                {"zak_left", D, R, "ng x 2", "Zak phase of the left cell (intra k2, inter k1): acoustic, optical; NaN where k1 = k2"},
                {"zak_right", D, R, "ng x 2", "Zak phase of the right cell (intra k1, inter k2): acoustic, optical; NaN where k1 = k2"},
                {"bands_inf", D, R, "ng x 4", "infinite lattice at each gamma: acoustic bottom, top, optical bottom, top (rad/s)"},
                {"lambda_min", D, R, "ng", "smallest eigenvalue of K at each gamma (< 0: K not positive definite, omega clamped to 0 there)"},
                {"N", A, I, "scalar", "sites"},
                {"layout", A, S, "scalar", "lattice layout"},
                {"nq", A, I, "scalar", "-linear_nq: the Zak loop uses 2 nq points"},
                {"zak_rule", A, S, "scalar", "how the Zak phases were computed, and what NaN means"}}});
  return s;
}

// -1: not decided yet; NLTOPO_SCHEMA_CHECK or SetSchemaCheck decide (a debug build: on).
int g_check = -1;

bool CheckOn()
{
  if (g_check < 0) {
#if defined(NDEBUG)
    const char *e = std::getenv("NLTOPO_SCHEMA_CHECK");
    g_check = e && *e && std::strcmp(e, "0");
#else
    g_check = 1;
#endif
  }
  return g_check;
}

} // namespace

const std::vector<Schema> &Schemas()
{
  static const std::vector<Schema> s = Build();
  return s;
}

const Schema *FindSchema(const char *group, const char *variant)
{
  for (const Schema &s : Schemas())
    if (!std::strcmp(s.group, group) && !std::strcmp(s.variant, variant)) return &s;
  return nullptr;
}

bool NameMatches(const std::string &pattern, const std::string &name)
{
  const size_t lt = pattern.find('<'), gt = pattern.find('>');
  if (lt == std::string::npos || gt == std::string::npos || gt < lt) return pattern == name;
  const std::string pre = pattern.substr(0, lt), post = pattern.substr(gt + 1);
  return name.size() > pre.size() + post.size() && !name.compare(0, pre.size(), pre) && !name.compare(name.size() - post.size(), post.size(), post);
}

bool GroupMatches(const std::string &pattern, const std::string &path)
{
  size_t p = 0, q = 0;
  while (true) {
    const size_t pe = pattern.find('/', p), qe = path.find('/', q);
    if (!NameMatches(pattern.substr(p, pe - p), path.substr(q, qe - q))) return false;
    if (pe == std::string::npos || qe == std::string::npos) return pe == qe;
    p = pe + 1, q = qe + 1;
  }
}

const Field *FindField(const std::string &group_path, const std::string &name, FieldKind kind)
{
  std::string path = group_path;
  if (path.size() > 1 && path.back() == '/') path.pop_back();
  for (int exact = 1; exact >= 0; exact--) // a name itself before a pattern (reference_converged before reference_<observable>)
    for (const Schema &s : Schemas()) {
      if (!GroupMatches(s.group, path)) continue;
      for (const Field &f : s.fields)
        if (f.kind == kind && (exact ? name == f.name : NameMatches(f.name, name))) return &f;
    }
  return nullptr;
}

const char *KindName(FieldKind k) { return k == FieldKind::Dataset ? "dataset" : "attribute"; }

const char *TypeName(FieldType t) { return t == FieldType::Real ? "real" : t == FieldType::Int ? "int" : "string"; }

void SetSchemaCheck(bool on) { g_check = on; }

PetscErrorCode SchemaCheckWrite(MPI_Comm comm, const char *group, const char *name, FieldKind kind, FieldType type)
{
  PetscFunctionBeginUser;
  if (!CheckOn()) PetscFunctionReturn(0);
  const Field *f = FindField(group, name, kind);
  PetscCheck(f, comm, PETSC_ERR_PLIB, "output schema (src/io/schema.cpp) has no %s %s in group %s: add it there", KindName(kind), name, group);
  PetscCheck(f->type == type, comm, PETSC_ERR_PLIB, "output schema (src/io/schema.cpp): %s %s/%s is %s there, written as %s", KindName(kind), group, name,
             TypeName(f->type), TypeName(type));
  PetscFunctionReturn(0);
}

PetscErrorCode WriteBandEdges(PetscViewer v, const char *group, const BandEdges &be)
{
  const PetscReal values[4] = {be.acoustic_bottom, be.acoustic_top, be.optical_bottom, be.optical_top};
  PetscFunctionBeginUser;
  for (int k = 0; k < 4; k++) PetscCall(WriteAttr(v, group, kBandEdges[k].name, values[k]));
  PetscFunctionReturn(0);
}

} // namespace nltopo
