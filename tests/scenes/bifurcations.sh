# -cont_bifurcations (on with -floquet): events along the insulated branch of
# options/fep.opts, located between its points. Checked against the stored
# Floquet data itself (each located change of stability lies between two
# points whose multipliers show it, to -cont_bif_tol in omega), against the
# Krein rule (a Hamiltonian-Hopf pair has opposite signatures, a pass equal
# ones), internal resonances (odd orders only on these symmetric orbits, on the
# root, with stored circle multipliers near it on either side) and across
# 1 and 2 ranks; the FEP plot marks the events. Then -cont_switch at the
# branch point of the small lattice: the two families born there start at the
# located point, carry the parent and are time-reversal images of each other.
source "$(dirname "$0")/common.bash"
run1 -options_file "$SRC/options/fep.opts" -cont_branch insulated -cont_energy_max 300 -cont_verbose 0 -output paper.h5 | tee paper.txt
small="-cont_branch insulated -lattice_cells 5 -cont_energy_max 300 -cont_verbose 0"
run1 -options_file "$SRC/options/fep.opts" $small -output s1.h5 > s1.txt
run2 -options_file "$SRC/options/fep.opts" $small -output s2.h5 > s2.txt
run1 -options_file "$SRC/options/fep.opts" $small -cont_bif_passes 0 -cont_bif_resonance_order 0 -output s0.h5 > s0.txt
grep -q "event .*: branch point (+1) E-E, instability begins at omega 2.41824" paper.txt
$PY "$SRC/tests/scenes/plot_check.py" "$SRC/src/plots/plot_fep.py" paper.h5 fep.png
$PY - <<'PYEOF'
import h5py, numpy as np
def load(fn):
    b = h5py.File(fn, "r")["continuation/insulated"]
    return b, b["bifurcations"]
b, e = load("paper.h5")
tol = e.attrs["tol"]
assert tol == 1e-7 and e.attrs["probes"] > 0
n = e["kind"].shape[0]
for k in ("kind", "energy", "omega", "s", "multiplier_re", "multiplier_im", "direction", "point", "instability", "omega_bracket"):
    assert e[k].shape == (n,), k
assert e["krein"].shape == (n, 2) and e["resonance"].shape == (n, 2) and e["vector"].shape == (n, 204) and e["kind"].dtype.kind == "i"
w, kind, d, pt = e["omega"][:], e["kind"][:], e["direction"][:], e["point"][:]
assert np.all(e["omega_bracket"][:] <= tol)
assert np.all(np.diff(e["s"][:]) >= 0)   # in the order of the branch
omega = b["omega"][:]
mu = b["multipliers_re"][:] + 1j * b["multipliers_im"][:]
for i in range(n):
    # each event lies between the two points it is reported after
    lo, hi = sorted((omega[pt[i]], omega[pt[i] + 1]))
    assert lo - tol <= w[i] <= hi + tol, (i, w[i], lo, hi)
    v = e["vector"][i]
    assert abs(np.linalg.norm(v) - 1) < 1e-10
    if kind[i] == 5:  # Hamiltonian-Hopf: two pairs of opposite Krein signature collide
        assert e["krein"][i][0] * e["krein"][i][1] == -1, (i, e["krein"][i])
        assert abs(abs(e["multiplier_re"][i] + 1j * e["multiplier_im"][i]) - 1) < 1e-3
    if kind[i] == 4:  # Krein collision that passes: equal signatures, on the circle
        assert e["krein"][i][0] == e["krein"][i][1] != 0
    if kind[i] == 6:  # internal resonance: an odd order (the NNM has the half-period symmetry), on the root
        p, q = e["resonance"][i]
        assert q >= 3 and q % 2 == 1 and 0 < 2 * p < q, (p, q)
        th = 2 * np.pi * p / q
        assert abs(e["multiplier_re"][i] - np.cos(th)) < 1e-12 and abs(e["multiplier_im"][i] - np.sin(th)) < 1e-12
        # the stored points on either side hold a circle multiplier near the root (the count below it
        # is no check: bulk multipliers cross it too, and only edge ones are located by default)
        for j in (pt[i], pt[i] + 1):
            m = mu[j][(np.abs(np.abs(mu[j]) - 1) < 1e-6) & (mu[j].imag > 0)]
            assert np.abs(np.angle(m) - th).min() < 0.1, (i, j)
    else:
        assert tuple(e["resonance"][i]) == (0, 0)
