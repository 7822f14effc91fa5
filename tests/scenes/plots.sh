# The plot scripts draw their figures from real study outputs; plot_check.py
# checks that every panel holds data, that its limits cover it, that it has
# axis labels, that a panel of several series has a legend naming them, that
# every map has a colour bar, that numbered event markers stand apart and
# each has its row in the events table, and that point labels stand apart
# (its docstring); plot_check_selftest.py shows it rejects figures that break
# each rule (an empty panel, a map without a colour bar, overlapping event
# markers, a 1 x 4 strip for --grid 2x2, other sites than --sites, ...).
# Here: every script's -h; the simulate figure and its colour bar; the time
# histories of the sites asked for; the FEP of two small continuations (one
# with located events: numbers, table, passes and resonances; one with B-B
# orbits) against their files (fep_figure_check.py); the Floquet figure 2 x 2.
# The scripts read through the Python reader of their checkout (python/nltopo),
# found from this working directory without PYTHONPATH, and never through h5py.
source "$(dirname "$0")/common.bash"
if grep -n "h5py" "$SRC"/src/plots/*.py; then echo "src/plots reads HDF5 itself: read through nltopo_plot.open_run (python/nltopo)"; exit 1; fi
env -u PYTHONPATH $PY -c "import os, sys; sys.path.insert(0, sys.argv[1] + '/src/plots'); import nltopo_plot, nltopo
assert os.path.samefile(os.path.dirname(nltopo.__file__), sys.argv[1] + '/python/nltopo'), nltopo.__file__" "$SRC"
$PY "$SRC/tests/scenes/plot_check_selftest.py" selftest
$PY "$SRC/tests/scenes/plot_check.py" --help "$SRC"/src/plots/plot_*.py | tee help.txt   # every script's -h: exit 0 and its usage
[ "$(grep -c ": exit 0, usage" help.txt)" -eq "$(ls "$SRC"/src/plots/plot_*.py | wc -l)" ]
run1 -options_file "$SRC/options/linear.opts" -output lin.h5 > /dev/null
run1 -options_file "$SRC/options/simulate.opts" -output sim.h5 -sim_t_final 600 > /dev/null
$PY "$SRC/tests/scenes/plot_check.py" "$SRC/src/plots/plot_linear.py" lin.h5 lin.png
$PY "$SRC/tests/scenes/plot_check.py" "$SRC/src/plots/plot_simulate.py" sim.h5 sim.png | tee sim_check.txt
grep -q "displacement u(t).*1 map(s) with colour bars" sim_check.txt
# time histories: the sites asked for (1-based), the default ones (the interface cell and a bulk site), a site outside refused
$PY "$SRC/tests/scenes/plot_check.py" --sites 5,51,52 "$SRC/src/plots/plot_timehistories.py" sim.h5 hist.png --sites 5,51,52 | tee hist_check.txt
grep -q "1 map(s) with colour bars" hist_check.txt
$PY "$SRC/tests/scenes/plot_check.py" --sites 26,50,51,52 "$SRC/src/plots/plot_timehistories.py" sim.h5 hist_default.png > /dev/null
if $PY "$SRC/src/plots/plot_timehistories.py" sim.h5 bad.png --sites 0,5 2> bad_sites.txt; then echo "--sites 0 accepted"; exit 1; fi
grep -q "outside 1..102 (sites are 1-based)" bad_sites.txt
# the FEP: located events on a small lattice (passes, resonances, a branch point); B-B orbits on the paper's lattice
run1 -options_file "$SRC/options/fep.opts" -cont_branch insulated -lattice_cells 5 -cont_energy_max 300 -cont_verbose 0 -output fep_events.h5 > /dev/null
run1 -options_file "$SRC/options/fep.opts" -cont_branch insulated -cont_energy_max 1.5 -cont_max_change 0.4 -cont_bifurcations 0 -cont_verbose 0 \
  -output fep_bb.h5 > /dev/null
$PY "$SRC/tests/scenes/fep_figure_check.py" "$SRC" fep_events.h5 fep_bb.h5 | tee fep_check.txt   # with every rule of plot_check.py
grep -q "numbered event markers, none overlapping, each in the events table" fep_check.txt
$PY "$SRC/tests/scenes/plot_check.py" --grid 2x2 "$SRC/src/plots/plot_floquet.py" fep_events.h5 floquet.png | grep "2x2 grid"
echo "plots OK"
