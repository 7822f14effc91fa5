# -sweep_shard and -study merge (docs/studies/sweep.md "Shards and merge"): a
# reduced options/sweep_quick.opts grid run as 3 shards (at 1 and 2 ranks) and
# merged equals the unsharded run bit for bit in every dataset of /sweep but
# the wall times; a shard resumes as a shard; a shard rerun alone replaces a
# lost one; shard sets with a point missing or twice, from another scene, or
# incomplete are refused in one line, with no output.
source "$(dirname "$0")/common.bash"
OPTS=(-options_file "$SRC/options/sweep_quick.opts" -sweep_omega_n 4 -sweep_energy_n 3 -sweep_progress 0)
run2 "${OPTS[@]}" -output whole.h5 > whole.txt
run1 "${OPTS[@]}" -sweep_shard 0/3 -output shard0.h5 | tee shard0.txt
run2 "${OPTS[@]}" -sweep_shard 1/3 -output shard1.h5 > shard1.txt
run1 "${OPTS[@]}" -sweep_shard 2/3 -output shard2.h5 > shard2.txt
grep -q "^  shard 0 of 3: 4 of the 12 points" shard0.txt
run1 -study merge -merge_inputs shard2.h5,shard0.h5,shard1.h5 -output all.h5 | tee merge.txt
$PY "$CHECKS/sweep_shard.py" merged all.h5

# Refusals: one line naming the file, a non-zero exit, no output.
expect_fail() { # [OUT=<output>] expect_fail <ranks> <pattern> nltopo args... (-output $OUT, default bad.h5)
  local np=$1 pattern=$2 out=${OUT:-bad.h5} rc; shift 2
  set +e
  if [ "$np" = 1 ]; then "$NLTOPO" "$@" -output "$out" > so.txt 2> se.txt; else "$MPIEXEC" -q -n "$np" "$NLTOPO" "$@" -output "$out" > so.txt 2> se.txt; fi
  rc=$?
  set -e
  [ $rc -ne 0 ] && [ "$(grep -c . se.txt)" -eq 1 ] && grep -q -- "$pattern" se.txt && [ -z "$(ls "$out" "$out".tmp.* "$out".lock 2> /dev/null)" ] ||
    { cat se.txt; echo "FAILED: $*"; exit 1; }
  echo "ok ($np rank(s)): $(cat se.txt)"
}
cp shard1.h5 dup.h5
run1 "${OPTS[@]}" -sweep_shard 2/3 -lattice_gamma 0.3 -sim_t_final 50 -sweep_kcorr 0 -output other.h5 > other.txt
$PY "$CHECKS/sweep_shard.py" undone shard2.h5 undone.h5
expect_fail 1 "-merge_inputs: shard 2/3 is missing" -study merge -merge_inputs shard0.h5,shard1.h5
expect_fail 2 "-merge_inputs dup.h5 is shard 1/3, as is shard1.h5 (duplicate points)" -study merge -merge_inputs shard0.h5,shard1.h5,shard2.h5,dup.h5
expect_fail 1 "-merge_inputs other.h5 is another scene than shard0.h5: it was written with -lattice_gamma 0.3" -study merge -merge_inputs shard0.h5,shard1.h5,other.h5
expect_fail 1 "-merge_inputs undone.h5 is incomplete: 3 of its 4 points done" -study merge -merge_inputs shard0.h5,shard1.h5,undone.h5
expect_fail 1 "-merge_inputs whole.h5 holds a whole sweep, not a shard" -study merge -merge_inputs shard0.h5,whole.h5
expect_fail 1 "-sweep_shard 3/3: shard i of n needs 0 <= i < n" "${OPTS[@]}" -sweep_shard 3/3

# -sweep_shard is bookkeeping (no option comparison), yet a fresh run does not replace another shard's output.
cp shard0.h5 keep0.h5
set +e; "$NLTOPO" "${OPTS[@]}" -sweep_shard 1/3 -output shard0.h5 > so.txt 2> se.txt; rc=$?; set -e
[ $rc -ne 0 ] && [ "$(grep -c . se.txt)" -eq 1 ] && grep -q -- "-output shard0.h5 holds shard 0/3 of this sweep (this run: shard 1/3)" se.txt ||
  { cat se.txt; echo "FAILED: another shard's output replaced"; exit 1; }
cmp shard0.h5 keep0.h5

# A shard resumes as a shard: from an interrupted shard's partial output (here made by marking a point not done).
$PY "$CHECKS/sweep_shard.py" undone shard2.h5 res.h5.partial.h5 1
OUT=res.h5 expect_fail 1 "-sweep_resume: res.h5.partial.h5 holds shard 2/3 (now -sweep_shard 1/3)" "${OPTS[@]}" -sweep_shard 1/3 -sweep_resume
run1 "${OPTS[@]}" -sweep_shard 2/3 -sweep_resume -output res.h5 > res.txt
$PY "$CHECKS/sweep_shard.py" resumed res.h5 shard2.h5

# A lost shard is rerun alone (here at 1 rank, first at 2) and the map merged again (at 2 ranks).
run1 "${OPTS[@]}" -sweep_shard 1/3 -output shard1b.h5 > shard1b.txt
run2 -study merge -merge_inputs shard0.h5,shard1b.h5,shard2.h5 -output all2.h5 > merge2.txt  # the merge at 2 ranks
$PY "$CHECKS/sweep_shard.py" merged all2.h5
echo "sweep_shard scene OK"
