# Seeded option fuzzing (tests/fuzz/fuzz.py): cases over every study at 1 and
# 2 ranks, with value mutations and the input families (names in mixed case,
# options files and their mutations, pipes, stray words and their look-alikes);
# each run completes (root attribute complete = 1) or stops with one
# 'nltopo: error:' line and leaves no file, and none hangs or crashes.
# The run policy: FUZZ_CASES (30) cases with the fixed seed FUZZ_SEED, then
# FUZZ_RANDOM_CASES (30) with a fresh random seed, printed below. The long run
# (configure with -DNLTOPO_LONG_TESTS=ON, then ctest -L long) is 500 cases with
# a fresh seed. Reproduce a failure from its FAIL line:
#   /usr/bin/python3 tests/fuzz/fuzz.py build/nltopo /tmp/fz --seed SEED --only CASE
source "$(dirname "$0")/common.bash"
fuzz() { "$PY" "$SRC/tests/fuzz/fuzz.py" "$NLTOPO" "$@" --mpiexec "$MPIEXEC" --jobs "${FUZZ_JOBS:-3}" --timeout 60; }
rc=0
fixed=${FUZZ_CASES:-30}
fresh=${FUZZ_RANDOM_CASES:-30}
if [ "$fixed" -gt 0 ]; then fuzz "$WORK/fixed" --cases "$fixed" --seed "${FUZZ_SEED:-20261122}" || rc=1; fi
if [ "$fresh" -gt 0 ]; then
  seed=$(od -An -N4 -tu4 /dev/urandom | tr -d ' ')
  echo "fuzz: fresh random seed $seed for $fresh cases"
  fuzz "$WORK/random" --cases "$fresh" --seed "$seed" || rc=1
fi
exit $rc
