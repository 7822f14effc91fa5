# The plot scripts draw their figures from real study outputs.
source "$(dirname "$0")/common.bash"
run1 -options_file "$SRC/options/linear.opts" -output lin.h5 > /dev/null
run1 -options_file "$SRC/options/simulate.opts" -output sim.h5 -sim_t_final 600 > /dev/null
$PY "$SRC/src/plots/plot_linear.py" lin.h5 lin.png
$PY "$SRC/src/plots/plot_simulate.py" sim.h5 sim.png
for f in lin.png sim.png; do [ "$(stat -c %s $f)" -gt 20000 ] || { echo "empty figure $f"; exit 1; }; done
echo "plots OK"
