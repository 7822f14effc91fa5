# options/fep_long.opts (matrix-free inexact-Newton shooting with the
# averaged-stiffness preconditioner) on shortened lattices: the insulated branch
# of N = 102 and of N = 1002 on 2 ranks lie on the dense-Jacobian branch of
# N = 102 (the localized mode barely feels the lattice end) with GMRES
# iterations per Newton step that do not grow with N; the matrix-free Floquet
# multipliers of the N = 102 branch (trivial pair deflated) lead with the
# left-end edge mode's pair, b = (mu + 1/mu)/2 = cos(2 pi sqrt(3) / omega): that
# mode (omega = sqrt(3), model.md "Trap") lies where the orbit's amplitude is
# ~1e-9, so its multipliers are the linear ones, and up to E ~ 1 its b is the
# largest nontrivial |b| (N = 102 dense spectra).
source "$(dirname "$0")/common.bash"
common=(-cont_energy_max 3 -cont_verbose 0 -cont_max_change 0.2)
# the dense reference with small steps, past E = 3 (the mf branches' last step may overshoot it by ~40 %):
# interpolated to the mf points (their steps differ: inexact Newton)
run1 -options_file "$SRC/options/fep.opts" -cont_branch insulated -floquet 0 -cont_energy_max 5 -cont_verbose 0 -cont_max_change 0.04 -output dense.h5 > dense.txt
run1 -options_file "$SRC/options/fep_long.opts" -lattice_cells 25 -floquet 0 "${common[@]}" -output mf102.h5 > mf102.txt
run2 -options_file "$SRC/options/fep_long.opts" -lattice_cells 250 -floquet 0 "${common[@]}" -output mf1002.h5 > mf1002.txt
# the matrix-free route (forced at this N by -floquet_mf_dense_max 0), with enough eigensolver restarts that every multiplier converges
run1 -options_file "$SRC/options/fep_long.opts" -lattice_cells 25 -cont_energy_max 1 -cont_verbose 0 -cont_max_change 0.2 -floquet_mf_eps_max_it 40 -floquet_mf_dense_max 0 -output floquet.h5 > floquet.txt
# issue 20's check at N = 102: fep_long.opts as shipped to E = 20 (2N = 204 <= -floquet_mf_dense_max: the
# dense leading pairs) on 2 ranks, against the full dense analysis (-floquet_mf 0: every multiplier, SLEPc) and
# against the matrix-free route on the same branch
long20=(-options_file "$SRC/options/fep_long.opts" -lattice_cells 25 -cont_energy_max 20 -cont_checkpoint_seconds 0)
run2 "${long20[@]}" -output lead20.h5 > lead20.txt
run1 "${long20[@]}" -floquet_mf 0 -output dense20.h5 > dense20.txt
run1 "${long20[@]}" -floquet_mf_dense_max 0 -output mf20.h5 > mf20.txt
# Krylov-Schur on M (largest) with these settings called a spurious |mu| = 306.9 converged at E = 1.86
# (benchmarks/README.md); the true-residual check must keep it from becoming an "unstable" verdict
run1 "${long20[@]}" -cont_energy_max 2 -floquet_mf_dense_max 0 -floquet_mf_which largest -floquet_mf_eps_ncv 60 -floquet_mf_eps_max_it 30 -output largest.h5 > largest.txt
# -cont_resume on 2 ranks: the E <= 1 branch above, continued to E = 3 (with
# the numerics it was computed with: a resume refuses others), without the
# multipliers (-floquet 0: their options then do not count)
run2 -options_file "$SRC/options/fep_long.opts" -lattice_cells 25 -floquet 0 "${common[@]}" -cont_resume floquet.h5 -output resumed.h5 > resumed.txt
grep -q "resumed after point" resumed.txt
$PY - <<'PYEOF'
import h5py, numpy as np
g = lambda f: h5py.File(f, "r")["continuation/insulated"]
D, A, B, F, R = g("dense.h5"), g("mf102.h5"), g("mf1002.h5"), g("floquet.h5"), g("resumed.h5")
# the resumed branch keeps the points it was given, bit for bit, and goes on along the same family
n0 = len(F["energy"])
assert len(R["energy"]) > n0 + 1 and np.array_equal(R["energy"][:n0], F["energy"][:]) and np.array_equal(R["z0"][:n0], F["z0"][:]), len(R["energy"])
assert R["energy"][n0] > F["energy"][-1]
for X in (A, B, R):
    assert X.attrs["reached_energy_max"] == 1
    # same orbits as the dense route: omega at the mf energies, by 4-point Lagrange interpolation in log E
    led, wd = np.log(D["energy"][:]), D["omega"][:]
    matched, worst = 0, 0.0
    for e, w in zip(X["energy"][:], X["omega"][:]):
        k = min(max(np.searchsorted(led, np.log(e)) - 2, 0), len(led) - 4)
        xs, ys, x = led[k:k + 4], wd[k:k + 4], np.log(e)
        wi = sum(ys[i] * np.prod([(x - xs[j]) / (xs[i] - xs[j]) for j in range(4) if j != i]) for i in range(4))
        worst = max(worst, abs(w - wi) / wi)
        matched += 1
    assert worst < 1e-7, worst
    assert matched >= 20, matched
    if X == R: print("resumed branch: %d + %d points on the dense N = 102 branch to %.1e" % (n0, len(R["energy"]) - n0, worst))
    assert X["energy"][-1] <= D["energy"][-1], (X["energy"][-1], D["energy"][-1])   # no extrapolation
    # the Krylov count of a resumed run covers its new points only
    per_newton = X.attrs["krylov_iterations"] / X["newton_its"][n0 if X == R else 0:].sum()
    assert per_newton < 20, per_newton
    print("mf branch:", len(X["energy"]), "points on the dense N = 102 branch to %.1e; GMRES per Newton step" % worst, round(per_newton, 1))
