# Stop signals (docs/errors.md "Signals"). SIGTERM to mpiexec (by
# its process id) of a 2-rank sweep and of a 2-rank continuation, and to a
# serial continuation and stability study: each stops at its next safe point with one line
# "nltopo: interrupted by SIGTERM ...", a non-zero exit, its partial output
# <output>.partial.h5 marked complete = 0, no -output, and no temporary, lock
# (or journal) left; the resumed run equals an uninterrupted one bit for bit
# and replaces the partial output. Then failures at 2 ranks leave no temporary
# and do not hang. Every run is under a time limit.
source "$(dirname "$0")/common.bash"
LIMIT=180 # seconds for any one run
# OpenMPI's mpiexec (4.1) forwards SIGTERM/SIGINT as SIGCONT at once, SIGTERM
# after odls_base_sigkill_timeout (1 s) and SIGKILL after as long again: the
# runs below stop within that second (docs/errors.md). -q: no mpiexec banner.
M2=("$MPIEXEC" -q -n 2)

# wait_limited <pid>: RC = its exit status; kills it (and fails) if it outlives LIMIT
# (tail -s 0.05: it looks every 50 ms whether the process is gone, not every second)
wait_limited() {
  local pid=$1
  if ! timeout "$LIMIT" tail -s 0.05 --pid="$pid" -f /dev/null; then
    kill -KILL "$pid" 2> /dev/null || true
    echo "FAILED: process $pid still running after $LIMIT s" >&2
    exit 1
  fi
  RC=0
  wait "$pid" || RC=$?
}
# wait_until <seconds> <command...>: polls until the command succeeds
wait_until() {
  local limit=$1
  shift
  for _ in $(seq 1 $((limit * 20))); do
    "$@" && return 0
    sleep 0.05
  done
  echo "FAILED: timed out waiting for: $*" >&2
  exit 1
}
# check_interrupted <rc> <stderr file> <output file> <pattern> [signal]: non-zero exit, one
# nltopo line naming the signal (SIGTERM) and the partial output <output>.partial.h5,
# that file complete = 0, no -output written, no temporary or lock left
check_interrupted() {
  local rc=$1 err=$2 out=$3 pattern=$4 sig=${5:-SIGTERM}
  [ "$rc" -ne 0 ] || { echo "FAILED: exit 0 after $sig ($out)"; exit 1; }
  if [ "$(grep -c '^nltopo:' "$err")" -ne 1 ] || ! grep -q -- "^nltopo: interrupted by $sig $pattern.*partial output $out.partial.h5 (complete = 0)" "$err"; then
    cat "$err"
    echo "FAILED: not one 'interrupted' line for $out"
    exit 1
  fi
  if ls "$out".tmp.* "$out".partial.h5.tmp.* "$out".lock > /dev/null 2>&1; then echo "FAILED: temporary or lock left: $(ls "$out".*)"; exit 1; fi
  [ ! -e "$out" ] || { echo "FAILED: an interrupted run wrote $out"; exit 1; }
  $PY "$CHECKS/signals.py" partial "$out.partial.h5" || { echo "FAILED: $out.partial.h5 not complete = 0"; exit 1; }
  echo "ok (exit $rc): $(grep '^nltopo:' "$err")"
}

# 1. A 2-rank sweep: SIGTERM to mpiexec once a few points are journaled.
# (rk 5dp instead of the quick grid's symsplit: the grid must still be running when the signal arrives)
SW=(-options_file "$SRC/options/sweep_quick.opts" -sweep_omega_n 8 -sweep_energy_n 4 -sweep_energy_min 1e-1 -sweep_energy_max 1e2 -sweep_checkpoint 0.5
    -sim_ts_type rk -sim_ts_dt 0.01)
