# -study stabilitymap on the N = 22 interface lattice (options/stabilitymap.opts at -smap_cells 5, issue
# 37): the insulated branch to E = 0.8 at gamma 0.4, its Hamiltonian-Hopf onsets followed in -lattice_gamma
# over [0.38, 0.43], check branches at gamma 0.42 and 0.41 (at 2 ranks one per rank), at 1 and 2 ranks. Checked: the base branch's own
# Floquet classes against the raster column at gamma 0.4 (an independent truth: the labels come from the
# curves alone); every check orbit's class against the map's label (agree), every check event on a curve
# of its kind; the curves through their events; no inconsistent column; 1 vs 2 ranks: the same curves and
# raster; the figure (plot_check.py).
source "$(dirname "$0")/common.bash"
ARGS="-options_file $SRC/options/stabilitymap.opts -smap_cells 5 -smap_check 0.42,0.41 -cont_energy_max 0.8 -cont_codim2_min 0.38 -cont_codim2_max 0.43
  -smap_raster_p 31 -smap_raster_energy 41"
run1 $ARGS -output m1.h5 | tee out1.txt
run2 $ARGS -output m2.h5 > out2.txt
for q in 0.42 0.41; do
  grep -q "\[check -lattice_gamma $q\] .* events; the map's label agrees with the branch's verdict at \([0-9]*\) of \1 orbits" out1.txt
  grep -q "\[check -lattice_gamma $q\] .* events; the map's label agrees with the branch's verdict at \([0-9]*\) of \1 orbits" out2.txt
done
$PY "$CHECKS/stabilitymap.py" content m1.h5
$PY "$CHECKS/stabilitymap.py" ranks m1.h5 m2.h5
$PY "$SRC/tests/scenes/plot_check.py" "$SRC/src/plots/plot_stabilitymap.py" m1.h5 m1.png
