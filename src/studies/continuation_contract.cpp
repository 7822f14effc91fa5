// -study continuation's contract (studies/registry.hpp): the prefixes of its
// options and the schemas of /continuation, which the record binds
// (studies/continuation_record.cpp).
#include "studies/nnm_setup.hpp"
#include "studies/registry.hpp"
#include "studies/continuation_record.hpp"

namespace nltopo {

// The leading eigenvector's columns (issue 35, scaling with N), in both Floquet variants.
static const char *const kLeadingParticipation =
    "participation ratio of the leading nontrivial eigenvector's displacement over sites, (sum |u_i|^2)^2 / sum |u_i|^4: 1 on one site, N spread "
    "evenly (leading: the largest |mu| beyond 1 + tol, else the circle's nearest +-1; the trivial pair left out); NaN matrix-free";
static const char *const kLeadingEdgeShare =
    "share of the leading nontrivial eigenvector's displacement norm within -floquet_edge_sites of the interface cell (as the instability class "
    "uses it); NaN matrix-free";

// -cont_codim2 (issue 37, stability/codim2.hpp): an event followed in (E, p).
Schema Codim2Schema(const char *path)
{
  using namespace schema_names;
  return {path,
          "",
          {{"p", D, R, "npts", "the parameter's: 1 (-lattice_gamma), stiffness (-lattice_k), stiffness/displacement^2 (-lattice_cubic)",
            "the second parameter (the option the attribute parameter names) at each point, in order along the curve: the side where p first "
            "decreases (reversed), the event (row event_point), the side where it first increases (monotone unless the curve turns in p)"},
           {"energy", D, R, "npts", "energy", "energy of the orbit at the event"},
           {"omega", D, R, "npts", "rad/time", "frequency of the orbit at the event"},
           {"period", D, R, "npts", "time", "period of the orbit at the event"},
           {"test", D, R, "npts", "1",
            "the kind's test function there, 0 on the curve (fold: d ln E / d ln omega along the family at fixed p; branch point: b - 1, "
            "b = (mu + 1/mu)/2 of the nontrivial pair nearest +1; period doubling: "
            "b + 1, b = (mu + 1/mu)/2 of the pair nearest -1; Hamiltonian-Hopf: (b1 - b2)^2 of the colliding pairs' b)"},
           {"multipliers_re", D, R, "npts x 4", "1",
            "the four Floquet multipliers nearest the kind's critical point (+1 for a fold or branch point, -1 for a period doubling; Hamiltonian-Hopf: the "
            "colliding pairs, nearest in b = (mu + 1/mu)/2), nearest first; real part"},
           {"multipliers_im", D, R, "npts x 4", "1", "the same multipliers, imaginary part"},
           {"max_modulus", D, R, "npts", "1", "largest |mu| of the orbit"},
           {"point_kind", D, I, "npoints", "1",
            "the curve's codim-2 points, in order along it: its two ends (rows 0 and npts - 1), classified when a side collapsed (the colliding "
            "pairs' b within 1e-2 of +-1, or E below 1e-2 of the event's), and each turn in p located between two rows",
            codes::kCodim2Point},
           {"point_p", D, R, "npoints", "as p", "the parameter at each codim-2 point"},
           {"point_energy", D, R, "npoints", "energy", "the energy of the orbit at each codim-2 point"},
           {"point_omega", D, R, "npoints", "rad/time", "the frequency of the orbit at each codim-2 point"},
           {"point_arc", D, R, "npoints", "1",
            "where each codim-2 point lies along the curve: a fractional row r + f, f the fraction of the arclength step from row r to r + 1 (turns: "
            "located by regula falsi on the step's arclength to -cont_codim2_tol)"},
           {"parameter", A, S, "scalar", "1", "the second parameter's option: -lattice_gamma, -lattice_k or -lattice_cubic (-cont_codim2_parameter)"},
           {"kind", A, I, "scalar", "1", "the kind of event the curve continues, in the codes of /bifurcations kind", codes::kEventKind},
           {"event", A, I, "scalar", "1", "the event's row in /continuation/<branch>/bifurcations"},
           {"event_point", A, I, "scalar", "1", "the row of the curve at the event itself (the run's own p)"},
           {"stop_reason", A, S, "scalar", "1", "why the curve ended on each side of the event (p decreasing: ...; p increasing: ...)"},
           {"solves", A, I, "scalar", "1", "orbits solved to follow the curve"},
           {"seconds", A, R, "scalar", "s", "wall time of the curve"}}};
}

// The Krein resonance map (issue 35 item 4, stability/krein_map.hpp): written with -floquet (either route).
static Schema KreinMapSchema()
{
  using namespace schema_names;
  return {"/continuation/<branch>/krein_map",
          "",
          {{"open", D, I, "npts x kmax", "1",
            "opposite-signature resonances w_q + w_q' = k Omega (Omega = 2 pi / period) that the linear dispersion allows at each orbit (row) for k = 1..kmax "
            "(column): the sum of the bits of the open pair classes (A acoustic band, O optical band, E localised linear mode of edge_omega)",
            codes::kKreinPairs},
           {"edge_omega", D, R, "nedge", "rad/time",
            "the E modes: the finite lattice's linear frequencies outside both infinite-lattice bands, the branch's own linear mode left out"},
           {"energy_criterion", D, I, "npts", "1", "where dE/dOmega changes sign along the branch (energy criterion, PRL 117, 094101 (2016))",
            codes::kEnergyCriterion},
           {"dE_domega", D, R, "npts", "energy/(rad/time)", "dE/dOmega by the central difference along the branch (one-sided at its ends)"},
           {"kmax", A, I, "scalar", "1", "the largest k with a possible resonance on the branch (columns of open)"},
           {"pair_classes", A, S, "scalar", "1", "the pair classes in bit order (bit 0 first)"}}};
}

StudyContract ContinuationStudyContract()
{
  using namespace schema_names;
  return {
      WithPrefixes({NnmSetup::OptionPrefixes(), {"-floquet"}}),
      {{"/continuation", "", WithBandEdges({})},
       {"/continuation/<branch>",
        "",
        {{"energy", D, R, "npts", "energy", "total energy of each orbit"},
         {"omega", D, R, "npts", "rad/time", "orbit frequency"},
         {"period", D, R, "npts", "time", "orbit period"},
         {"mcr", D, R, "npts", "1", "MCR of u0"},
         {"newton_its", D, R, "npts", "1", "Newton iterations"},
         {"krylov_its", D, R, "npts", "1", "GMRES iterations (0: dense LU)"},
         {"shape_corr", D, R, "npts", "1", "shape correlation with the previous orbit"},
         {"beta", D, R, "npts", "energy", "unfolding parameter (energy defect)"},
         {"z0", D, R, "npts x 2N", "[u: displacement, v: displacement/time]", "initial state [u, v] of each orbit"},
         {"interactions", D, R, "ninter", "1", "indices of points flagged as modal interactions"},
         {"next_tangent", D, R, "2N + 2", "[du: displacement, dv: displacement/time, dT: time, dbeta: energy]",
          "family tangent after the last point (du, dv, dT, dbeta), for -cont_resume"},
         {"next_ds", D, R, "1", "1", "the next step length, for -cont_resume"},
         {"linear_omega", A, R, "scalar", "rad/time", "linear frequency the branch starts from (a switched branch: the event's omega on its parent)"},
         {"parent", A, S, "scalar", "1",
          "-cont_switch: the branch point or period doubling the branch starts from, <branch>:<event>; empty for a linear mode's branch"},
         {"period_multiple", A, I, "scalar", "1",
          "its orbits last this many periods of the parent's orbit at the event (2: born at a period doubling; omega = 2 pi / period, plotted at period_multiple x omega); 1 otherwise"},
         {"stop_reason", A, S, "scalar", "1", "why the branch ended"},
         {"reached_energy_max", A, I, "scalar", "1", "1 if -cont_energy_max was reached", codes::kYesNo},
         {"points", A, I, "scalar", "1", "npts"},
         {"jacobian_evaluations", A, I, "scalar", "1", "shooting Jacobians"},
         {"residual_evaluations", A, I, "scalar", "1", "shooting residuals"},
         {"tangent_products", A, I, "scalar", "1", "tangent products"},
         {"krylov_iterations", A, I, "scalar", "1", "GMRES iterations"},
         {"seconds", A, R, "scalar", "s", "wall time of the branch"}}},
       {"/continuation/<branch>",
        "floquet",
        {{"multipliers_re", D, R, "npts x 2N", "1", "Floquet multipliers, real part"},
         {"multipliers_im", D, R, "npts x 2N", "1", "Floquet multipliers, imaginary part"},
         {"krein", D, I, "npts x 2N", "1", "Krein signature in {-1, 0, 1}", codes::kKrein},
         {"max_modulus", D, R, "npts", "1", "largest |mu|"},
         {"det_error", D, R, "npts", "1", "|det M - 1|"},
         {"stable", D, I, "npts", "1", "1 if max |mu| <= 1 + tol", codes::kStable},
         {"instability", D, I, "npts", "1", "0 none, 1 B-B, 2 B-E, 3 E-E", codes::kInstability},
         {"verdict", D, I, "npts", "1", "the orbit's stability verdict (docs/long-lattices.md, Verdicts)", codes::kVerdict},
         {"verdict_bound", D, R, "npts", "1",
          "stable: -floquet_tol; stable-to: delta, nothing beyond 1 + delta; unstable-*: |mu| - 1 of the confirmed multiplier; unresolved: the largest "
          "|mu| - 1 not excluded (inf: no bound)"},
         {"verdict_efold", D, R, "npts", "periods", "unstable-*: e-folding time of the growth, 1 / ln|mu|, in periods of the orbit; inf otherwise"},
         {"verdict_reason", D, S, "npts", "1", "how the route reached the verdict, one line (the multiplier, the class, the confirmation)"},
         // issue 35: the leading eigenvector's extent
         {"leading_participation", D, R, "npts", "sites", kLeadingParticipation},
         {"leading_edge_share", D, R, "npts", "1", kLeadingEdgeShare}}},
       {"/continuation/<branch>/bifurcations",
        "",
        {{"kind", D, I, "nevents", "1",
          "1 energy fold, 2 branch point (+1), 3 period doubling (-1), 4 Krein collision, 5 Hamiltonian-Hopf, 6 internal resonance", codes::kEventKind},
         {"energy", D, R, "nevents", "energy", "energy at the located event (middle of the final bracket)"},
         {"omega", D, R, "nevents", "rad/time", "frequency at the located event"},
         {"s", D, R, "nevents", "1", "arclength from the first point, |dX| summed over (z0, T, beta)"},
         {"multiplier_re", D, R, "nevents", "1", "the critical multiplier just off the circle, real part (fold: 1)"},
         {"multiplier_im", D, R, "nevents", "1", "the critical multiplier, imaginary part (upper half plane)"},
         {"krein", D, I, "nevents x 2", "1",
          "Krein signatures of the colliding pairs' upper-half-plane members on the circle side (+1/-1: the pair's two members)", codes::kKrein},
         {"vector", D, R, "nevents x 2N", "[u: displacement, v: displacement/time]",
          "the critical eigenvector of M [u, v], unit norm, phase turned real (fold: the family tangent)"},
         {"direction", D, I, "nevents", "1", "+1: an instability begins along the branch (fold: E maximum), -1: it ends (fold: E minimum)", codes::kDirection},
         {"point", D, I, "nevents", "1", "the continuation point the event follows"},
         {"instability", D, I, "nevents", "1", "localisation of the critical eigenvector: 1 B-B, 2 B-E, 3 E-E (0: fold)", codes::kInstability},
         {"omega_bracket", D, R, "nevents", "rad/time", "width in omega of the final bracket"},
         {"resonance", D, I, "nevents x 2", "1", "internal resonance (kind 6): p, q of the root of unity exp(2 pi i p/q) crossed; 0 0 otherwise"},
         {"tol", A, R, "scalar", "1", "-cont_bif_tol"},
         {"probes", A, I, "scalar", "1", "orbits solved to locate the events"},
         {"seconds", A, R, "scalar", "s", "wall time of the location"}}},
       {"/continuation/<branch>",
        "floquet_mf",
        {{"multipliers_re", D, R, "npts x nev", "1",
          "leading multipliers (|mu| >= 1 of each pair), real part; NaN: not converged, rejected by its true residual, or fewer pairs than nev"},
         {"multipliers_im", D, R, "npts x nev", "1", "leading multipliers, imaginary part"},
         {"max_modulus", D, R, "npts", "1", "largest |mu| (NaN: not converged)"},
         {"krein", D, I, "npts x nev", "1", "Krein signatures of the leading multipliers as in the dense route (dense route only; 0 matrix-free)",
          codes::kKrein},
         {"instability", D, I, "npts", "1", "the leading instability's class, 0 stable, 1 B-B, 2 B-E, 3 E-E (dense route only); -1 not computed (matrix-free)",
          codes::kInstability},
         {"stable", D, I, "npts", "1",
          "1 stable (dense route only), 0 unstable (a multiplier beyond 1 + tol), -1 not decided (matrix-free: a complex quadruplet cannot be excluded)",
          codes::kStable},
         {"verdict", D, I, "npts", "1", "the orbit's stability verdict (docs/long-lattices.md, Verdicts)", codes::kVerdict},
         {"verdict_bound", D, R, "npts", "1",
          "stable: -floquet_tol; stable-to: delta, nothing beyond 1 + delta; unstable-*: |mu| - 1 of the confirmed multiplier; unresolved: the largest "
          "|mu| - 1 not excluded (inf: no bound)"},
         {"verdict_efold", D, R, "npts", "periods", "unstable-*: e-folding time of the growth, 1 / ln|mu|, in periods of the orbit; inf otherwise"},
         {"verdict_reason", D, S, "npts", "1", "how the route reached the verdict, one line (the multiplier, the class, the confirmation)"},
         {"floquet_products", A, I, "scalar", "1", "monodromy products (tangent integrations; the dense route: 2N columns per orbit)"},
         {"floquet_unconverged", A, I, "scalar", "1", "orbits with unconverged multipliers"},
         {"floquet_undecided", A, I, "scalar", "1", "orbits with stable = -1"},
         {"floquet_route", A, S, "scalar", "1", "dense (2N <= -floquet_mf_dense_max), matrix-free, or localized (-floquet_mf_which localized)"},
         // issue 35: the leading eigenvector's extent (dense route; NaN matrix-free)
         {"leading_participation", D, R, "npts", "sites", kLeadingParticipation},
         {"leading_edge_share", D, R, "npts", "1", kLeadingEdgeShare}}},
       Codim2Schema("/continuation/<branch>/codim2/<curve>"),
       KreinMapSchema()}};
}

} // namespace nltopo
