# options/simulate_long.opts on a shortened long lattice (N = 1002, 2 ranks):
# the interface dynamics equals the paper-default N = 102 run (the mode and the
# first 1000 s barely feel the ends); u is stored at every 10th site.
source "$(dirname "$0")/common.bash"
run2 -options_file "$SRC/options/simulate_long.opts" -lattice_cells 250 -sim_store_u_stride 10 -sim_progress 0 -output long.h5 > long.txt
# the reference: the same options on the paper's N = 102 (only the lattice length differs)
run1 -options_file "$SRC/options/simulate_long.opts" -lattice_cells 25 -sim_store_u 0 -sim_progress 0 -output short.h5 > short.txt
$PY "$CHECKS/long.py" long_vs_short
