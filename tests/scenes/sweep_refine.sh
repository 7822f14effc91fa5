# Adaptive refinement (-sweep_refine_from, docs/studies/sweep.md "Adaptive
# refinement"): a tiny grid, then two refinement levels (at 1 and 2 ranks, the
# second capped by -sweep_refine_max_points): each level's new points are
# exactly those of the quadtree leaves over the thresholds (recomputed by the
# check), the earlier points are carried over bit for bit, the base grid's
# datasets equal the grid's; a level resumes; a missing, incomplete, sharded
# or other-scene -sweep_refine_from is refused in one line, with no output.
source "$(dirname "$0")/common.bash"
OPTS=(-options_file "$SRC/options/sweep_quick.opts" -sweep_omega_min 1.6 -sweep_omega_max 2.1 -sweep_omega_n 4 -sweep_energy_min 1 -sweep_energy_max 100
      -sweep_energy_n 3 -sweep_kcorr 0 -sweep_progress 0)
REF=(-sweep_refine_mcr 0.265 -sweep_refine_ratio 3)
run2 "${OPTS[@]}" -output l0.h5 > l0.txt
run1 "${OPTS[@]}" "${REF[@]}" -sweep_refine_from l0.h5 -output l1.h5 | tee l1.txt
$PY "$CHECKS/sweep_refine.py" level l0.h5 l1.h5 0.265 0.3 3
$PY "$CHECKS/sweep_refine.py" base l1.h5 l0.h5
run2 "${OPTS[@]}" -sweep_refine_mcr 0.05 -sweep_refine_max_points 8 -sweep_refine_from l1.h5 -output l2.h5 | tee l2.txt
$PY "$CHECKS/sweep_refine.py" level l1.h5 l2.h5 0.05 0.3 1 8
$PY "$SRC/tests/scenes/plot_check.py" "$SRC/src/plots/plot_sweep.py" l2.h5 refined.png
$PY "$CHECKS/sweep_refine.py" plot l2.h5 "$SRC"

# Refusals: one line naming the option and file, a non-zero exit, no output.
expect_fail() { # expect_fail <pattern> nltopo args... (-output bad.h5)
  local pattern=$1 rc; shift
  set +e
  "$NLTOPO" "$@" -output bad.h5 > so.txt 2> se.txt
  rc=$?
  set -e
  [ $rc -ne 0 ] && [ "$(grep -c . se.txt)" -eq 1 ] && grep -q -- "$pattern" se.txt && [ -z "$(ls bad.h5 bad.h5.* 2> /dev/null)" ] ||
    { cat se.txt; echo "FAILED: $*"; exit 1; }
  echo "ok: $(cat se.txt)"
}
$PY "$CHECKS/sweep_refine.py" incomplete l0.h5 undone.h5
expect_fail "-sweep_refine_from none.h5: no such file" "${OPTS[@]}" -sweep_refine_from none.h5
expect_fail "-sweep_refine_from undone.h5: 11 of 12 points done (not complete)" "${OPTS[@]}" -sweep_refine_from undone.h5
expect_fail "-sweep_refine_from l0.h5 was written without -lattice_gamma (now 0.3)" "${OPTS[@]}" -lattice_gamma 0.3 -sweep_refine_from l0.h5
expect_fail "-sweep_refine_from l0.h5 was written with -sweep_omega_n 4 (now 5)" "${OPTS[@]}" -sweep_omega_n 5 -sweep_refine_from l0.h5
expect_fail "-sweep_refine_from l0.h5 with -sweep_shard 0/2: a refinement level runs as one job" "${OPTS[@]}" -sweep_shard 0/2 -sweep_refine_from l0.h5
cp l0.h5 keep0.h5
set +e; "$NLTOPO" "${OPTS[@]}" -sweep_refine_from l0.h5 -output_overwrite -output l0.h5 > so.txt 2> se.txt; rc=$?; set -e
[ $rc -ne 0 ] && [ "$(grep -c . se.txt)" -eq 1 ] && grep -q -- "-sweep_refine_from l0.h5 is -output" se.txt && cmp l0.h5 keep0.h5 ||
  { cat se.txt; echo "FAILED: -sweep_refine_from = -output"; exit 1; }

# A level resumes: its partial output (here l1 with its new points marked not done) is continued, the result = l1.
$PY "$CHECKS/sweep_refine.py" undo_new l1.h5 res.h5.partial.h5
run1 "${OPTS[@]}" "${REF[@]}" -sweep_refine_from l0.h5 -sweep_resume -output res.h5 > res.txt
$PY "$CHECKS/sweep_refine.py" same res.h5 l1.h5
echo "sweep_refine scene OK"