# the weak B-E collisions of omega 1.7-1.9 (paper: B-E instabilities below the optical band)
be = [(w[i], d[i]) for i in range(n) if kind[i] == 5 and e["instability"][i] == 2 and 1.7 < w[i] < 1.9]
assert len(be) >= 4, be
# the real E-E instability: one branch point, located to tol, where the stored points turn unstable
bp = [i for i in range(n) if kind[i] == 2]
assert len(bp) == 1, bp
# the 1:3 internal resonance of the edge pair below the branch point (omega 2.0275, E 34)
res = [i for i in range(n) if kind[i] == 6 and abs(w[i] - 2.027498) < 1e-5]
assert len(res) == 1 and tuple(e["resonance"][res[0]]) == (1, 3) and e["instability"][res[0]] == 3, res
i = bp[0]
assert d[i] == 1 and e["instability"][i] == 3 and abs(w[i] - 2.418248) < 1e-5, w[i]
assert abs(e["multiplier_re"][i] - 1) < 1e-3 and e["multiplier_im"][i] == 0
before, after = mu[pt[i]], mu[pt[i] + 1]
assert np.abs(before).max() < 1 + 1e-6                                  # stable before
assert np.any((np.abs(after.imag) < 1e-12) & (after.real > 1.1))        # a real pair beyond
# 1 and 2 ranks: the same events on the small lattice
(_, e1), (_, e2) = load("s1.h5"), load("s2.h5")
k1, k2 = e1["kind"][:], e2["kind"][:]
assert len(k1) > 0 and np.array_equal(k1, k2), (k1, k2)
assert np.abs(e1["omega"][:] - e2["omega"][:]).max() < 2 * tol
assert np.array_equal(e1["direction"][:], e2["direction"][:])
# Passes and resonances (kinds 4, 6) are found apart from the changes of stability: without them the
# other events are the same ones, at the same omega
(_, e0) = load("s0.h5")
k0, keep = e0["kind"][:], ~np.isin(k1, (4, 6))
assert not np.isin(k0, (4, 6)).any() and np.array_equal(k0, k1[keep]), (k0, k1)
assert np.abs(e0["omega"][:] - e1["omega"][:][keep]).max() < 2 * tol
assert np.isin(k1, (4,)).sum() >= 1 and np.isin(k1, (6,)).sum() >= 1   # N = 22: E-E passes and 1:3 resonances
# each resonance of the small lattice (every multiplier counts there): the stored spectra on either
# side of its segment differ in how many lie below the root, by at least as many as are located there
b1 = h5py.File("s1.h5", "r")["continuation/insulated"]
mu1 = b1["multipliers_re"][:] + 1j * b1["multipliers_im"][:]
for r in np.flatnonzero(k1 == 6):
    p, q = e1["resonance"][r]
    th, j = 2 * np.pi * p / q, e1["point"][r]
    below = [((np.abs(np.abs(m) - 1) < 1e-6) & (m.imag > 0) & (np.angle(m) < th)).sum() for m in (mu1[j], mu1[j + 1])]
    same = [k for k in np.flatnonzero(k1 == 6) if e1["point"][k] == j and tuple(e1["resonance"][k]) == (p, q)]
    assert abs(below[1] - below[0]) >= len(same), (r, below, same)   # (crossings no harmonic drives count too)
