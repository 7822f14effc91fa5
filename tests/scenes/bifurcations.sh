# -cont_bifurcations (on with -floquet): events along the insulated branch of
# options/fep.opts on the N = 22 lattice (the paper's N = 102 lattice and its
# own numbers: the long test tests/long/bifurcations_paper.sh, opt-in),
# located between its points. Checked against the stored
# Floquet data itself (each located change of stability lies between two
# points whose multipliers show it, to -cont_bif_tol in omega), against the
# Krein rule (a Hamiltonian-Hopf pair has opposite signatures, a pass equal
# ones), internal resonances (odd orders only on these symmetric orbits, on the
# root, with stored circle multipliers near it on either side) and across
# 1 and 2 ranks; the FEP plot marks the events. Then -cont_switch at the
# branch point of the small lattice: the two families born there start at the
# located point, carry the parent and are time-reversal images of each other.
source "$(dirname "$0")/common.bash"
small="-cont_branch insulated -lattice_cells 5 -cont_energy_max 300 -cont_verbose 0"
run1 -options_file "$SRC/options/fep.opts" $small -output s1.h5 > s1.txt
run2 -options_file "$SRC/options/fep.opts" $small -output s2.h5 > s2.txt
run1 -options_file "$SRC/options/fep.opts" $small -cont_bif_passes 0 -cont_bif_resonance_order 0 -output s0.h5 > s0.txt
grep -q "event .*: branch point (+1) E-E, instability begins at omega 2.41826" s1.txt
$PY "$CHECKS/bifurcations.py" events
bp=$(cat bp_index.txt)
# -cont_switch at the branch point bp (the two families born there) and, in the same run, at a period doubling.
# The lattice's own NNM families have none (x(t + T/2) = -x(t): M is the square of the half-period map,
# docs/continuation.md "Branch switching"); the switched family breaks that symmetry and has period-doubling
# windows. Switching at the first onset on its _plus side (insulated_bp<bp>_plus:<pd>) starts the doubled-period
# family insulated_bp<bp>_plus_pd<pd>: at the located point, at half its frequency, with period_multiple 2.
# Both events named by kind and omega as a user would type them (bp at omega 2.418267, pd at 2.526939 on the
# N = 22 lattice; the next period doubling, its end, lies at 2.531442): the checks below find the families of
# the branch point and of the first onset by index, and the resume's bit-for-bit comparison with the run named
# by index shows that both select the same events and give the same families.
# (to E = 150: past the branch point at E 74, the period doubling at E 95 and the doubled family's loop, E 95-134)
small150="-cont_branch insulated -lattice_cells 5 -cont_energy_max 150 -cont_verbose 0"
run1 -options_file "$SRC/options/fep.opts" $small150 -cont_switch insulated:bp@2.418,insulated_bp${bp}_plus:pd@2.527 -output pd.h5 > pd.txt
$PY "$SRC/tests/scenes/plot_check.py" "$SRC/src/plots/plot_fep.py" pd.h5 pd.png
$PY "$CHECKS/bifurcations.py" switching "$bp" pd.h5
pd=$($PY "$CHECKS/bifurcations.py" first_period_doubling "$bp" pd.h5)
$PY "$CHECKS/bifurcations.py" period_doubling "$bp" "$pd"
# -cont_resume recreates the switched families: the same run stopped at E = 100 (every branch stopped part-way,
# the doubled family inside its loop) and resumed to 150 equals the run to 150 bit for bit
sw2="-cont_switch insulated:$bp,insulated_bp${bp}_plus:$pd"
small100="-cont_branch insulated -lattice_cells 5 -cont_energy_max 100 -cont_verbose 0"
run1 -options_file "$SRC/options/fep.opts" $small100 $sw2 -output r100.h5 > r100.txt
run1 -options_file "$SRC/options/fep.opts" $small150 $sw2 -cont_resume r100.h5 -output r150.h5 > r150.txt
grep -q "\[insulated_bp${bp}_plus_pd$pd\] -cont_resume r100.h5: [0-9]* points of the family born at the period doubling" r150.txt
$PY "$CHECKS/bifurcations.py" resumed_families pd.h5 r150.h5 r100.h5
