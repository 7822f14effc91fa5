# options/simulate_long.opts on a shortened long lattice (N = 1002, 2 ranks):
# the interface dynamics equals the paper-default N = 102 run (the mode and the
# first 1000 s barely feel the ends); u is stored at every 10th site.
source "$(dirname "$0")/common.bash"
run2 -options_file "$SRC/options/simulate_long.opts" -lattice_cells 250 -sim_store_u_stride 10 -sim_progress 0 -output long.h5 > long.txt
# the reference: the same options on the paper's N = 102 (only the lattice length differs)
run1 -options_file "$SRC/options/simulate_long.opts" -lattice_cells 25 -sim_store_u 0 -sim_progress 0 -output short.h5 > short.txt
$PY - <<'PYEOF'
import h5py, numpy as np
L, S = h5py.File("long.h5", "r")["simulate"], h5py.File("short.h5", "r")["simulate"]
assert L["u"].shape == (1001, 101) and L.attrs["u_stride"] == 10
a, b = L.attrs, S.attrs
assert abs(a["t_off"] - b["t_off"]) < 1e-3 * b["t_off"], (a["t_off"], b["t_off"])
rl, rs = L["rms"][:], S["rms"][:]
ml, ms = 2 * 250, 2 * 25                       # interface site m (0-based)
near_l, near_s = rl[ml - 10:ml + 11], rs[ms - 10:ms + 11]
err = np.abs(near_l - near_s).max() / near_s.max()
assert err < 1e-3, err
print("long (N = 1002, 2 ranks) vs short (N = 102): t_off", a["t_off"], b["t_off"], "RMS near the interface rel. diff", err)
PYEOF
