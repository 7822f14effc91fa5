# -study sweep: outputs.md /sweep; ranks 1 and 2 give the same grid bit for
# bit; a sweep killed mid-way and resumed equals an uninterrupted one bit for
# bit and recomputes only the missing points; a grid point equals the simulate
# study's run with the same options; bad sweep input gives one-line errors.
source "$(dirname "$0")/common.bash"
OPTS=(-options_file "$SRC/options/sweep_quick.opts" -sweep_omega_n 4 -sweep_energy_n 4 -sweep_energy_min 1e-2 -sweep_energy_max 1e2
      -sweep_checkpoint 0.2)
run1 "${OPTS[@]}" -output full1.h5 | tee out1.txt
run2 "${OPTS[@]}" -output full2.h5 | tee out2.txt
ls full1.h5.journal.* 2> /dev/null && { echo "journals left behind"; exit 1; }

# Kill a 2-rank sweep (mpiexec and both ranks, SIGKILL) once a few points are journaled.
setsid "$MPIEXEC" -n 2 "$NLTOPO" "${OPTS[@]}" -output killed.h5 > killed.txt 2>&1 &
pid=$!
for i in $(seq 1 600); do
  n=$( (cat killed.h5.journal.* 2> /dev/null || true) | wc -l)
  [ "$n" -ge 5 ] && break
  sleep 0.05
done
# setsid made mpiexec ($pid) a session leader; its ranks share the session but
# Open MPI puts each in its own process group, so `kill -- -$pid` alone would
# leave them running. Kill every process of that session (mpiexec and both
# ranks) by id at once, then check that none of them is left alive.
pids=$(pgrep -s "$pid" || true)
echo "killing session $pid: $(ps -o pid=,comm= -p "$(echo $pids | tr ' ' ,)" | tr '\n' ' ')"
[ "$(ps -o comm= -p "$(echo $pids | tr ' ' ,)" | grep -cx nltopo)" -eq 2 ] || { echo "expected mpiexec and 2 ranks in session $pid"; exit 1; }
kill -9 $pids || true # a process that already exited is reported here, not hidden
wait "$pid" 2> /dev/null || true # bash's "Killed" notice: expected
for i in $(seq 1 100); do
  alive=$(ps -o pid=,stat= -p "$(echo $pids | tr ' ' ,)" | awk '$2 !~ /^Z/ {print $1}' || true)
  [ -z "$alive" ] && break
  sleep 0.05
done
[ -z "$alive" ] || { echo "processes of the killed sweep still alive: $alive"; exit 1; }
echo "--- output of the killed sweep (both ranks) ---"; cat killed.txt; echo "---"
! grep -q "error" killed.txt || { echo "the killed sweep reported an error before the kill"; exit 1; }
$PY "$CHECKS/sweep.py" killed_readable
nj=$( (cat killed.h5.journal.* 2> /dev/null || true) | wc -l)
echo "journal lines at the kill: $nj"
run2 "${OPTS[@]}" -output killed.h5 -sweep_resume | tee resumed.txt
grep -q "resuming killed.h5.partial.h5" resumed.txt
[ ! -e killed.h5.partial.h5 ] || { echo "the completed resume left its partial output"; exit 1; }

# Point (omega index 2, E* index 3) through the simulate study with the same options.
W=$($PY "$CHECKS/sweep.py" grid_value omega 2)
E=$($PY "$CHECKS/sweep.py" grid_value energy 3)
run1 -study simulate -options_file "$SRC/options/simulate.opts" -sim_t_final 1000 -force_omega "$W" -force_energy "$E" -sim_store_u 0 \
     -sim_sample_dt 0 -sim_progress 0 -sim_ts_type symsplit -sim_ts_dt 0.1 -sim_dt_quartic_energy 100 -output point.h5 > point.txt  # the sweep's integrator
# The 0-1 test at two points of known character (sweep_quick.opts settings, -kcorr_record 1500):
# the insulated mode forced at its linear frequency at E* = 1e-2 (a periodic, localised response)
# and omega = 2.1 inside the optical band at E* = 200 (chaotic, docs/model.md "The 0-1 test for chaos").
# Also the finite-time Lyapunov exponent (-sweep_lyapunov) and the regime at those points.
run1 -options_file "$SRC/options/sweep_quick.opts" -sweep_omega_list 1.7320508075688772,2.1 -sweep_energy_list 1e-2,200 -sweep_lyapunov -output kc.h5 > kc.txt