timeout "$LIMIT" "${M2[@]}" "$NLTOPO" "${SW[@]}" -output sw_full.h5 -options_left > sw_full.txt
"${M2[@]}" "$NLTOPO" "${SW[@]}" -output sw_int.h5 -options_left > sw_int.txt 2> sw_int.err &
pid=$!
journaled() { [ "$( (cat sw_int.h5.journal.* 2> /dev/null || true) | wc -l)" -ge 2 ]; }
wait_until 120 journaled
t0=$(date +%s.%N)
kill -TERM "$pid"
wait_limited "$pid"
rc=$RC
echo "sweep: mpiexec exited $($PY "$CHECKS/signals.py" elapsed "$t0" "$(date +%s.%N)") s after SIGTERM"
check_interrupted "$rc" sw_int.err sw_int.h5 "between sweep points"
if ls sw_int.h5.journal.* > /dev/null 2>&1; then echo "FAILED: journals left (they are merged into the file)"; exit 1; fi
done_before=$($PY "$CHECKS/signals.py" done_points sw_int.h5.partial.h5)
[ "$done_before" -lt 32 ] || { echo "FAILED: the sweep ended before the signal arrived: nothing to test"; exit 1; }
timeout "$LIMIT" "${M2[@]}" "$NLTOPO" "${SW[@]}" -output sw_int.h5 -sweep_resume -options_left > sw_res.txt
$PY "$CHECKS/signals.py" sweep_resumed "$done_before"
[ ! -e sw_int.h5.partial.h5 ] || { echo "FAILED: the completed resume left its partial output"; exit 1; }

# 2. Continuations: SIGTERM between (or inside) the solves of two points; the
#    resume takes the stored tangent and step, so it goes on exactly as the
#    uninterrupted run did.
# compare_branches <uninterrupted> <resumed> <datasets...>
compare_branches() {
  local a=$1 b=$2
  shift 2
  $PY "$CHECKS/signals.py" branch_resumed "$a" "$b" "$@"
}
points_printed() { [ "$(grep -c ' E = ' "$1" || true)" -ge "$2" ]; }

# 2a. Serial, dense Floquet multipliers at every point: SIGTERM to nltopo itself.
C1=(-options_file "$SRC/options/fep.opts" -cont_branch insulated -cont_energy_max 10 -cont_verbose 1 -cont_bifurcations 0)
timeout "$LIMIT" "$NLTOPO" "${C1[@]}" -output c1_full.h5 -options_left > c1_full.txt
"$NLTOPO" "${C1[@]}" -output c1_int.h5 -options_left > c1_int.txt 2> c1_int.err &
pid=$!
wait_until 120 points_printed c1_int.txt 8
kill -TERM "$pid"
wait_limited "$pid"
rc=$RC
[ "$rc" -eq 143 ] || { echo "FAILED: exit $rc, expected 143 (128 + SIGTERM)"; exit 1; }
check_interrupted "$rc" c1_int.err c1_int.h5 "after [0-9]* points of branch insulated"
timeout "$LIMIT" "$NLTOPO" "${C1[@]}" -cont_resume c1_int.h5.partial.h5 -output c1_int.h5 -options_left > c1_res.txt
grep -q "stored tangent and step" c1_res.txt
compare_branches c1_full.h5 c1_int.h5 energy omega period mcr beta z0 newton_its multipliers_re multipliers_im max_modulus stable

# 2b. Two ranks: SIGTERM to mpiexec.
C2=(-options_file "$SRC/options/fep.opts" -cont_branch insulated -floquet 0 -cont_energy_max 100 -cont_verbose 1)
timeout "$LIMIT" "${M2[@]}" "$NLTOPO" "${C2[@]}" -output c2_full.h5 -options_left > c2_full.txt
"${M2[@]}" "$NLTOPO" "${C2[@]}" -output c2_int.h5 -options_left > c2_int.txt 2> c2_int.err &
pid=$!
wait_until 120 points_printed c2_int.txt 12
kill -TERM "$pid"
wait_limited "$pid"
rc=$RC
check_interrupted "$rc" c2_int.err c2_int.h5 "after [0-9]* points of branch insulated"
timeout "$LIMIT" "${M2[@]}" "$NLTOPO" "${C2[@]}" -cont_resume c2_int.h5.partial.h5 -output c2_int.h5 -options_left > c2_res.txt
grep -q "stored tangent and step" c2_res.txt
compare_branches c2_full.h5 c2_int.h5 energy omega period mcr beta z0 newton_its

