# The plot scripts draw their figures from real study outputs; plot_check.py
# checks that every panel holds data and that its limits cover it.
source "$(dirname "$0")/common.bash"
run1 -options_file "$SRC/options/linear.opts" -output lin.h5 > /dev/null
run1 -options_file "$SRC/options/simulate.opts" -output sim.h5 -sim_t_final 600 > /dev/null
$PY "$SRC/tests/scenes/plot_check.py" "$SRC/src/plots/plot_linear.py" lin.h5 lin.png
$PY "$SRC/tests/scenes/plot_check.py" "$SRC/src/plots/plot_simulate.py" sim.h5 sim.png
echo "plots OK"