$PY "$CHECKS/sweep.py" grid

# Bad sweep input: one line, non-zero exit; a stored sweep is never damaged.
expect_fail() { # expect_fail <pattern> nltopo args...
  local pattern=$1; shift
  set +e; "$NLTOPO" "$@" > so.txt 2> se.txt; local rc=$?; set -e
  [ $rc -ne 0 ] && [ "$(grep -c . se.txt)" -eq 1 ] && grep -q -- "$pattern" se.txt || { cat se.txt; echo "FAILED: $*"; exit 1; }
  echo "ok: $(cat se.txt)"
}
expect_fail "-sweep_omega_n" "${OPTS[@]}" -sweep_omega_n 0 -output bad1.h5
expect_fail "no sweep file" "${OPTS[@]}" -sweep_resume -output nothere.h5
expect_fail "-force_omega" "${OPTS[@]}" -force_omega 2 -output bad2.h5
cp full1.h5 keep.h5
expect_fail "-sweep_resume keep.h5 was written with -sweep_omega_n 4 (now 5)" "${OPTS[@]}" -sweep_omega_n 5 -sweep_resume -output keep.h5
cmp keep.h5 full1.h5
ls bad1.h5 bad2.h5 nothere.h5 2> /dev/null && { echo "output left behind"; exit 1; }
# A run that fails (a softening lattice diverges at E* = 50) is flagged and the sweep goes on.
run2 -study sweep -sweep_omega_list 1.2,1.73 -sweep_energy_list 1e-3,50 -lattice_cubic -0.5 -output fail.h5 > fail.txt 2> fail.err
[ "$(grep -c "warning: sweep point E\* = 50" fail.err)" -eq 2 ] || { cat fail.err; exit 1; }
$PY "$CHECKS/sweep.py" failed_points
# Damping (an effect) is honoured by the sweep: after the cut-off every point
# loses energy within the bounds of the simulate scene (checks/sweep.py damped).
run2 -study sweep -sweep_omega_list 1.6,1.9 -sweep_energy_list 0.1,1 -sweep_kcorr 0 -lattice_damping 0.01 -output damped.h5 > damped.txt
$PY "$CHECKS/sweep.py" damped
# Rank groups (-sweep_group_size 2 on 2 ranks: each point's lattice distributed over both) give the
# 1-rank map to rounding, the Lyapunov exponent included; refused where they cannot work.
GOPTS=(-study sweep -sweep_omega_list 1.7320508075688772,2.1 -sweep_energy_list 1e-2 -sweep_kcorr 0 -sweep_lyapunov)
run1 "${GOPTS[@]}" -output grp1.h5 > grp1.txt
run2 "${GOPTS[@]}" -sweep_group_size 2 -output grp2.h5 | tee grp2.txt
grep -q "on 2 rank(s) in groups of 2" grp2.txt
$PY "$CHECKS/sweep.py" groups
expect_fail "-sweep_group_size 3 must divide the number of ranks (1)" "${GOPTS[@]}" -sweep_group_size 3 -output bad3.h5
set +e; "$MPIEXEC" -n 2 "$NLTOPO" "${GOPTS[@]}" -sweep_kcorr -sweep_group_size 2 -output bad4.h5 > so.txt 2> se.txt; rc=$?; set -e
[ $rc -ne 0 ] && grep -q -- "-sweep_kcorr needs -sweep_group_size 1" se.txt && [ ! -e bad4.h5 ] || { cat se.txt; echo "FAILED: kcorr with groups"; exit 1; }
$PY "$SRC/tests/scenes/plot_check.py" "$SRC/src/plots/plot_sweep.py" full1.h5 map.png
# Issue 34, class 9: an interrupted sweep says on stdout that its counts cover the points done.
"$NLTOPO" -options_file "$SRC/options/sweep_quick.opts" -sweep_omega_n 40 -sweep_energy_n 10 -sweep_progress 0 -output si.h5 > si.txt 2> si.err &
pid=$!
sleep 1.5
kill -TERM "$pid"
rc=0
wait "$pid" || rc=$?
cat si.err
[ "$rc" -eq 143 ] || { echo "FAILED: the interrupted sweep exited $rc"; exit 1; }
grep -q "^  partial result: [0-9]* of 400 points done (interrupted" si.txt || { cat si.txt; echo "FAILED: no partial-result line"; exit 1; }
echo "sweep scene OK"
