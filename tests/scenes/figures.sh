# figures/make_all.sh, every figure of the paper (docs/figures.md "Every figure of the
# paper"), at its tiny test size: each figure's runs finish, every PNG is
# written and drawn through plot_check.py (data in every panel, limits that
# cover it, axis labels, legends that name the series), and the timing table
# lists every figure and the total. The panels drawn beside the studies' own
# results: Fig. 5a-b's simulate runs repeat zak runs exactly and show the
# linear phases at the lowest E*; Fig. 8a-b's profile is the exponential fit
# the sweep ran with. NLTOPO_FIG_SIZE=small (the default of make_all.sh,
# ~2.5 min) or paper (~5.5 min, beyond this test's TIMEOUT: run make_all.sh
# itself) runs the real sizes instead:
#   NLTOPO_FIG_SIZE=small ctest -R scene_figures
source "$(dirname "$0")/common.bash"
SIZE=${NLTOPO_FIG_SIZE:-test}
if ! FIG_SIZE=$SIZE FIG_OUT="$WORK/out" NLTOPO="$NLTOPO" bash "$SRC/figures/make_all.sh"; then
  for log in out/logs/*.log; do echo "--- $log (end)"; tail -15 "$log"; done
  exit 1
fi
cat out/timings.md
pngs=(fig2_linear_modes fig3_fep fig4ab_floquet fig4c_stability fig5ab_zak_runs fig5cd_zak fig6_sweep fig7_time_histories fig8ab_forcing
  fig8c_exponential fig9_perturb fig10_stabilitymap)
for png in "${pngs[@]}"; do
  [ -s "out/$png.png" ] || { echo "make_all.sh wrote no out/$png.png"; exit 1; }
done
# every figure was drawn through plot_check.py: one "limits cover them" line per panel
for n in 2 3 4 5 6 7 8 9 10; do
  panels=$(grep -c "limits cover them" "out/logs/fig$n.log" || true)
  [ "$panels" -ge 2 ] || { echo "figure $n: plot_check.py checked $panels panels"; cat "out/logs/fig$n.log"; exit 1; }
  grep -q "^| $n | .* | ok |$" out/timings.md || { echo "figure $n missing from timings.md"; exit 1; }
done
grep -q '^| \*\*total\*\* |.*| 0 failed |$' out/timings.md
# the panels drawn from runs the zak study does not store (5a-b) and from the profile the sweep writes (8a-b)
for script in plot_zak_runs plot_forcing; do
  panels=$(grep -c "^$script.py: panel .*limits cover them" out/logs/fig*.log | awk -F: '{ s += $2 } END { print s }')
  [ "$panels" -eq 2 ] || { echo "$script.py: plot_check.py checked $panels panels, expected (a) and (b)"; exit 1; }
done
$PY "$CHECKS/figures.py" drawn_data "$SRC/src/plots"
# a figure that fails is reported (its row, the exit status) and the others go on
set +e
FIG_SIZE=$SIZE FIG_OUT="$WORK/bad" FIG_ONLY="2 1" NLTOPO="$NLTOPO" bash "$SRC/figures/make_all.sh" > bad.txt 2>&1
rc=$?
set -e
cat bad.txt
[ $rc -eq 1 ] && [ -s bad/fig2_linear_modes.png ] && grep -q "no figure 1" bad.txt || { echo "make_all.sh with an unknown figure: exit $rc"; exit 1; }
echo "figures scene OK ($SIZE)"