print("bifurcations scene OK:", n, "events, E-E branch point at omega", w[i])
open("bp_index.txt", "w").write(str(int([k for k in range(len(k1)) if k1[k] == 2][0])))
PYEOF
bp=$(cat bp_index.txt)
run1 -options_file "$SRC/options/fep.opts" $small -cont_switch insulated:$bp -output sw.h5 > sw.txt
$PY "$SRC/tests/scenes/plot_check.py" "$SRC/src/plots/plot_fep.py" sw.h5 sw.png
$PY - "$bp" <<'PYEOF'
import h5py, sys, numpy as np
bp = int(sys.argv[1])
C = h5py.File("sw.h5", "r")["continuation"]
P, e = C["insulated"], C["insulated/bifurcations"]
N = P["z0"].shape[1] // 2
for side in ("plus", "minus"):
    b = C[f"insulated_bp{bp}_{side}"]
    assert b.attrs["parent"] in (f"insulated:{bp}", f"insulated:{bp}".encode())
    assert b.attrs["reached_energy_max"] == 1 and b["energy"].shape[0] > 5
    # it starts at the located point: the parent's orbit there, at rest (v = 0 on the parent family)
    assert abs(b["omega"][0] - e["omega"][bp]) < 1e-6 and abs(b["energy"][0] / e["energy"][bp] - 1) < 1e-6
    assert np.abs(b["z0"][0, N:]).max() < 1e-6 * np.abs(b["z0"][0, :N]).max()
    # and leaves the parent family: its orbits are not at rest at the section (the parent's all are)
    assert np.all(np.abs(b["z0"][1:, N:]).max(axis=1) > 1e-3 * np.abs(b["z0"][1:, :N]).max(axis=1))
    assert "bifurcations" in b and "multipliers_re" in b
