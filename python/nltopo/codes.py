"""Integer codes: parsing the `codes` attribute (format >= 1) and the built-in
table of their meanings for format-0 files, which carry none.

A `codes` string is "v meaning; v meaning; ...": parts separated by "; ", the
first token of each part the integer value. A meaning's short name is the
meaning without its parenthesised remark ("branch point (+1)" -> "branch point").
"""
import re

# The meanings the writer gives them (src/io/schema.hpp, namespace codes);
# format 0 files are decoded with these.
YES_NO = "1 yes; 0 no"
DONE = "1 computed; 0 not run (stop signal or not reached yet)"
STABLE = "1 stable; 0 unstable; -1 not decided"
KREIN = "1 positive signature; -1 negative signature; 0 not defined (real multiplier or below -floquet_krein_tol)"
INSTABILITY = ("0 none; 1 B-B (critical eigenvector in the bulk); 2 B-E (between bulk and edge); "
               "3 E-E (at the interface edge); -1 not computed")
EVENT_KIND = ("1 energy fold; 2 branch point (+1); 3 period doubling (-1); 4 Krein collision (pass); "
              "5 Hamiltonian-Hopf; 6 internal resonance")
DIRECTION = "1 an instability begins along the branch (fold: E maximum); -1 it ends (fold: E minimum); 0 neither (a Krein pass)"
VERDICT = ("-1 not computed (resumed from a file written before verdicts); 0 stable (dense route: every multiplier within 1 + tol); "
           "1 unstable-localized (a multiplier beyond 1 + delta, eigenvector at the interface, confirmed by k-period integration); "
           "2 unstable-extended (the same, extended eigenvector); 3 stable-to (nothing beyond 1 + verdict_bound); "
           "4 unresolved (verdict_reason says why)")
PREDICTABLE = "1 predictable; 0 unpredictable (twin statistics); -1 not checked (no -sweep_mcr_tol)"
REGIME = ("0 regular (lyapunov x window below -sweep_lyapunov_efolds); 1 chaotic, the MCR statistically predictable (an ergodic average; "
          "or not checked without -sweep_mcr_tol); 2 unpredictable (the twins spread beyond -sweep_mcr_tol); -1 not computed "
          "(no -sweep_lyapunov, E* not reached, or failed)")
SCALING_VERDICT = ("0 stable (no orbit of the window unstable at any N); 1 persists (p < -scaling_persist_exponent); 2 finite-size "
                   "(p >= it); 3 undetermined (fewer than two N with an unstable orbit, or the threshold within one standard error of p)")
# the codim-2 points of a -cont_codim2 curve (/continuation/<branch>/codim2/<curve> point_kind)
CODIM2_POINT = ("0 end of the curve (a bound, -cont_codim2_max_points or step collapse: stop_reason); 1 turn in p (dp/ds = 0, the curve goes on); "
                "2 Hamiltonian-Hopf end at b = +1 (1:1 resonance); 3 Hamiltonian-Hopf end at b = -1 (1:2 resonance); 4 linear limit (E -> 0)")
# the stability map (/stabilitymap): its regions, which side of a curve is unstable, whether a check orbit agrees
REGION = "0 stable; 1 B-B unstable; 2 B-E unstable; 3 E-E unstable"
CURVE_SIDE = "1 left of its direction of travel; -1 right; 0 unknown (no direction, or vertical at its event)"
AGREE = ("1 the map's label equals the orbit's class; 0 it does not; -1 not compared (within -smap_same_curve_rtol of a curve, or "
         "outside [-smap_energy_min, -cont_energy_max])")
# the Krein resonance map (/continuation/<branch>/krein_map): open is a bitmask, the sum of its classes' bits
KREIN_PAIRS = ("0 none; 1 AA (acoustic + acoustic); 2 AO (acoustic + optical); 4 OO (optical + optical); "
               "8 EA (localised + acoustic); 16 EO (localised + optical); "
               "32 EE (localised + localised, crossed since the previous orbit)")
ENERGY_CRITERION = ("0 no sign change; 1 E extremum (dE/dOmega through 0: a real pair through +1); "
                    "2 Omega extremum (dE/dOmega through infinity); 3 both")

