# Shared set-up for scene tests: bash <scene>.sh <nltopo> <source dir> <work dir>
# Every run passes -options_left; ctest fails the test if PETSc reports an unused option.
set -euo pipefail
NLTOPO=$1
SRC=$2
WORK=$3
rm -rf "$WORK"
mkdir -p "$WORK"
cd "$WORK"
PY=/usr/bin/python3 # Debian's python3 with h5py and numpy
CHECKS=$SRC/tests/scenes/checks # the scenes' check steps: $PY "$CHECKS/<scene>.py" <step> (scene_check.py)
MPIEXEC=${MPIEXEC:-mpiexec}
run1() { "$NLTOPO" "$@" -options_left; }
run2() { "$MPIEXEC" -n 2 "$NLTOPO" "$@" -options_left; }
# A run started in the background (run1 ... &, then wait for its pid) next to another
# singleton: give it its own TMPDIR, where Open MPI keeps its session directory
# (tests/CMakeLists.txt), e.g. TMPDIR=$(own_tmpdir) run1 ... &
own_tmpdir() { mktemp -d "$WORK/tmpdir.XXXXXX"; }
