# The long test bifurcations_paper (opt-in, docs/testing.md: cmake -DNLTOPO_LONG_TESTS=ON, then
# ctest -L long or ctest -R bifurcations_paper; its time: benchmarks/README.md "Test time trimmed"):
# -cont_bifurcations along the insulated branch of options/fep.opts on the paper's lattice (N = 102) to
# E = 300. The rules of tests/scenes/checks/bifurcations.py event_rules (each event located between two
# stored points whose multipliers show it, the Krein rule, resonances on their root, one E-E branch point
# where the stored points turn unstable), which scene_bifurcations applies to the N = 22 lattice in every
# run of the suite; here the paper lattice's own numbers: the weak B-E collisions of omega 1.7-1.9, the 1:3
# resonance at omega 2.027498 and the E-E branch point at omega 2.418248; the FEP figure numbers its 22 events.
# bash tests/long/bifurcations_paper.sh <nltopo> <source dir> <work dir>
source "$(dirname "$0")/../scenes/common.bash"
run1 -options_file "$SRC/options/fep.opts" -cont_branch insulated -cont_energy_max 300 -cont_verbose 0 -output paper.h5 | tee paper.txt
grep -q "event .*: branch point (+1) E-E, instability begins at omega 2.41824" paper.txt
$PY "$SRC/tests/scenes/plot_check.py" "$SRC/src/plots/plot_fep.py" paper.h5 fep.png
$PY "$SRC/tests/scenes/fep_figure_check.py" "$SRC" paper.h5   # its 22 events numbered apart, the B-B orbits apart from B-E and E-E
$PY "$CHECKS/bifurcations.py" paper
