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
$PY "$CHECKS/workprecision_nnm.py" shooting
$PY "$SRC/tests/scenes/wp_figure_check.py" "$SRC" s1.h5
$PY "$SRC/tests/scenes/plot_check.py" --point-labels "$SRC/src/plots/plot_workprecision.py" s1.h5 s1.png > /dev/null
