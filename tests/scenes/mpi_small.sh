# Small lattices on 3 and 4 ranks (ranks owning one or two sites, both neighbours
# off-rank): linear and simulate agree with 1 rank for every layout.
source "$(dirname "$0")/common.bash"
for layout in interface left right; do
  for cells in 2; do
    args="-lattice_layout $layout -lattice_cells $cells -force_site 2 -force_amplitude 0.5 -force_energy 0.05 -sim_t_final 150 -sim_sample_dt 0"
    run1 -study simulate $args -output s1_${layout}_$cells.h5 > /dev/null
    "$MPIEXEC" -n 3 "$NLTOPO" -study simulate $args -output s3_${layout}_$cells.h5 -options_left > /dev/null
    run1 -study linear -lattice_layout $layout -lattice_cells $cells -output l1_${layout}_$cells.h5 > /dev/null
    "$MPIEXEC" -n 3 "$NLTOPO" -study linear -lattice_layout $layout -lattice_cells $cells -output l3_${layout}_$cells.h5 -options_left > /dev/null
  done
done
"$MPIEXEC" -n 4 "$NLTOPO" -study simulate -lattice_cells 2 -force_site 2 -force_amplitude 0.5 -force_energy 0.05 -sim_t_final 150 -sim_sample_dt 0 -output s4.h5 -options_left > /dev/null
$PY - <<'PYEOF'
import h5py, numpy as np, glob
for f1 in sorted(glob.glob("s1_*.h5")):
    a, b = h5py.File(f1, "r")["simulate"], h5py.File(f1.replace("s1_", "s3_"), "r")["simulate"]
    assert abs(a.attrs["mcr"] - b.attrs["mcr"]) < 1e-10, (f1, a.attrs["mcr"], b.attrs["mcr"])
    assert np.abs(a["rms"][:] - b["rms"][:]).max() < 1e-10, f1
for f1 in sorted(glob.glob("l1_*.h5")):
    a, b = h5py.File(f1, "r")["linear"], h5py.File(f1.replace("l1_", "l3_"), "r")["linear"]
    assert np.abs(a["omega"][:] - b["omega"][:]).max() < 1e-12, f1
c = h5py.File("s4.h5", "r")["simulate"].attrs["mcr"]
assert abs(c - h5py.File("s1_interface_2.h5", "r")["simulate"].attrs["mcr"]) < 1e-10
print("3 and 4 ranks agree with 1 rank")
PYEOF