# 2c. Stability (serial): SIGTERM during the second case keeps the first.
"$NLTOPO" -options_file "$SRC/options/stability.opts" -stability_omega 1.7320508075688772,1.75 -stability_periods 5000 -sim_progress 0 \
  -output st_int.h5 -options_left > st_int.txt 2> st_int.err &
pid=$!
case_done() { grep -q "nltopo stability: omega" st_int.txt; }
wait_until 120 case_done
kill -TERM "$pid"
wait_limited "$pid"
check_interrupted "$RC" st_int.err st_int.h5 "during stability case 1"
$PY "$CHECKS/signals.py" first_case_kept

# 3. Failures at 2 ranks: one line from nltopo, a non-zero exit, no hang, no temporary.
expect_fail2() { # expect_fail2 <pattern> <output> nltopo args...
  local pattern=$1 out=$2
  shift 2
  local rc=0
  timeout "$LIMIT" "${M2[@]}" "$NLTOPO" "$@" -output "$out" > f.txt 2> f.err || rc=$?
  [ "$rc" -ne 0 ] && [ "$rc" -ne 124 ] || { cat f.err; echo "FAILED (exit $rc): $*"; exit 1; }
  [ "$(grep -c . f.err)" -eq 1 ] && grep -q -- "$pattern" f.err || { cat f.err; echo "FAILED: not one line naming '$pattern'"; exit 1; }
  if ls "$out" "$out".tmp.* "$out".lock "$out".partial.h5 > /dev/null 2>&1; then echo "FAILED: left behind: $(ls -d "$out"*)"; exit 1; fi
  echo "ok: $(cat f.err)"
}
# an error after the output is opened, on every rank (the continuation's first orbit)
expect_fail2 "no periodic orbit found at -cont_energy_min" fc.h5 -options_file "$SRC/options/fep.opts" -cont_branch insulated -floquet 0 -nnm_start_snes_max_it 1
# a check after the branch is continued (stability)
expect_fail2 "-stability_omega 1.95: the insulated branch ends" fs.h5 -options_file "$SRC/options/stability.opts" -cont_energy_max 1 -stability_omega 1.95
# a run that fails on one rank's own lattice (zak, perturb): every rank fails with its message
expect_fail2 "time integration stopped at t = " fz.h5 -options_file "$SRC/options/zak.opts" -zak_energy_list 0.01,0.1 -sim_ts_max_steps 10
expect_fail2 "time integration stopped at t = " fp.h5 -options_file "$SRC/options/perturb.opts" -perturb_ensemble 1 -perturb_delta_list 0.1 \
  -perturb_energy_list 0.1 -sim_ts_max_steps 10
# one rank cannot write its sweep journal (a directory in the way)
mkdir -p fj.h5.journal.1 && touch fj.h5.journal.1/keep
expect_fail2 "cannot write the sweep journal fj.h5.journal.1" fj.h5 -study sweep -sweep_omega_n 2 -sweep_energy_n 2 -sim_t_final 100

# 4. SIGHUP (a closed terminal or session) stops a run like SIGTERM: at 1 rank
#    (exit 129 = 128 + SIGHUP) and at 2 ranks (to one rank process: all stop).
C4=(-options_file "$SRC/options/fep.opts" -cont_branch insulated -floquet 0 -cont_energy_max 100 -cont_verbose 1)
# (the signalled runs far longer than the 4 points waited for: mpiexec forwards the ranks' output late, and a
# short run could end before the signal reaches it)
C4H=("${C4[@]}" -cont_energy_max 1e3 -cont_max_change 0.05)
"$NLTOPO" "${C4H[@]}" -output hup1.h5 -options_left > hup1.txt 2> hup1.err &
pid=$!
wait_until 120 points_printed hup1.txt 4
kill -HUP "$pid"
wait_limited "$pid"
[ "$RC" -eq 129 ] || { cat hup1.err; echo "FAILED: exit $RC after SIGHUP, expected 129"; exit 1; }
check_interrupted "$RC" hup1.err hup1.h5 "after [0-9]* points of branch insulated" SIGHUP
"${M2[@]}" "$NLTOPO" "${C4H[@]}" -output hup2.h5 -options_left > hup2.txt 2> hup2.err &
pid=$!
wait_until 120 points_printed hup2.txt 4
rank=$(pgrep -P "$pid" -x nltopo | tail -1)
[ -n "$rank" ] || { echo "FAILED: no rank process under mpiexec $pid"; exit 1; }
kill -HUP "$rank"
wait_limited "$pid"
check_interrupted "$RC" hup2.err hup2.h5 "after [0-9]* points of branch insulated" SIGHUP