# (group pattern, name) -> codes, for format 0. A pattern segment "<...>" or
# "case<k>" stands for any name (the schema's convention).
FORMAT0 = {
    ("/", "complete"): YES_NO,
    ("/continuation/<branch>", "stable"): STABLE,
    ("/continuation/<branch>", "instability"): INSTABILITY,
    ("/continuation/<branch>", "krein"): KREIN,
    ("/continuation/<branch>", "verdict"): VERDICT,  # (format 1 on; listed so the table knows every code)
    ("/continuation/<branch>", "reached_energy_max"): YES_NO,
    ("/continuation/<branch>/codim2/<curve>", "kind"): EVENT_KIND,
    ("/continuation/<branch>/codim2/<curve>", "point_kind"): CODIM2_POINT,  # (format 1 on)
    ("/continuation/<branch>/bifurcations", "kind"): EVENT_KIND,
    ("/continuation/<branch>/bifurcations", "direction"): DIRECTION,
    ("/continuation/<branch>/bifurcations", "instability"): INSTABILITY,
    ("/continuation/<branch>/bifurcations", "krein"): KREIN,
    ("/stability/case<k>", "floquet_stable"): YES_NO,
    ("/stability/case<k>", "instability"): INSTABILITY,
    ("/stability/case<k>", "verdict"): VERDICT,
    ("/stability/case<k>", "persisted"): YES_NO,
    ("/stability/case<k>", "omega_replaced"): YES_NO,
    ("/stabilitymap/cells<c>", "region"): REGION,  # (format 1 on: -study stabilitymap)
    ("/stabilitymap/cells<c>", "branch_instability"): INSTABILITY,
    ("/stabilitymap/cells<c>", "event_kind"): EVENT_KIND,
    ("/stabilitymap/cells<c>", "event_class"): INSTABILITY,
    ("/stabilitymap/cells<c>", "event_direction"): DIRECTION,
    ("/stabilitymap/cells<c>", "curve_kind"): EVENT_KIND,
    ("/stabilitymap/cells<c>", "curve_class"): INSTABILITY,
    ("/stabilitymap/cells<c>", "curve_direction"): DIRECTION,
    ("/stabilitymap/cells<c>", "curve_side"): CURVE_SIDE,
    ("/stabilitymap/cells<c>/curves/<curve>", "kind"): EVENT_KIND,
    ("/stabilitymap/cells<c>/curves/<curve>", "point_kind"): CODIM2_POINT,
    ("/stabilitymap/checks/<check>", "instability"): INSTABILITY,
    ("/stabilitymap/checks/<check>", "map_label"): REGION,
    ("/stabilitymap/checks/<check>", "agree"): AGREE,
    ("/stabilitymap/checks/<check>", "event_kind"): EVENT_KIND,
    ("/stabilitymap/checks/<check>", "event_class"): INSTABILITY,
    ("/stabilitymap/checks/<check>", "event_direction"): DIRECTION,
    ("/floquet_scaling/cells<c>", "stable"): STABLE,
    ("/floquet_scaling/cells<c>", "instability"): INSTABILITY,
    ("/floquet_scaling/windows", "envelope_instability"): INSTABILITY,
    ("/floquet_scaling/windows", "verdict"): SCALING_VERDICT,
    ("/sweep", "reached"): YES_NO,
    ("/sweep", "failed"): YES_NO,
    ("/sweep", "predictable"): PREDICTABLE,
    ("/sweep", "done"): DONE,
    ("/sweep", "kcorr_computed"): YES_NO,
    ("/sweep", "regime"): REGIME,  # (format 1 on)
    ("/sweep", "lyapunov_computed"): YES_NO,
    ("/sweep/refined", "reached"): YES_NO,  # -sweep_refine_from
    ("/sweep/refined", "failed"): YES_NO,
    ("/sweep/refined", "predictable"): PREDICTABLE,
    ("/sweep/refined", "done"): DONE,
    ("/sweep/refined", "regime"): REGIME,
    ("/zak", "reached"): YES_NO,
    ("/zak", "done"): DONE,
    ("/perturb/<kind>", "done"): DONE,
    ("/simulate", "energy_reached"): YES_NO,
    ("/workprecision", "reference_converged"): YES_NO,
    ("/continuation/<branch>/krein_map", "open"): KREIN_PAIRS,
    ("/continuation/<branch>/krein_map", "energy_criterion"): ENERGY_CRITERION,
}

_PART = re.compile(r";\s*(?=-?\d+\s)")


def parse(text):
    """{int: meaning} of a codes string "v meaning; v meaning; ..."."""
    out = {}
    for part in _PART.split(text.strip()):
        part = part.strip()
        if not part:
            continue
        value, _, meaning = part.partition(" ")
        try:
            out[int(value)] = meaning.strip()
        except ValueError:
            raise ValueError(f"codes {text!r}: part {part!r} does not begin with an integer") from None
    return out


def short(meaning):
    """A meaning without its parenthesised remark: "B-B (critical ...)" -> "B-B"."""
    return meaning.split(" (")[0].strip()


def _segment_matches(pattern, name):
    lt, gt = pattern.find("<"), pattern.find(">")
    if lt < 0 or gt < lt:
        return pattern == name
    pre, post = pattern[:lt], pattern[gt + 1:]
    return len(name) > len(pre) + len(post) and name.startswith(pre) and name.endswith(post)


def group_matches(pattern, path):
    """Whether a written group path matches a schema group pattern."""
    p = [s for s in pattern.split("/") if s]
    q = [s for s in path.split("/") if s]
    return len(p) == len(q) and all(_segment_matches(a, b) for a, b in zip(p, q))


def format0(group, name):
    """The built-in codes string of a field of a format-0 file, or None."""
    for (pattern, n), text in FORMAT0.items():
        if n == name and group_matches(pattern, group):
            return text
    return None
