# One run per -output (docs/errors.md "One run per output", issue 34 class 1).
# Forced overlap: the first run is stopped (SIGSTOP) once its temporary (a
# sweep: its journal) exists, a second run into the same -output starts with
# another scene, then the first goes on (SIGCONT). The second is refused at
# once with one line naming the first; the first exits 0 and the file equals
# the result of its scene run alone; no lock, temporary or journal is left.
# CONCURRENCY_ROUNDS rounds (default 1) of four pairs: simulate at 1+1, 1+2
# and 2+1 ranks, and a sweep at 1+1. Then stale locks: a run killed by
# SIGKILL (as by the OOM killer) at 1 and 2 ranks leaves its lock and
# temporary, and the next run takes them over with one warning line; a lock
# whose process id was reused is taken over too; a lock of another host, or
# one that names no run, is refused in one line saying what to do, at once.
source "$(dirname "$0")/common.bash"
LIMIT=120
M2=("$MPIEXEC" -q -n 2)
SIM=(-study simulate -lattice_cells 5 -force_site 12 -sim_progress 0 -sim_store_u 0)
A1=("${SIM[@]}" -sim_t_final 5000) # the first run's scene at 1 rank (a few tenths of a second)
A2=("${SIM[@]}" -sim_t_final 1000) # at 2 ranks
B=("${SIM[@]}" -sim_t_final 100 -force_energy 0.5) # the second run's scene
SW=(-study sweep -lattice_cells 5 -force_site 12 -sweep_omega_n 3 -sweep_energy_n 2 -sweep_energy_min 0.1 -sweep_energy_max 1 -sweep_progress 0
    -sim_t_final 1000)
SWB=("${SW[@]}" -lattice_cubic 0.5)

run_np() { # run_np <ranks> nltopo args...
  local np=$1
  shift
  if [ "$np" -eq 1 ]; then timeout "$LIMIT" "$NLTOPO" "$@"; else timeout "$LIMIT" "${M2[@]}" "$NLTOPO" "$@"; fi
}
wait_for() { # wait_for <glob>: until a file matching it exists
  for _ in $(seq 1 $((LIMIT * 50))); do
    compgen -G "$1" > /dev/null && return 0
    sleep 0.02
  done
  echo "FAILED: no $1 within $LIMIT s"
  exit 1
}
COMM=$(basename "$NLTOPO" | cut -c1-15) # (ps shows 15 characters of a command name)
ranks_of() { # ranks_of <pid>: the nltopo processes under it (timeout, mpiexec)
  local p
  for p in $(pgrep -P "$1"); do
    [ "$(ps -o comm= -p "$p")" = "$COMM" ] && echo "$p"
    ranks_of "$p"
  done
  return 0
}
nothing_left() { # nothing_left <output>: no lock, temporary or journal next to it
  local left
  left=$(ls -d "$1".* 2> /dev/null || true)
  [ -z "$left" ] || { echo "FAILED: left next to $1: $left"; exit 1; }
}

run_np 1 "${A1[@]}" -output ref_a1.h5 -options_left > /dev/null
run_np 2 "${A2[@]}" -output ref_a2.h5 -options_left > /dev/null
run_np 1 "${SW[@]}" -output ref_sw.h5 -options_left > /dev/null

# pair <output> <ranks 1> <args 1 (array name)> <reference> <glob to wait for> <ranks 2> <args 2 (array name)>
pair() {
  local out=$1 np1=$2 ref=$4 glob=$5 np2=$6 rc1=0 rc2=0
  local -n first=$3 second=$7
  local pid ranks attempt
  # The first run may end between its temporary appearing and the search for its ranks, or before
  # they are stopped (a small, fast scene on an idle machine): then it is simply run again, up to 5 times.
  for attempt in 1 2 3 4 5; do
    rm -f "$out"
    run_np "$np1" "${first[@]}" -output "$out" -options_left > first.txt 2> first.err &
    pid=$!
    wait_for "$glob"
    ranks=$(ranks_of "$pid")
    if [ "$(echo $ranks | wc -w)" -eq "$np1" ]; then
      kill -STOP $ranks 2> /dev/null || true
      compgen -G "$glob" > /dev/null && break # stopped while it writes: the overlap is forced
      kill -CONT $ranks 2> /dev/null || true  # it ended before the stop: again
    else
      kill -0 "$pid" 2> /dev/null && break # still running with another count of ranks: a failure, below
    fi
    wait "$pid" || true
    ranks=""
  done
  [ "$(echo $ranks | wc -w)" -eq "$np1" ] || { echo "FAILED: not $np1 rank(s) of the first run found in 5 attempts: '$ranks'"; exit 1; }
  run_np "$np2" "${second[@]}" -output "$out" -options_left > second.txt 2> second.err || rc2=$?
  kill -CONT $ranks
  wait "$pid" || rc1=$?
  [ "$rc1" -eq 0 ] || { cat first.err; echo "FAILED: the first run into $out exited $rc1"; exit 1; }
  [ "$rc2" -ne 0 ] && [ "$rc2" -ne 124 ] || { cat second.err; echo "FAILED: the second run into $out exited $rc2 while the first wrote it"; exit 1; }
  if [ "$(grep -c . second.err)" -ne 1 ] ||
    ! grep -q "^nltopo: error: -output $out is being written by another run (process [0-9]* on this host, since [-0-9: ]*): wait for it to end, or choose another -output$" second.err; then
    cat second.err
    echo "FAILED: the second run into $out did not print the one refusal line"
    exit 1
  fi
  $PY "$CHECKS/concurrency.py" same_result "$out" "$ref"
  nothing_left "$out"
  echo "ok: $np1 + $np2 ranks into $out: the first exit 0 with its own result, the second: $(cat second.err)"
}
for round in $(seq 1 "${CONCURRENCY_ROUNDS:-1}"); do
  pair sim.h5 1 A1 ref_a1.h5 "sim.h5.tmp.*" 1 B
  pair sim.h5 1 A1 ref_a1.h5 "sim.h5.tmp.*" 2 B
  pair sim.h5 2 A2 ref_a2.h5 "sim.h5.tmp.*" 1 B
  pair sw.h5 1 SW ref_sw.h5 "sw.h5.journal.*" 1 SWB
  echo "round $round: 4 forced-overlap pairs passed"
