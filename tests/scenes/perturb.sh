# -study perturb on a small ensemble: chiral realisations keep the linear
# insulated frequency at sqrt(3) (to the 1e-8 hybridisation with the end mode),
# achiral ones move it; delta = 0 is the unperturbed lattice for every seed;
# 1 and 2 ranks give the same numbers; the study's own options are refused.
source "$(dirname "$0")/common.bash"
OPTS=(-options_file "$SRC/options/perturb.opts" -perturb_delta_list 0,0.05 -perturb_ensemble 3 -perturb_energy_list 0.1)
# omega(E) of the insulated NNM computed here (serial run), read from a continuation file (2-rank run)
run1 "${OPTS[@]}" -output p1.h5 | tee p1.txt
run1 -study continuation -cont_branch insulated -cont_energy_max 0.2 -output fep.h5 > fep.txt
run2 "${OPTS[@]}" -perturb_fep fep.h5 -output p2.h5 > p2.txt
$PY - <<'PYEOF'
import h5py, numpy as np
f1, f2 = h5py.File("p1.h5", "r")["perturb"], h5py.File("p2.h5", "r")["perturb"]
for kind in ("chiral", "achiral"):
    a, b = f1[kind], f2[kind]
    assert a["mcr"].shape == (2, 1, 3) and a["insulated_omega"].shape == (2, 3) and a["delta"].shape == (2,)
    assert np.array_equal(a["insulated_omega"][:], b["insulated_omega"][:]), ("np1 vs np2", kind)
    # the two routes to omega(E) interpolate different orbits of the same branch
    assert np.abs(a["omega_ext"][:] - b["omega_ext"][:]).max() < 1e-6, (a["omega_ext"][:], b["omega_ext"][:])
    assert np.abs(a["mcr"][:] - b["mcr"][:]).max() < 1e-3
    m = a["mcr"][:]
    assert (m[0] == m[0, 0, 0]).all(), "delta = 0: every seed is the same lattice"
    assert 0.3 < m[0, 0, 0] < 0.4, m[0, 0, 0]          # the insulated mode is excited
w = f1["chiral/insulated_omega"][:]
assert (np.abs(w - np.sqrt(3)) < 1e-8).all(), w - np.sqrt(3)
wa = f1["achiral/insulated_omega"][:]
assert (np.abs(wa[1] - np.sqrt(3)) > 1e-4).all(), wa[1] - np.sqrt(3)
assert np.array_equal(f1["chiral/mcr"][0], f1["achiral/mcr"][0])
print("perturb scene OK: chiral omega - sqrt 3", np.abs(w - np.sqrt(3)).max(), "achiral", wa[1] - np.sqrt(3))
PYEOF
$PY "$SRC/tests/scenes/plot_check.py" "$SRC/src/plots/plot_perturb.py" p1.h5 p.png
set +e; "$NLTOPO" "${OPTS[@]}" -lattice_perturbation chiral -output bad.h5 > so.txt 2> se.txt; rc=$?; set -e
[ $rc -ne 0 ] && [ "$(grep -c . se.txt)" -eq 1 ] && grep -q -- "-lattice_perturbation is set by -study perturb" se.txt || { cat se.txt; exit 1; }
[ ! -e bad.h5 ]
echo "perturb scene OK"
