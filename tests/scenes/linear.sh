# options/linear.opts: insulated frequency, band edges, Zak phases, outputs.md /linear; 1 and 2 ranks agree.
source "$(dirname "$0")/common.bash"
run1 -options_file "$SRC/options/linear.opts" -output lin1.h5 | tee out1.txt
run2 -options_file "$SRC/options/linear.opts" -output lin2.h5 > out2.txt
grep -q "insulated omega      1.73205080" out1.txt
$PY "$CHECKS/linear.py" spectrum
# The topological transition (options/transition.opts, paper Fig. 2a) at 1 and 2 ranks; without
# -linear_gamma_list (the runs above) nothing of it is computed or written.
! grep -q "transition" out1.txt
run1 -options_file "$SRC/options/transition.opts" -output tr1.h5 | tee out_tr1.txt
run2 -options_file "$SRC/options/transition.opts" -output tr2.h5 > out_tr2.txt
grep -q "jumps to 3.141593 between gamma = -0.01 and 0.01; NaN (gap closed, k1 = k2) at gamma = 0$" out_tr1.txt
$PY "$CHECKS/linear.py" transition
$PY "$SRC/tests/scenes/plot_check.py" "$SRC/src/plots/plot_transition.py" tr1.h5 tr.png
$PY "$SRC/tests/scenes/plot_check.py" "$SRC/src/plots/plot_linear.py" tr1.h5 trlin.png
test -s trlin_transition.png
# Large N: the shift-invert path (N = 10002 > -linear_dense_max) on 2 ranks
run2 -options_file "$SRC/options/linear.opts" -lattice_cells 2500 -output big.h5 > out_big.txt
$PY "$CHECKS/linear.py" large_n
