# options/fep.opts at low energy: the five branches start at their linear
# frequencies, the file follows outputs.md, 1 and 2 ranks agree; the FEP plot draws.
source "$(dirname "$0")/common.bash"
short="-cont_energy_max 2e-4 -cont_verbose 0"
run1 -options_file "$SRC/options/linear.opts" -output lin.h5 > /dev/null
run1 -options_file "$SRC/options/fep.opts" $short -output fep1.h5 | tee out1.txt
run2 -options_file "$SRC/options/fep.opts" $short -output fep2.h5 > out2.txt
$PY "$SRC/tests/scenes/plot_check.py" "$SRC/src/plots/plot_fep.py" fep1.h5 fep.png
$PY "$SRC/tests/scenes/plot_check.py" --grid 2x2 "$SRC/src/plots/plot_floquet.py" fep1.h5 floquet.png
$PY "$CHECKS/continuation.py" branches
# -cont_mcr_min stops the insulated branch where it delocalizes (near the
# optical band bottom, the paper's E ~ 12 threshold: checks/continuation.py mcr_min).
run1 -options_file "$SRC/options/fep.opts" -cont_branch insulated -floquet 0 -cont_energy_max 100 -cont_mcr_min 0.3 -cont_verbose 0 -output mcr.h5 > mcr.txt
$PY "$CHECKS/continuation.py" mcr_min
# -cont_checkpoint_seconds: a run killed mid-branch (SIGKILL, no clean-up)
# leaves a readable <output>.partial.h5 with the points so far, consistent
# across datasets and marked complete = 0 (and no -output); finished runs are
# marked complete = 1.
"$NLTOPO" -options_file "$SRC/options/fep_long.opts" -lattice_cells 25 -cont_energy_max 100 -cont_checkpoint_seconds 1e-9 -output ck.h5 > ck.txt 2>&1 &
pid=$!
for i in $(seq 1 240); do
  sleep 0.25
  [ "$(grep -c 'checkpoint:' ck.txt || true)" -ge 3 ] && break
done
kill -9 $pid
wait $pid || true
grep -q "checkpoint:" ck.txt
$PY "$CHECKS/continuation.py" killed_checkpoint
# The same at 2 ranks (collective checkpoint writes), run to its end: every
# checkpoint is replaced by the final file, complete = 1, no temporary or checkpoint left.
run2 -options_file "$SRC/options/fep_long.opts" -lattice_cells 25 -cont_energy_max 0.01 -cont_verbose 0 -cont_checkpoint_seconds 1e-9 -output ck2.h5 > ck2.txt
[ "$(grep -c 'checkpoint:' ck2.txt)" -ge 5 ]
if ls ck2.h5.tmp.* > /dev/null 2>&1; then echo "a temporary file was left behind"; exit 1; fi
$PY "$CHECKS/continuation.py" final_checkpoint
