# -study perturb on a small ensemble: chiral realisations keep the linear
# insulated frequency at sqrt(3) (to the 1e-8 hybridisation with the end mode),
# achiral ones move it; delta = 0 is the unperturbed lattice for every seed;
# 1 and 2 ranks give the same numbers; the study's own options are refused.
source "$(dirname "$0")/common.bash"
OPTS=(-options_file "$SRC/options/perturb.opts" -perturb_delta_list 0,0.05 -perturb_ensemble 3 -perturb_energy_list 0.1)
# omega(E) of the insulated NNM computed here (serial run), read from a continuation file (2-rank run)
run1 "${OPTS[@]}" -output p1.h5 | tee p1.txt
run1 -study continuation -cont_branch insulated -cont_energy_max 0.2 -output fep.h5 > fep.txt
run2 "${OPTS[@]}" -perturb_fep fep.h5 -output p2.h5 > p2.txt
$PY "$CHECKS/perturb.py" ensemble
$PY "$SRC/tests/scenes/plot_check.py" "$SRC/src/plots/plot_perturb.py" p1.h5 p.png
set +e; "$NLTOPO" "${OPTS[@]}" -lattice_perturbation chiral -output bad.h5 > so.txt 2> se.txt; rc=$?; set -e
[ $rc -ne 0 ] && [ "$(grep -c . se.txt)" -eq 1 ] && grep -q -- "-lattice_perturbation is set by -study perturb" se.txt || { cat se.txt; exit 1; }
[ ! -e bad.h5 ]
# Issue 34, class 9: an interrupted ensemble says it is partial; each row's statistics
# cover the realisations it has, and a cell without any shows no number.
"$NLTOPO" "${OPTS[@]}" -perturb_fep fep.h5 -perturb_ensemble 400 -output pi.h5 > pi.txt 2> pi.err &
pid=$!
sleep 1.5
kill -TERM "$pid"
rc=0
wait "$pid" || rc=$?
cat pi.err
[ "$rc" -eq 143 ] || { echo "FAILED: the interrupted perturb study exited $rc"; exit 1; }
grep -q "realisations not done (interrupted); each row covers those it has" pi.txt && grep -q "realisations done)" pi.txt
grep -q "^  partial result: interrupted by SIGTERM between realisations" pi.txt
! grep -q "nan+-" pi.txt || { cat pi.txt; echo "FAILED: statistics of realisations not run"; exit 1; }
echo "perturb scene OK"
