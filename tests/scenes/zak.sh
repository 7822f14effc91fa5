# -study zak at low energy: the linear phases phi_0 = 0 (optical band bottom)
# and phi_pi = pi (top) per unit cell, theta = pi; the same numbers on 1 and 2 ranks.
source "$(dirname "$0")/common.bash"
run1 -options_file "$SRC/options/zak.opts" -zak_energy_list 0.01,0.1 -output z1.h5 | tee z1.txt
run2 -options_file "$SRC/options/zak.opts" -zak_energy_list 0.01,0.1 -output z2.h5 > z2.txt
$PY - <<'PYEOF'
import h5py, numpy as np
a, b = h5py.File("z1.h5", "r")["zak"], h5py.File("z2.h5", "r")["zak"]
for k in ("energy", "phi0_mean", "phi0_median", "phipi_mean", "phipi_median"):
    assert a[k].shape == (2,), k
    assert np.array_equal(a[k][:], b[k][:]), ("np1 vs np2", k)
assert "energy_threshold" in a.attrs
assert (np.abs(a["phi0_median"][:]) < 0.05).all(), a["phi0_median"][:]
assert (np.abs(a["phipi_median"][:] - np.pi) < 0.05).all(), a["phipi_median"][:]
assert (np.abs(a["phi0_mean"][:]) < 0.2).all() and (np.abs(a["phipi_mean"][:] - np.pi) < 0.2).all()
assert (np.abs(a["theta_median"][:] - np.pi) < 0.05).all()
assert a.attrs["energy_threshold"] == -1  # distinct over this low-energy range
print("zak scene OK: phi_0 median", a["phi0_median"][:], "phi_pi median", a["phipi_median"][:])
PYEOF
$PY "$SRC/src/plots/plot_zak.py" z1.h5 z.png
[ "$(stat -c %s z.png)" -gt 20000 ] || { echo "empty figure"; exit 1; }