# 5. SIGPIPE is ignored: a run whose stdout reader is gone (`| head -1`, or a
#    reader gone before the first line) drops what it prints, finishes and
#    commits, exit 0 and nothing on stderr; also under PETSc's
#    -no_signal_handler. Under mpiexec (Open MPI 4.1) mpiexec itself aborts on
#    the broken pipe and sends the ranks SIGTERM: they stop as interrupted, with
#    no crash banner, or it kills them at once and the next run into the same
#    -output takes over what they left (docs/errors.md "Signals").
C5=(-options_file "$SRC/options/fep.opts" -cont_branch insulated -floquet 0 -cont_energy_max 0.01 -cont_verbose 1)
piped() { # piped <output> <reader...>: nltopo's exit status in RC
  local out=$1
  shift
  RC=0
  timeout "$LIMIT" "$NLTOPO" "${C5[@]}" -output "$out" -options_left 2> "$out.err" | "$@" > /dev/null || RC=${PIPESTATUS[0]}
  [ "$RC" -eq 0 ] && [ ! -s "$out.err" ] || { cat "$out.err"; echo "FAILED: exit $RC with stdout closed ($out)"; exit 1; }
  $PY "$CHECKS/signals.py" complete_output "$out"
  echo "ok: stdout closed under the run ($*): exit 0, $out complete"
}
piped pipe_head.h5 head -1
piped pipe_gone.h5 true
C5+=(-no_signal_handler)
piped pipe_nsh.h5 head -1
rc=0
timeout "$LIMIT" "${M2[@]}" "$NLTOPO" "${C5[@]}" -output pipe2.h5 -options_left 2> pipe2.err | head -1 > /dev/null || rc=${PIPESTATUS[0]}
if grep -q "PETSC ERROR\|MPI_ABORT" pipe2.err; then cat pipe2.err; echo "FAILED: crash banner with stdout closed at 2 ranks"; exit 1; fi
if [ "$rc" -eq 0 ] || grep -q "^nltopo: SIGTERM arrived after the last safe point" pipe2.err; then # (the run was done when mpiexec's SIGTERM came)
  $PY "$CHECKS/signals.py" complete_output pipe2.h5
elif grep -q "^nltopo: interrupted by SIGTERM" pipe2.err; then
  if ls pipe2.h5.tmp.* pipe2.h5.partial.h5.tmp.* pipe2.h5.lock > /dev/null 2>&1; then echo "FAILED: temporary or lock left: $(ls pipe2.h5.*)"; exit 1; fi
else
  # Open MPI's mpiexec may also abort at once (SIGPIPE on the stdout it forwards) and kill the
  # ranks before they report: nothing of nltopo's is printed, and what a killed run leaves is
  # taken over by the next run into the same -output (docs/errors.md "One run per output").
  grep -q "mpiexec: SIGPIPE detected" pipe2.err || { cat pipe2.err; echo "FAILED: neither complete nor interrupted at 2 ranks"; exit 1; }
  timeout "$LIMIT" "$NLTOPO" "${C5[@]}" -output pipe2.h5 -output_overwrite -options_left > /dev/null 2> pipe2b.err || { cat pipe2b.err; echo "FAILED: the next run into pipe2.h5"; exit 1; }
  $PY "$CHECKS/signals.py" complete_output pipe2.h5
  if ls pipe2.h5.tmp.* pipe2.h5.partial.h5* pipe2.h5.lock > /dev/null 2>&1; then echo "FAILED: left beside pipe2.h5: $(ls pipe2.h5.*)"; exit 1; fi