ka, kb = A.attrs["krylov_iterations"], B.attrs["krylov_iterations"]
assert kb <= 1.2 * ka + 10, (ka, kb)   # N = 1002 needs no more Krylov iterations than N = 102
mm, w = F["max_modulus"][:], F["omega"][:]
assert F["multipliers_re"].shape == (len(mm), 1)   # -floquet_mf_nev 1: the leading nontrivial pair
assert F.attrs["floquet_route"] == b"matrix-free" or F.attrs["floquet_route"] == "matrix-free", F.attrs["floquet_route"]
# matrix-free, all on the circle: no verdict (a complex quadruplet inside the spectrum cannot be excluded)
assert np.all(np.abs(mm - 1) < 1e-4) and np.all(F["stable"][:] == -1) and F.attrs["floquet_undecided"] == len(mm), mm
mu = F["multipliers_re"][:] + 1j * F["multipliers_im"][:]
b = ((mu + 1 / mu) / 2).real
b_edge = np.cos(2 * np.pi * np.sqrt(3) / w)
# where the edge pair is distinguishable from the (deflated) trivial pair b = 1, up to E ~ 1
sel = (1 - b_edge > 1e-6) & (w < 1.76)
assert sel.sum() >= 6, sel.sum()
err = np.abs(b[sel, 0] - b_edge[sel]).max()
assert err < 1e-8, err
print("matrix-free Floquet, E <= 1: max |mu| - 1 = %.1e; nontrivial pair = edge mode's to %.1e (%d orbits)" % (np.abs(mm - 1).max(), err, sel.sum()))

# N = 102 to E = 20: the leading pair against every dense multiplier of the same orbits
L, D20, M20 = g("lead20.h5"), g("dense20.h5"), g("mf20.h5")
route = lambda X: X.attrs["floquet_route"].decode() if isinstance(X.attrs["floquet_route"], bytes) else X.attrs["floquet_route"]
assert route(L) == "dense" and route(M20) == "matrix-free", (route(L), route(M20))
n = len(D20["energy"])
assert n >= 20 and len(L["energy"]) == n and len(M20["energy"]) == n, (n, len(L["energy"]), len(M20["energy"]))
assert np.allclose(L["energy"][:], D20["energy"][:], rtol=1e-8, atol=0)   # 2 ranks: the same orbits
mu = D20["multipliers_re"][:] + 1j * D20["multipliers_im"][:]
unstable_quads = 0
for i in range(n):
    m = mu[i][np.argsort(np.abs(mu[i] - 1))][2:]      # the trivial pair: the two nearest 1
    lead = m[np.argmax(np.abs(m))]
    ref_stable = np.abs(lead) <= 1 + 1e-4
    assert abs(L["max_modulus"][i] - np.abs(lead)) < 1e-6, (i, L["max_modulus"][i], np.abs(lead))
    assert L["stable"][i] == int(ref_stable) == D20["stable"][i], (i, L["stable"][i], D20["stable"][i])
    # the leading pair's Krein signature: that of the same multiplier in the full analysis
    lm = L["multipliers_re"][i, 0] + 1j * L["multipliers_im"][i, 0]
    j = np.argmin(np.abs(mu[i] - lm))
    assert abs(mu[i][j] - lm) < 1e-6 and L["krein"][i, 0] == D20["krein"][i, j], (i, lm, L["krein"][i, 0], D20["krein"][i, j])
    assert L["instability"][i] == D20["instability"][i], (i, L["instability"][i], D20["instability"][i])
    if not ref_stable:   # the kind: the leading multiplier itself (complex: a Krein-collision quadruplet)
        assert abs(abs(lm) - abs(lead)) < 1e-6 and (abs(lead.imag) > 1e-6) == (abs(lm.imag) > 1e-6), (i, lm, lead)
        if abs(lead.imag) > 1e-6:
            unstable_quads += 1
            assert M20["stable"][i] == -1, (i, M20["stable"][i])   # matrix-free: never "stable" here
    assert M20["stable"][i] in (-1, 0) and M20["instability"][i] == -1, (M20["stable"][i], M20["instability"][i])