pl, mi = C[f"insulated_bp{bp}_plus"], C[f"insulated_bp{bp}_minus"]
n = min(pl["energy"].shape[0], mi["energy"].shape[0])
# the two sides are time-reversal images: same u0, opposite v0, same frequency-energy curve
assert np.abs(pl["z0"][:n, :N] - mi["z0"][:n, :N]).max() < 1e-6 * np.abs(pl["z0"][:n, :N]).max()
assert np.abs(pl["z0"][:n, N:] + mi["z0"][:n, N:]).max() < 1e-6 * np.abs(pl["z0"][:n, :N]).max()
assert np.abs(pl["omega"][:n] - mi["omega"][:n]).max() < 1e-7   # two continuations: rounding apart
print("branch switching OK:", pl["energy"].shape[0], "points on each side from omega", pl["omega"][0])
PYEOF
# -cont_switch at a period doubling. The lattice's own NNM families have none (x(t + T/2) = -x(t):
# M is the square of the half-period map, README "Branch switching"); the switched family above
# breaks that symmetry and has period-doubling windows. Switching at the first onset on its _plus
# side (in the same run: insulated:<bp>,insulated_bp<bp>_plus:<pd>) starts the doubled-period family
# insulated_bp<bp>_plus_pd<pd>: at the located point, at half its frequency, with period_multiple 2.
pd=$($PY - "$bp" <<'PYEOF'
import h5py, sys
e = h5py.File("sw.h5", "r")[f"continuation/insulated_bp{sys.argv[1]}_plus/bifurcations"]
k = [i for i in range(e["kind"].shape[0]) if e["kind"][i] == 3 and e["direction"][i] == 1]
assert k, "no period doubling on the switched family"
print(k[0])
PYEOF
)
# (named by kind and omega here: the checks below and the resume's bit-for-bit comparison with the
# run named by index show that both select the same events and give the same families)
wbp=$($PY -c "import h5py; print('%.9g' % h5py.File('sw.h5', 'r')['continuation/insulated/bifurcations/omega'][$bp])")
wpd=$($PY -c "import h5py; print('%.9g' % h5py.File('sw.h5', 'r')['continuation/insulated_bp${bp}_plus/bifurcations/omega'][$pd])")
run1 -options_file "$SRC/options/fep.opts" $small -cont_switch insulated:bp@$wbp,insulated_bp${bp}_plus:pd@$wpd -output pd.h5 > pd.txt
$PY "$SRC/tests/scenes/plot_check.py" "$SRC/src/plots/plot_fep.py" pd.h5 pd.png
$PY - "$bp" "$pd" <<'PYEOF'
import h5py, sys, numpy as np
bp, pd = sys.argv[1], int(sys.argv[2])
C = h5py.File("pd.h5", "r")["continuation"]
P = C[f"insulated_bp{bp}_plus"]
e = P["bifurcations"]
assert e["kind"][pd] == 3 and e["multiplier_re"][pd] < -1
D = C[f"insulated_bp{bp}_plus_pd{pd}"]
assert f"insulated_bp{bp}_plus_pd{pd}_plus" not in C and f"insulated_bp{bp}_plus_pd{pd}_minus" not in C  # one family
assert D.attrs["parent"] in (f"insulated_bp{bp}_plus:{pd}", f"insulated_bp{bp}_plus:{pd}".encode())
assert D.attrs["period_multiple"] == 2 and P.attrs["period_multiple"] == 1 and C["insulated"].attrs["period_multiple"] == 1
n = D["energy"].shape[0]
# this family is a closed loop (it rises to a fold, falls to another and retraces itself): it stops where it began
assert n > 5 and D.attrs["stop_reason"] == b"the family closed: it returned to its first orbit", D.attrs["stop_reason"]
# point 0 is the parent's orbit at the located point, traversed twice: half its frequency
assert abs(2 * D["omega"][0] - e["omega"][pd]) < 1e-7 and abs(D["energy"][0] / e["energy"][pd] - 1) < 1e-6
T0 = D["period"][0]
assert np.all(np.abs(D["period"][:] / T0 - 1) < 0.05)  # orbits of about twice the parent's period
# ... whose multipliers are the parent's squared: the pair at -1 joins the trivial pair at +1
mu = D["multipliers_re"][0] + 1j * D["multipliers_im"][0]
assert np.sum(np.abs(mu - 1) < 1e-2) >= 4, np.sort(np.abs(mu - 1))[:6]
# the first step leaves along the critical eigenvector
dz = D["z0"][1] - D["z0"][0]
v = e["vector"][pd]
assert abs(dz @ v) / np.linalg.norm(dz) > 0.9
print("period doubling switching OK:", n, "points from omega", e["omega"][pd], "(", D.attrs["stop_reason"].decode(), ")")
PYEOF
# -cont_resume recreates the switched families: the same run stopped at E = 150 (every branch,
# the doubled family closed below it) and resumed to 300 equals the run to 300 bit for bit
sw2="-cont_switch insulated:$bp,insulated_bp${bp}_plus:$pd"
small150="-cont_branch insulated -lattice_cells 5 -cont_energy_max 150 -cont_verbose 0"
run1 -options_file "$SRC/options/fep.opts" $small150 $sw2 -output r150.h5 > r150.txt
run1 -options_file "$SRC/options/fep.opts" $small $sw2 -cont_resume r150.h5 -output r300.h5 > r300.txt
grep -q "\[insulated_bp${bp}_plus_pd$pd\] -cont_resume r150.h5: [0-9]* points of the family born at the period doubling" r300.txt
$PY - <<'PYEOF'
import h5py, numpy as np
A, B, H = (h5py.File(f, "r")["continuation"] for f in ("pd.h5", "r300.h5", "r150.h5"))
assert sorted(A.keys()) == sorted(B.keys()) and len(A.keys()) == 4, (list(A.keys()), list(B.keys()))
for n in A.keys():
    a, b = A[n], B[n]
    if n != "insulated" and "_pd" not in n:
        assert H[n]["energy"].shape[0] < a["energy"].shape[0], n   # resumed, not recomputed whole
    for k in ("energy", "omega", "z0", "multipliers_re", "multipliers_im", "bifurcations/omega", "bifurcations/kind"):
        assert np.array_equal(a[k][:], b[k][:]), (n, k)
    for k in ("parent", "period_multiple", "stop_reason"):
        assert a.attrs[k] == b.attrs[k], (n, k)
print("resume of the switched families OK:", {n: B[n]["energy"].shape[0] for n in B.keys()})
PYEOF