fi
echo "ok: stdout closed under mpiexec -n 2: exit $rc, $(grep '^nltopo:' pipe2.err || echo 'no nltopo line')"

# 6. An interrupted re-run never replaces a complete result: it leaves it byte
#    for byte and its part goes to <output>.partial.h5; a fresh run is then
#    refused next to that partial output (it would replace it), and the
#    resume replaces both with the complete output.
cp c2_full.h5 re.h5
cp re.h5 re.copy
"$NLTOPO" "${C4[@]}" -output re.h5 -options_left > re.txt 2> re.err &
pid=$!
wait_until 120 points_printed re.txt 4
kill -TERM "$pid"
wait_limited "$pid"
grep -q "^nltopo: interrupted by SIGTERM after [0-9]* points of branch insulated.*partial output re.h5.partial.h5 (complete = 0); -cont_resume re.h5.partial.h5 continues it$" re.err ||
  { cat re.err; echo "FAILED: the interrupted re-run's line"; exit 1; }
cmp re.h5 re.copy || { echo "FAILED: an interrupted re-run changed the complete re.h5"; exit 1; }
$PY "$CHECKS/signals.py" partial re.h5.partial.h5
rc=0
timeout "$LIMIT" "$NLTOPO" "${C4[@]}" -output re.h5 > no.txt 2> no.err || rc=$?
[ "$rc" -ne 0 ] && grep -q "^nltopo: error: -output re.h5: re.h5.partial.h5 holds the partial output (complete = 0) of an earlier run; continue it with -cont_resume re.h5.partial.h5, or remove it or give -output_overwrite to start afresh$" no.err ||
  { cat no.err; echo "FAILED: a fresh run next to a partial output was not refused"; exit 1; }
timeout "$LIMIT" "$NLTOPO" "${C4[@]}" -cont_resume re.h5.partial.h5 -output re.h5 -options_left > re_res.txt
[ ! -e re.h5.partial.h5 ] && ! cmp -s re.h5 re.copy || { echo "FAILED: the resume did not replace re.h5 and its partial output"; exit 1; }
$PY "$CHECKS/signals.py" complete_output re.h5
echo "ok: an interrupted re-run left the complete re.h5, its part in re.h5.partial.h5; refused, then resumed"
# 6b. A resume of a two-branch partial output stopped while it extends the
#     first branch: its partial output still holds the second branch's points.
C6=(-options_file "$SRC/options/fep.opts" -cont_branch insulated,interface -floquet 0 -cont_verbose 1)
timeout "$LIMIT" "$NLTOPO" "${C6[@]}" -cont_energy_max 1e-4 -output two.h5 -options_left > two.txt
mv two.h5 two.h5.partial.h5
n_interface=$($PY "$CHECKS/signals.py" branch_points two.h5.partial.h5 interface)
"$NLTOPO" "${C6[@]}" -cont_energy_max 100 -cont_resume two.h5.partial.h5 -output two.h5 -options_left > two_res.txt 2> two_res.err &
pid=$!
insulated_grew() { [ "$(grep -c '\[insulated\] .* E = ' two_res.txt || true)" -ge 4 ]; }
wait_until 120 insulated_grew
kill -TERM "$pid"
wait_limited "$pid"
grep -q "^nltopo: interrupted by SIGTERM after [0-9]* points of branch insulated" two_res.err || { cat two_res.err; exit 1; }
[ "$($PY "$CHECKS/signals.py" branch_points two.h5.partial.h5 interface)" -eq "$n_interface" ] ||
  { echo "FAILED: the stopped resume dropped the second branch's points from its partial output"; exit 1; }
echo "ok: a resume stopped in its first branch kept the second branch's $n_interface points"
echo "signals scene OK"
