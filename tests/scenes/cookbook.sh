# README.md's "How do I..." cookbook, run as written: every command line
# between <!-- cookbook:begin --> and <!-- cookbook:end --> of the README itself
# (not a copy) runs, in order, in this scene's work directory, where build/nltopo,
# options/, src/, figures/, tests/ and python/ point into the build and the
# source tree, exactly as from the repository root. Each line must exit 0, and
# its row below names the check step (checks/cookbook.py) that reads one value
# of what it wrote. A cookbook line without a row fails the test, and so does a
# row that matches no line.
#
# Size overrides: a line that takes over ~30 s as written runs with an
# addition (the README line itself is unchanged):
#   line                            override (appended, or prefixed for env)        as written -> here
#   options/simulate_long.opts      -lattice_cells 2500 (N = 10^4, not 10^6)          ~1 min -> ~5 s on 2 ranks
#   bash figures/make_all.sh        FIG_SIZE=test FIG_ONLY=2 FIG_OUT=figs (Fig. 2)    minutes -> ~5 s
# Every other line runs as written (the longest, the fast FEP, ~15 s).
source "$(dirname "$0")/common.bash"
for d in options src figures tests python; do ln -s "$SRC/$d" "$d"; done
mkdir build
ln -s "$NLTOPO" build/nltopo

mapfile -t lines < <(awk '/<!-- cookbook:end -->/ {on = 0} on && !/^```/ && !/^#/ && NF {print} /<!-- cookbook:begin -->/ {on = 1}' "$SRC/README.md")
[ "${#lines[@]}" -ge 12 ] || { echo "README.md's cookbook holds ${#lines[@]} command lines, fewer than 12"; exit 1; }

declare -A used
total_start=$(date +%s.%N)
k=0
for line in "${lines[@]}"; do
  k=$((k + 1))
  prefix="" suffix=""
  case "$line" in
    *"simulate.opts -force_omega 2 -force_energy 10"*) step=forced ;;
    *"-lattice_gamma 0.3 -lattice_cubic 1"*) step=gamma_cubic ;;
    *"-lattice_damping"*) step=damped ;;
    *"options/workprecision.opts"*) step=workprecision ;;
    *"-cont_energy_max 10 "*) step=branch ;;
    *"-cont_resume"*) step=resume ;;
    *"fep.opts -floquet 0"*) step=fast_fep ;;
    *"sweep_quick.opts"*) step=sweep_overlay ;;
    *"options/zak.opts"*) step=ranks ;;
    *"simulate_long.opts"*) step=long suffix=" -lattice_cells 2500" ;;
    *"figures/make_all.sh"*) step=figures prefix="FIG_SIZE=test FIG_ONLY=2 FIG_OUT=$WORK/figs " ;;
    *"import nltopo"*) step=python ;;
    *" -help"*) step=help ;;
    *" -log_view"*) step=log_view ;;
    *) echo "cookbook line $k has no row in tests/scenes/cookbook.sh: $line"; exit 1 ;;
  esac
  [ -z "${used[$step]:-}" ] || { echo "two cookbook lines match the row $step: $line"; exit 1; }
  used[$step]=1
  if [ -n "$prefix$suffix" ] && [[ "$line" == *"&&"* ]]; then
    echo "cookbook line $k has a size override but several commands: $line"; exit 1
  fi
  ls > "files_before_$k.txt"
  start=$(date +%s.%N)
  if ! bash -c "$prefix$line$suffix" > "out_$k.txt" 2>&1; then
    tail -30 "out_$k.txt"
    echo "cookbook line $k failed: $prefix$line$suffix"
    exit 1
  fi
  seconds=$(echo "$(date +%s.%N) - $start" | bc)
  $PY "$CHECKS/cookbook.py" "$step" "out_$k.txt" "files_before_$k.txt"
  printf "cookbook line %2d: %6.1f s  %s%s%s\n" "$k" "$seconds" "$prefix" "$line" "$suffix"
done
for step in forced gamma_cubic damped workprecision branch resume fast_fep sweep_overlay ranks long figures python help log_view; do
  [ -n "${used[$step]:-}" ] || { echo "the row $step of tests/scenes/cookbook.sh matches no cookbook line"; exit 1; }
done
printf "cookbook OK: %d lines in %.1f s\n" "$k" "$(echo "$(date +%s.%N) - $total_start" | bc)"
