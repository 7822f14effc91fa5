# -study workprecision -wp_scene shooting (options/workprecision_nnm.opts) on the
# linear lattice (Gamma = 0, N = 22), where the NNM is the linear insulated mode:
# the reference frequency is the eigenfrequency of K (from -study linear), every
# multiplier lies on the unit circle, and the errors fall at each method's order
# (bm4 4, bm6 6) as the steps per period double; the splitting's monodromy is
# symplectic (det M = 1 to rounding); 1 and 2 ranks agree; the figure holds it
# (wp_figure_check.py).
source "$(dirname "$0")/common.bash"
L=(-lattice_cubic 0 -lattice_cells 5)
run1 -study linear "${L[@]}" -output lin.h5 > /dev/null
run1 -options_file "$SRC/options/workprecision_nnm.opts" "${L[@]}" -wp_repeats 1 -output s1.h5 | tee s1.txt
run2 -options_file "$SRC/options/workprecision_nnm.opts" "${L[@]}" -wp_repeats 1 -output s2.h5 > s2.txt
$PY - "$SRC" <<'PYEOF'
import h5py, numpy as np
w = h5py.File("lin.h5", "r")["linear/omega"][:]
g1, g2 = (h5py.File(n, "r")["workprecision"] for n in ("s1.h5", "s2.h5"))
a = g1.attrs
assert (a["scene"].decode() if isinstance(a["scene"], bytes) else a["scene"]) == "shooting"
exact = w[np.argmin(np.abs(w - a["reference_omega"]))]
print("reference omega", a["reference_omega"], "eigenfrequency", exact, "max|mu|", a["reference_max_modulus"])
assert abs(a["reference_omega"] / exact - 1) < 1e-13, (a["reference_omega"], exact)
assert abs(a["reference_max_modulus"] - 1) < 1e-12 and a["reference_converged"] == 1
method = [m.decode() for m in g1["method"][:]]
acc = [x.decode() for x in g1["accuracy"][:]]
e = g1["error_omega"][:]
def err(m, n):
    return e[[k for k in range(len(method)) if method[k] == m and acc[k] == f"{n} steps/period"][0]]
for m, order, steps in (("symsplit bm4", 4, (32, 64, 128)), ("symsplit bm6", 6, (32, 64))):
    for n0, n1 in zip(steps, steps[1:]):
        r = err(m, n0) / err(m, n1)
        print(f"{m}: omega error {n0} -> {n1} steps per period divided by {r:.1f} (2^{order} = {2 ** order})")
        assert 0.7 * 2 ** order < r < 1.4 * 2 ** order, (m, n0, r)
det = g1["error_det"][:]
for k, m in enumerate(method):
    if m.startswith("symsplit"):
        assert det[k] < 1e-12, (m, acc[k], det[k])
for o in ("omega", "closure", "max_modulus", "det"):
    x, y = g1["error_" + o][:], g2["error_" + o][:]
    assert np.all(np.abs(x - y) <= 1e-6 * np.abs(x) + 1e-13), (o, x, y)
print("workprecision shooting scene OK")
PYEOF
$PY "$SRC/tests/scenes/wp_figure_check.py" "$SRC" s1.h5
$PY "$SRC/tests/scenes/plot_check.py" "$SRC/src/plots/plot_workprecision.py" s1.h5 s1.png > /dev/null
