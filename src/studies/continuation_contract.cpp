// -study continuation's contract (studies/registry.hpp): the prefixes of its
// options and the schemas of /continuation, which the record binds
// (studies/continuation_record.cpp).
#include "studies/nnm_setup.hpp"
#include "studies/registry.hpp"

namespace nltopo {

StudyContract ContinuationStudyContract()
{
  using namespace schema_names;
  return {WithPrefixes({NnmSetup::OptionPrefixes(), {"-floquet"}}), {
    {"/continuation", "", WithBandEdges({})},
    {"/continuation/<branch>", "",
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
      {"seconds", A, R, "scalar", "wall time of the branch"}}},
    {"/continuation/<branch>", "floquet",
     {{"multipliers_re", D, R, "npts x 2N", "Floquet multipliers, real part"},
      {"multipliers_im", D, R, "npts x 2N", "Floquet multipliers, imaginary part"},
      {"krein", D, I, "npts x 2N", "Krein signature in {-1, 0, 1}"},
      {"max_modulus", D, R, "npts", "largest |mu|"},
      {"det_error", D, R, "npts", "|det M - 1|"},
      {"stable", D, I, "npts", "1 if max |mu| <= 1 + tol"},
      {"instability", D, I, "npts", "0 none, 1 B-B, 2 B-E, 3 E-E"}}},
    {"/continuation/<branch>/bifurcations", "",
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
      {"seconds", A, R, "scalar", "wall time of the location"}}},
    {"/continuation/<branch>", "floquet_mf",
     {{"multipliers_re", D, R, "npts x nev", "leading multipliers (|mu| >= 1 of each pair), real part; NaN: not converged, rejected by its true residual, or fewer pairs than nev"},
      {"multipliers_im", D, R, "npts x nev", "leading multipliers, imaginary part"},
      {"max_modulus", D, R, "npts", "largest |mu| (NaN: not converged)"},
      {"krein", D, I, "npts x nev", "Krein signatures of the leading multipliers as in the dense route (dense route only; 0 matrix-free)"},
      {"instability", D, I, "npts", "the leading instability's class, 0 stable, 1 B-B, 2 B-E, 3 E-E (dense route only); -1 not computed (matrix-free)"},
      {"stable", D, I, "npts", "1 stable (dense route only), 0 unstable (a multiplier beyond 1 + tol), -1 not decided (matrix-free: a complex quadruplet cannot be excluded)"},
      {"floquet_products", A, I, "scalar", "monodromy products (tangent integrations; the dense route: 2N columns per orbit)"},
      {"floquet_unconverged", A, I, "scalar", "orbits with unconverged multipliers"},
      {"floquet_undecided", A, I, "scalar", "orbits with stable = -1"},
      {"floquet_route", A, S, "scalar", "dense (2N <= -floquet_mf_dense_max) or matrix-free"}}}}};
}

} // namespace nltopo
