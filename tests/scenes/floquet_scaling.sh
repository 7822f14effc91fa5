# -study floquet_scaling on the insulated branch at N = 22, 42 and 82 (cells
# 5, 10, 20) to E = 2 on 1 rank, cells 5 and 10 on 2 ranks with the envelopes
# of B-E orbits only (seconds each): the per-size columns, the window
# envelopes and fits recomputed from them, the verdict rule, the ranks'
# agreement, and the figure (plot_check.py); then the shipped
# options/floquet_scaling.opts on its first size for two orbits.
source "$(dirname "$0")/common.bash"
ARGS="-study floquet_scaling -scaling_energy_windows 0,0.5,1,2 -cont_energy_max 2 -cont_verbose 0"
run1 $ARGS -scaling_cells 5,10,20 -output s1.h5 | tee out1.txt
run2 $ARGS -scaling_cells 5,10 -scaling_class 2 -output s2.h5 | tee out2.txt
grep -q "window E in \[0.5, 1.): p = " out1.txt
$PY "$CHECKS/floquet_scaling.py" content
$PY "$SRC/tests/scenes/plot_check.py" "$SRC/src/plots/plot_floquet_scaling.py" s1.h5 s1.png
run1 -options_file "$SRC/options/floquet_scaling.opts" -scaling_cells 25 -cont_energy_max 0.06 -output o.h5 | tee outo.txt
grep -q "\[insulated, N = 102\] Floquet (-floquet_mf, dense" outo.txt
