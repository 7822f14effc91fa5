# options/linear.opts: insulated frequency, band edges, Zak phases, outputs.md /linear; 1 and 2 ranks agree.
source "$(dirname "$0")/common.bash"
run1 -options_file "$SRC/options/linear.opts" -output lin1.h5 | tee out1.txt
run2 -options_file "$SRC/options/linear.opts" -output lin2.h5 > out2.txt
grep -q "insulated omega      1.73205080" out1.txt
$PY - <<'PYEOF'
import h5py, numpy as np, math
f, g = h5py.File("lin1.h5", "r"), h5py.File("lin2.h5", "r")
for k in ("study", "version", "options", "wall_seconds"):
    assert k in f.attrs, k
assert f.attrs["study"] in (b"linear", "linear")
L = f["linear"]
N = 102
assert L["omega"].shape == (N,) and L["modes"].shape == (N, N)
w = L["omega"][:]
assert np.all(np.diff(w) >= 0), "omega ascending"
a = L.attrs
assert abs(a["insulated_omega"] - math.sqrt(3)) < 1e-10
assert 1.9494 <= a["optical_bottom"] < 1.96, a["optical_bottom"]
assert 2.23 < a["optical_top"] <= 2.23607, a["optical_top"]
assert 1.47 < a["acoustic_top"] <= 1.48325, a["acoustic_top"]
assert abs(a["interface_omega"] - 2.27) < 0.01, a["interface_omega"]
B = L["bloch"]
assert abs(B.attrs["zak_left_optical"] - math.pi) < 1e-8
assert abs(B.attrs["zak_right_optical"]) < 1e-8
assert abs(B["omega_optical"][:].min() - math.sqrt(3.8)) < 1e-3 and abs(B["omega_optical"][:].max() - math.sqrt(5)) < 1e-12
# modes are orthonormal eigenvectors of the spec's K
K = 3 * np.eye(N)
for i in range(1, N):
    kb = (0.6 if i % 2 else 1.4) if i <= 50 else (1.4 if i % 2 else 0.6)
    K[i - 1, i] = K[i, i - 1] = -kb
X = L["modes"][:]
assert np.abs(X @ X.T - np.eye(N)).max() < 1e-10
assert np.abs(X @ K - (w ** 2)[:, None] * X).max() < 1e-10
# 1 and 2 ranks give the same answer
M = g["linear"]
assert np.abs(M["omega"][:] - w).max() < 1e-12
assert np.abs(M["modes"][:] - X).max() < 1e-8
assert np.abs(M["insulated_mode"][:] - L["insulated_mode"][:]).max() < 1e-10
print("linear scene OK")
PYEOF
# Large N: the shift-invert path (N = 10002 > -linear_dense_max) on 2 ranks
run2 -options_file "$SRC/options/linear.opts" -lattice_cells 2500 -output big.h5 > out_big.txt
$PY - <<'PYEOF'
import h5py, math
L = h5py.File("big.h5", "r")["linear"]
a = L.attrs
assert "modes_selected" in L and L["modes_selected"].shape[1] == 10002
assert abs(a["insulated_omega"] - math.sqrt(3)) < 1e-10
assert abs(a["interface_omega"] - 2.2702567967) < 1e-8
# finite edges converge to the closed form as (pi/N)^2
for k, inf in (("acoustic_top", math.sqrt(2.2)), ("optical_bottom", math.sqrt(3.8)), ("optical_top", math.sqrt(5.0))):
    assert abs(a[k] - inf) < 1e-5, (k, a[k], inf)
print("large-N linear OK")
PYEOF