done

# A run killed by SIGKILL leaves its lock and temporary; the next run takes them over.
# Its rank may still be a zombie of a not yet reaped mpiexec: both reasons are a takeover.
for np in 1 2; do
  if [ "$np" -eq 1 ]; then args=("${A1[@]}"); else args=("${A2[@]}"); fi
  run_np "$np" "${args[@]}" -output killed$np.h5 > /dev/null 2>&1 &
  pid=$!
  wait_for "killed$np.h5.tmp.*"
  kill -KILL $(ranks_of "$pid")
  wait "$pid" 2> /dev/null || true
  [ -e killed$np.h5.lock ] && compgen -G "killed$np.h5.tmp.*" > /dev/null || { ls; echo "FAILED: the killed run left no lock and temporary"; exit 1; }
  run_np "$np" "${args[@]}" -output killed$np.h5 -options_left > k.txt 2> k.err || { cat k.err; echo "FAILED: the run after a killed one failed"; exit 1; }
  grep -q "^nltopo: warning: -output killed$np.h5: took over its lock killed$np.h5.lock from process [0-9]* (since [-0-9: ]*): it \(is no longer running\|has exited (a zombie not yet reaped)\) (killed?); removed its temporaries killed$np.h5.tmp.[0-9]*$" k.err ||
    { cat k.err; echo "FAILED: no takeover line"; exit 1; }
  $PY "$CHECKS/concurrency.py" same_result killed$np.h5 ref_a$np.h5
  nothing_left killed$np.h5
  echo "ok ($np ranks): $(grep '^nltopo:' k.err)"
done

# A lock whose process id now belongs to another process (here a sleep, with another start time): taken over.
sleep 60 &
sleeper=$!
echo "nltopo-lock pid=$sleeper host=$(hostname) boot=$(cat /proc/sys/kernel/random/boot_id) start=1 time=1700000000" > reused.h5.lock
run_np 1 "${B[@]}" -output reused.h5 -options_left > r.txt 2> r.err || { cat r.err; exit 1; }
kill "$sleeper"
grep -q "its process id now belongs to another process" r.err || { cat r.err; echo "FAILED: a lock of a reused process id was not taken over"; exit 1; }
nothing_left reused.h5
echo "ok: $(grep "^nltopo:" r.err)"

# Locks that cannot be judged: refused in one line saying what to do, at once, at 1 and 2 ranks; the lock stays.
refused() { # refused <ranks> <output> <pattern>
  local np=$1 out=$2 pattern=$3 rc=0 t0 t1
  cp "$out.lock" lock.copy
  t0=$(date +%s)
  run_np "$np" "${B[@]}" -output "$out" -options_left > no.txt 2> no.err || rc=$?
  t1=$(date +%s)
  [ "$rc" -ne 0 ] && [ "$rc" -ne 124 ] && [ $((t1 - t0)) -lt 20 ] || { cat no.err; echo "FAILED (np $np, exit $rc, $((t1 - t0)) s): $out"; exit 1; }
  [ "$(grep -c . no.err)" -eq 1 ] && grep -q -- "$pattern" no.err || { cat no.err; echo "FAILED (np $np): not one line naming '$pattern'"; exit 1; }
  cmp -s "$out.lock" lock.copy && [ ! -e "$out" ] || { echo "FAILED (np $np): the lock of $out was changed or the output written"; exit 1; }
  echo "ok (np $np, $((t1 - t0)) s): $(cat no.err)"
}
echo "nltopo-lock pid=4242 host=elsewhere.example boot= start=1 time=1700000000" > other.h5.lock
: > empty.h5.lock
for np in 1 2; do
  refused "$np" other.h5 "^nltopo: error: -output other.h5 is being written by another run (process 4242 on host elsewhere.example, since .*: wait for it to end, or choose another -output; if that run is over (killed), remove other.h5.lock$"
  refused "$np" empty.h5 "^nltopo: error: -output empty.h5 is locked by empty.h5.lock, which names no nltopo run: if no run is writing empty.h5, remove empty.h5.lock$"
done
echo "concurrency scene OK"
