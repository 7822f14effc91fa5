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
$PY "$CHECKS/mpi_small.py" ranks_agree