assert unstable_quads >= 3, unstable_quads   # E = 0.94, 1.86, 3.72 (benchmarks/README.md)
G = g("largest.h5")
ng = len(G["energy"])
assert np.allclose(G["energy"][:], D20["energy"][:ng], rtol=1e-8, atol=0)
for i in range(ng):   # "unstable" only where the dense route says so, and never the spurious value
    assert G["stable"][i] in (-1, 0) and (G["stable"][i] == -1 or D20["stable"][i] == 0), (i, G["stable"][i], D20["stable"][i])
    assert not np.isfinite(G["max_modulus"][i]) or G["max_modulus"][i] < 1.1, (i, G["max_modulus"][i])
assert "spurious Ritz values rejected" in open("largest.txt").read()
print("N = 102 to E = 20: dense leading pairs on 2 ranks = full dense analysis at %d orbits (%d unstable quadruplets); matrix-free: %d not decided"
      % (n, unstable_quads, (M20["stable"][:] == -1).sum()))
PYEOF
# -cont_resume of -floquet_mf files written before the verdicts (no floquet_route, krein or instability;
# stable = 1 meant only max |mu| <= 1 + tol): made from mf20.h5 by removing what the old files lacked
$PY - <<'PYEOF'
import h5py, numpy as np, shutil
for name, strip_option in (("old_mf.h5", False), ("old_mf_noopt.h5", True)):
    shutil.copy("mf20.h5", name)
    with h5py.File(name, "r+") as f:
        g = f["continuation/insulated"]
        for k in ("krein", "instability"): del g[k]
        for a in ("floquet_route", "floquet_undecided"): del g.attrs[a]
        st = np.ones_like(g["stable"][:]); del g["stable"]; g["stable"] = st
        if strip_option:   # an old file has no -floquet_mf_dense_max: at N = 102 this run's route is dense
            o = f.attrs["options"]; o = o.decode() if isinstance(o, bytes) else o
            f.attrs["options"] = np.bytes_(o.replace(" -floquet_mf_dense_max 0", ""))
PYEOF
run2 "${long20[@]}" -cont_energy_max 30 -floquet_mf_dense_max 0 -cont_resume old_mf.h5 -output resumed_mf.h5 > resumed_mf.txt
if run1 "${long20[@]}" -cont_energy_max 30 -cont_resume old_mf_noopt.h5 -output mixed.h5 > mixed.txt 2>&1; then echo "resume across routes not refused"; exit 1; fi
grep -q "computed by the matrix-free route, this run would take the dense one" mixed.txt && test ! -e mixed.h5
$PY - <<'PYEOF'
import h5py, numpy as np
R = h5py.File("resumed_mf.h5", "r")["continuation/insulated"]
n0 = len(h5py.File("mf20.h5", "r")["continuation/insulated/energy"])
assert len(R["energy"]) > n0
# the old stable = 1 is not a verdict: not decided; no class was computed
assert np.all(R["stable"][:] == -1) and np.all(R["instability"][:] == -1) and R.attrs["floquet_undecided"] == len(R["energy"]), R["stable"][:]
print("resumed an old -floquet_mf file: %d orbits, all not decided" % len(R["energy"]))
PYEOF
$PY "$SRC/tests/scenes/plot_check.py" "$SRC/src/plots/plot_fep.py" floquet.h5 floquet.png > /dev/null
$PY "$SRC/tests/scenes/plot_check.py" "$SRC/src/plots/plot_floquet.py" floquet.h5 multipliers.png > /dev/null
# the figure tells the verdicts apart: matrix-free orbits are "not decided", the dense leading pairs have classes
$PY "$SRC/tests/scenes/plot_check.py" "$SRC/src/plots/plot_floquet.py" mf20.h5 mf20.png > mf20_plot.txt
grep -qE "orbits by class: not decided \(matrix-free: a Krein quadruplet is not excluded\) [0-9]+$" mf20_plot.txt
$PY "$SRC/tests/scenes/plot_check.py" "$SRC/src/plots/plot_floquet.py" lead20.h5 lead20.png > lead20_plot.txt
grep -qE "orbits by class: stable [0-9]+, B-B 2, B-E 1$" lead20_plot.txt   # the three quadruplets (full analysis: B-E, B-B, B-B)
test -s floquet.png
