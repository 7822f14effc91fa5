# Progress of long phases (docs/continuation.md): a continuation with
# bifurcation location prints, with -cont_progress, how far it is towards
# -cont_energy_max with an estimate of the time to go, then how many segments
# the location has searched and how many events it has found so far; piped
# into a file, stdout keeps its order (it is line-buffered).
source "$(dirname "$0")/common.bash"
run1 -options_file "$SRC/options/fep.opts" -lattice_cells 5 -cont_branch insulated -cont_energy_max 20 -cont_progress 1e-9 -output p.h5 | cat > piped.txt
$PY "$CHECKS/progress.py" lines
echo "progress OK"
