# The plot scripts draw their figures from real study outputs; plot_check.py
# checks that every panel holds data, that its limits cover it, that it has
# axis labels, and that a panel of several series has a legend naming them
# (its docstring); plot_check_selftest.py shows it rejects figures that break
# each rule (an empty panel, limits that miss the data, no legend, ...).
source "$(dirname "$0")/common.bash"
$PY "$SRC/tests/scenes/plot_check_selftest.py" selftest
run1 -options_file "$SRC/options/linear.opts" -output lin.h5 > /dev/null
run1 -options_file "$SRC/options/simulate.opts" -output sim.h5 -sim_t_final 600 > /dev/null
$PY "$SRC/tests/scenes/plot_check.py" "$SRC/src/plots/plot_linear.py" lin.h5 lin.png
$PY "$SRC/tests/scenes/plot_check.py" "$SRC/src/plots/plot_simulate.py" sim.h5 sim.png
echo "plots OK"
