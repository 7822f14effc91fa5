# Seeded option fuzzing (tests/fuzz/fuzz.py): 210 cases over every study at 1
# and 2 ranks; each run completes (root attribute complete = 1) or stops with
# one 'nltopo: error:' line and leaves no file, and none hangs or crashes.
# Reproduce a failure: /usr/bin/python3 tests/fuzz/fuzz.py build/nltopo /tmp/fz --only CASE
source "$(dirname "$0")/common.bash"
"$PY" "$SRC/tests/fuzz/fuzz.py" "$NLTOPO" "$WORK/cases" --mpiexec "$MPIEXEC" --cases "${FUZZ_CASES:-210}" --seed "${FUZZ_SEED:-20261122}" \
  --jobs "${FUZZ_JOBS:-3}" --timeout 60
