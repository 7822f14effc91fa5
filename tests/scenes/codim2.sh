# -cont_codim2 on the N = 22 interface lattice (issue 37, acceptance "curves pass through the events of
# independent one-parameter runs"): the insulated branch's first located event, the Hamiltonian-Hopf onset
# (kind 5) of a B-E bubble at omega 1.747368 (E 0.62, -lattice_gamma 0.4), followed in -lattice_gamma over
# [0.35, 0.45] at 1 and 2 ranks: the same curve. Then two of its points (not the event itself, one on each side
# of gamma 0.4) are checked against independent one-parameter runs of the branch at exactly that gamma
# (written in full precision), with -cont_bif_tol 1e-9 and short steps (-cont_max_change 0.05: the locator
# must not step over the event), stopped soon after the event's E: each locates a Hamiltonian-Hopf onset, in
# the same direction (instability begins), at the curve's omega to 1e-6 and its E to 1e-5 relative; at 1 and
# 2 ranks.
source "$(dirname "$0")/common.bash"
base="-options_file $SRC/options/fep.opts -cont_branch insulated -lattice_cells 5 -cont_verbose 0"
curve="-cont_energy_max 1 -cont_codim2 insulated:hamiltonian_hopf@1.747368 -cont_codim2_min 0.35 -cont_codim2_max 0.45"
run1 $base $curve -output c1.h5 > c1.txt
run2 $base $curve -output c2.h5 > c2.txt
grep -q "\[insulated codim2 hh0\] the Hamiltonian-Hopf (opposite signatures) at -lattice_gamma 0.4: omega 1.74736" c1.txt
$PY "$CHECKS/codim2.py" curve
# the two points: rows event_point -6 and +6 of the curve (gamma near 0.378 and 0.420); each line: row p E
# (read before the loop: mpiexec would consume the loop's stdin)
mapfile -t pts < <($PY "$CHECKS/codim2.py" points)
[ "${#pts[@]}" -eq 2 ]
for pt in "${pts[@]}"; do
  read -r row p e <<< "$pt"
  emax=$($PY -c "print(repr(1.3 * $e))")   # past the event's E, short of the next events of the bubble
  one="-lattice_gamma $p -cont_bif_tol 1e-9 -cont_max_change 0.05 -cont_energy_max $emax"
  run1 $base $one -output r${row}_1.h5 > r${row}_1.txt
  run2 $base $one -output r${row}_2.h5 > r${row}_2.txt
  $PY "$CHECKS/codim2.py" through "$row" r${row}_1.h5
  $PY "$CHECKS/codim2.py" through "$row" r${row}_2.h5
done
