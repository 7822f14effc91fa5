#!/usr/bin/env bash
# Every figure of the paper (Tempelman, Matlack & Vakakis) from
# one command, on the options files, with the built nltopo (docs/figures.md):
#
#   bash figures/make_all.sh                    # small runs (default): minutes on 2 cores
#   FIG_SIZE=paper bash figures/make_all.sh     # the paper's sizes (times: benchmarks/README.md)
#
# Environment:
#   FIG_SIZE   small (default) | paper | test (the ctest scene's tiny runs)
#   FIG_OUT    where the PNGs, timings.md, data/ (HDF5) and logs/ go (default figures/out)
#   FIG_ONLY   the figures to make, e.g. "3 6" (default: 2 3 4 5 6 7 8 9 10); a figure
#              that needs the FEP (4, 6, 7, 9) runs it first when data/fep.h5 of
#              this size is missing
#   FIG_NP     ranks of the parallel studies: sweep, zak, perturb (default 2)
#   FIG_CHECK  1 (default): every figure is drawn through tests/scenes/plot_check.py,
#              which fails a panel without data, with limits that miss its data,
#              without axis labels, or with several series and no legend; 0: plain
#   NLTOPO     the binary (default build/nltopo); MPIEXEC (default mpiexec)
# Writes FIG_OUT/figN_*.png and FIG_OUT/timings.md (seconds per figure: the
# nltopo runs, the drawing, and the total). Exit status: the number of figures
# that failed (their log: FIG_OUT/logs/figN.log).
set -uo pipefail
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
SIZE=${FIG_SIZE:-small}
OUT=${FIG_OUT:-$ROOT/figures/out}
ONLY=${FIG_ONLY:-2 3 4 5 6 7 8 9 10}
NP=${FIG_NP:-2}
CHECK=${FIG_CHECK:-1}
NLTOPO=${NLTOPO:-$ROOT/build/nltopo}
MPIEXEC=${MPIEXEC:-mpiexec}
PY=/usr/bin/python3
OPT=$ROOT/options
PLOTS=$ROOT/src/plots
case "$SIZE" in small | paper | test) ;; *) echo "make_all.sh: FIG_SIZE must be small, paper or test, got '$SIZE'" >&2; exit 2 ;; esac
[ -x "$NLTOPO" ] || { echo "make_all.sh: no nltopo binary at $NLTOPO (build it: README.md \"Set-up in two commands\", or set NLTOPO)" >&2; exit 2; }
if [ "$(id -u)" = 0 ]; then # Open MPI refuses root without these
  export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
fi
export OMPI_MCA_rmaps_base_oversubscribe=${OMPI_MCA_rmaps_base_oversubscribe:-1}
mkdir -p "$OUT/data" "$OUT/logs"
OUT=$(cd "$OUT" && pwd)
DATA=$OUT/data
SQRT3=1.7320508075688772

# ---- run sizes ---------------------------------------------------------------
# Each figure's runs: the options file, then what this size changes. "paper" is
# the paper's numbers (options files as shipped, sweep_paper.opts' 50 x 50
# grid, 30,000 periods, 16 realisations); "small" keeps the physics and cuts
# grids, periods and ensembles; "test" is the ctest scene's (seconds per figure).
# ZAK_RUN_E: the E* whose zak runs Fig. 5a-b draws (the nearest grid energies).
case "$SIZE" in
  paper)
    FEP=(-options_file "$OPT/fep.opts")
    STAB=(-options_file "$OPT/stability.opts" -stability_omega "$SQRT3,1.8245,2.1876,2.2654,2.5")
    ZAK=(-options_file "$OPT/zak.opts")
    ZAK_RUN_E="0.01 1 10 100"
    SWEEP=(-options_file "$OPT/sweep_paper.opts")
    EXPO=(-options_file "$OPT/sweep_exponential.opts" -sweep_omega_n 50 -sweep_energy_n 50)
    HIST_E="0.01 1 5 10 30"
    PERT=(-options_file "$OPT/perturb.opts")
    SMAP=(-options_file "$OPT/stabilitymap.opts")
    ;;
  small)
    FEP=(-options_file "$OPT/fep.opts")
    STAB=(-options_file "$OPT/stability.opts" -stability_omega "$SQRT3,1.8245,2.1876,2.2654,2.5" -stability_periods 3000)
    ZAK=(-options_file "$OPT/zak.opts")
    ZAK_RUN_E="0.01 1 10 100"
    SWEEP=(-options_file "$OPT/sweep_quick.opts" -sweep_omega_n 25 -sweep_energy_n 25)
    EXPO=(-options_file "$OPT/sweep_exponential.opts")
    HIST_E="0.01 1 5 10 30"
    PERT=(-options_file "$OPT/perturb.opts" -perturb_ensemble 4)
    SMAP=(-options_file "$OPT/stabilitymap.opts" -smap_cells 25 -smap_classes 3 -smap_check 0.3,0.55)
    ;;
  test)
    # no bifurcation location (3/4 of the run): plot_fep.py's events are drawn and checked in the bifurcations scene
    FEP=(-options_file "$OPT/fep.opts" -cont_energy_min 1e-3 -cont_energy_max 30 -cont_max_change 0.4 -cont_bifurcations 0)
    STAB=(-options_file "$OPT/stability.opts" -stability_omega "$SQRT3,1.8245" -stability_periods 300)
    ZAK=(-options_file "$OPT/zak.opts" -zak_energy_n 7)
    ZAK_RUN_E="0.01 100"
    SWEEP=(-options_file "$OPT/sweep_quick.opts" -sweep_omega_n 6 -sweep_energy_n 6)
    EXPO=(-options_file "$OPT/sweep_exponential.opts" -sweep_omega_n 6 -sweep_energy_n 6)
    HIST_E="0.01 1 10"
    PERT=(-options_file "$OPT/perturb.opts" -perturb_delta_list 0,0.05 -perturb_ensemble 2 -perturb_energy_min 0.1 -perturb_energy_max 10 -perturb_energy_n 3)
    SMAP=(-options_file "$OPT/stabilitymap.opts" -smap_cells 5,3 -smap_check 0.41 -cont_energy_max 0.65 -cont_codim2_min 0.39 -cont_codim2_max 0.42
      -smap_raster_p 21 -smap_raster_energy 21)
    ;;
esac
# sweep_exponential.opts leaves the integrator at rk 5dp 1e-8; the paper grid's
# symsplit bm4 (sweep_paper.opts) is 5x faster with the same map (25 x 25: 7 s
# against 36 s on 2 ranks; MCR within 1e-6 below E* = 0.3, within the chaotic
# scatter above E* = 10)
EXPO+=(-sim_ts_type symsplit -sim_ts_dt 0.1 -sim_dt_quartic_energy 100)
QUIET=(-cont_verbose 0)

# ---- helpers -------------------------------------------------------------------
now() { date +%s.%N; }
add() { awk -v a="$1" -v b="$2" -v c="${3:-0}" 'BEGIN { printf "%.3f", a + b - c }'; } # a + b - c
LOG=/dev/null
RUN_S=0
PLOT_S=0
run1() { # one rank; timed into RUN_S
  local t0; t0=$(now)
  echo "+ nltopo $*" >> "$LOG"
  "$NLTOPO" "$@" >> "$LOG" 2>&1
  local rc=$?
  RUN_S=$(add "$RUN_S" "$(now)" "$t0")
  return $rc
}
runp() { # FIG_NP ranks
  local t0; t0=$(now)
  echo "+ $MPIEXEC -n $NP nltopo $*" >> "$LOG"
  "$MPIEXEC" -n "$NP" "$NLTOPO" "$@" >> "$LOG" 2>&1
  local rc=$?
  RUN_S=$(add "$RUN_S" "$(now)" "$t0")
  return $rc
}
plot() { # plot <script.py> args...: drawn through plot_check.py (FIG_CHECK=1)
  local t0; t0=$(now)
  local script=$PLOTS/$1
  shift
  echo "+ plot $(basename "$script") $*" >> "$LOG"
  if [ "$CHECK" = 1 ]; then
    "$PY" "$ROOT/tests/scenes/plot_check.py" "$script" "$@" >> "$LOG" 2>&1
  else
    "$PY" "$script" "$@" >> "$LOG" 2>&1
  fi
  local rc=$?
  PLOT_S=$(add "$PLOT_S" "$(now)" "$t0")
  return $rc
}
need_fep() { # data/fep.h5 of this size, made once (figure 3, or the first figure needing it)
  if [ -f "$DATA/fep.h5" ] && [ "$(cat "$DATA/fep.size" 2> /dev/null)" = "$SIZE" ]; then
    return 0
  fi
  rm -f "$DATA/fep.h5" "$DATA/fep.size"
  run1 "${FEP[@]}" "${QUIET[@]}" -output "$DATA/fep.h5" && echo "$SIZE" > "$DATA/fep.size"
}

# ---- the figures -------------------------------------------------------------------
# Fig. 2: linear modes (and the topological transition, once options/transition.opts exists)
fig2() {
  rm -f "$DATA/linear.h5" "$DATA/transition.h5"
  run1 -options_file "$OPT/linear.opts" -output "$DATA/linear.h5" || return 1
  plot plot_linear.py "$DATA/linear.h5" "$OUT/fig2_linear_modes.png" || return 1
  if [ -f "$OPT/transition.opts" ]; then # Fig. 2a: the spectrum and Zak phases against gamma
    run1 -options_file "$OPT/transition.opts" -output "$DATA/transition.h5" || return 1
    if [ -f "$PLOTS/plot_transition.py" ]; then
      plot plot_transition.py "$DATA/transition.h5" "$OUT/fig2a_transition.png" || return 1
    else
      plot plot_linear.py "$DATA/transition.h5" "$OUT/fig2a_transition.png" || return 1
    fi
  fi
}
# Fig. 3: the FEP of the five branches, the nonlinear optical band, the insulated NNM's shapes
fig3() {
  rm -f "$DATA/fep.h5" "$DATA/fep.size"
  need_fep || return 1
  plot plot_fep.py "$DATA/fep.h5" "$OUT/fig3_fep.png"
}
# Fig. 4: Krein signatures and multipliers along the insulated branch (a, b), the long runs (c)
fig4() {
  need_fep || return 1
  rm -f "$DATA/stability.h5"
  run1 "${STAB[@]}" -sim_progress 0 -output "$DATA/stability.h5" || return 1
  plot plot_floquet.py "$DATA/fep.h5" "$DATA/stability.h5" insulated "$OUT/fig4ab_floquet.png" || return 1
  plot plot_stability.py "$DATA/stability.h5" "$OUT/fig4c_stability.png"
}
# Fig. 5: the half-lattice phases (c, d), and time series of the runs behind them (a, b):
# the zak study keeps none, so -study simulate repeats its runs at ZAK_RUN_E
# (its options, mode, frequency and exact E*; the same MCR to round-off)
fig5() {
  rm -f "$DATA/zak.h5" "$DATA"/zak_run_*.h5
  runp "${ZAK[@]}" -output "$DATA/zak.h5" || return 1
  plot plot_zak.py "$DATA/zak.h5" "$OUT/fig5cd_zak.png" || return 1
  local reruns name args files=()
  reruns=$("$PY" -c "import sys; sys.path.insert(0, '$PLOTS'); import nltopo_plot
for name, args in nltopo_plot.zak_reruns('$DATA/zak.h5', [float(e) for e in '$ZAK_RUN_E'.split()]): print(name, ' '.join(args))") || return 1
  while read -r name args; do
    # shellcheck disable=SC2086 # args: one option or value per word
    run1 -study simulate $args -output "$DATA/$name.h5" || return 1
    files+=("$DATA/$name.h5")
  done <<< "$reruns"
  plot plot_zak_runs.py "$DATA/zak.h5" "${files[@]}" "$OUT/fig5ab_zak_runs.png"
}
# Fig. 6: the forced-response map with the FEP, the energy ratio, the 0-1 test
fig6() {
  need_fep || return 1
  rm -f "$DATA/sweep.h5" "$DATA"/sweep.h5.journal.*
  runp "${SWEEP[@]}" -output "$DATA/sweep.h5" || return 1
  plot plot_sweep.py "$DATA/sweep.h5" "$DATA/fep.h5" "$OUT/fig6_sweep.png"
}
# Fig. 7: time histories forced at the insulated NNM's frequency omega(E*)
fig7() {
  need_fep || return 1
  local files=() E w
  for E in $HIST_E; do
    w=$("$PY" -c "import sys, h5py; sys.path.insert(0, '$PLOTS'); import nltopo_plot
print(repr(float(nltopo_plot.branch_omega(h5py.File('$DATA/fep.h5', 'r')['continuation/insulated'], [$E])[0])))") || return 1
    rm -f "$DATA/history_$E.h5"
    run1 -options_file "$OPT/simulate.opts" -force_energy "$E" -force_omega "$w" -sim_sample_dt 0.25 -sim_progress 0 -output "$DATA/history_$E.h5" || return 1
    files+=("$DATA/history_$E.h5")
  done
  plot plot_timehistories.py "${files[@]}" "$OUT/fig7_time_histories.png"
}
# Fig. 8: the exponential forcing profile (a, b: the sweep writes it) and the map under it (c)
fig8() {
  rm -f "$DATA/sweep_exponential.h5" "$DATA"/sweep_exponential.h5.journal.*
  runp "${EXPO[@]}" -output "$DATA/sweep_exponential.h5" || return 1
  plot plot_forcing.py "$DATA/sweep_exponential.h5" "$OUT/fig8ab_forcing.png" || return 1
  plot plot_sweep.py "$DATA/sweep_exponential.h5" "$OUT/fig8c_exponential.png" -letters _c # the paper's (c) is the MCR
}
# Fig. 9: chiral and achiral perturbation ensembles, forced at omega(E*) of the FEP's insulated branch
fig9() {
  need_fep || return 1
  rm -f "$DATA/perturb.h5"
  runp "${PERT[@]}" -perturb_fep "$DATA/fep.h5" -output "$DATA/perturb.h5" || return 1
  plot plot_perturb.py "$DATA/perturb.h5" "$OUT/fig9_perturb.png"
}
# Fig. 10 (beyond the paper): where the insulated NNM is stable in (gamma, E), at two lattice sizes
fig10() {
  rm -f "$DATA/stabilitymap.h5"
  runp "${SMAP[@]}" -output "$DATA/stabilitymap.h5" || return 1
  plot plot_stabilitymap.py "$DATA/stabilitymap.h5" "$OUT/fig10_stabilitymap.png"
}
declare -A WHAT=([2]="linear modes (transition: slot)" [3]="FEP, nonlinear optical band, NNM shapes" [4]="Floquet: Krein, multipliers; long runs"
  [5]="half-lattice runs (a, b), phases (c, d)" [6]="MCR map + FEP, energy ratio, 0-1 test" [7]="time histories on the insulated branch"
  [8]="exponential forcing profile (a, b), its map (c)" [9]="perturbation ensembles" [10]="stability map in (gamma, E), two sizes")

# ---- run them and time them -------------------------------------------------------
TABLE=$OUT/timings.md
{
  echo "# make_all.sh timings"
  echo
  echo "FIG_SIZE=$SIZE, $(nproc) cores, FIG_NP=$NP, $(date -u '+%Y-%m-%d %H:%M UTC'), source $(git -C "$ROOT" describe --always --dirty 2> /dev/null || echo unknown)"
  echo
  echo "| figure | what | PNG | nltopo runs (s) | drawing + check (s) | total (s) | status |"
  echo "|---|---|---|---|---|---|---|"
} > "$TABLE"
failed=0
T0=$(now)
for n in $ONLY; do
  declare -F "fig$n" > /dev/null || { echo "make_all.sh: no figure $n (2..10)" >&2; failed=$((failed + 1)); continue; }
  LOG=$OUT/logs/fig$n.log
  : > "$LOG"
  RUN_S=0 PLOT_S=0
  rm -f "$OUT"/fig"$n"_*.png "$OUT"/fig"$n"[a-z]*_*.png
  t0=$(now)
  if "fig$n"; then status=ok; else status="FAILED (logs/fig$n.log)"; failed=$((failed + 1)); fi
  total=$(add 0 "$(now)" "$t0")
  pngs=$(cd "$OUT" && ls fig"$n"*_*.png 2> /dev/null | tr '\n' ' ')
  printf "| %s | %s | %s | %.1f | %.1f | %.1f | %s |\n" "$n" "${WHAT[$n]}" "${pngs% }" "$RUN_S" "$PLOT_S" "$total" "$status" >> "$TABLE"
  printf "make_all.sh: figure %s: %s in %.1f s (nltopo %.1f s, drawing %.1f s): %s\n" "$n" "$status" "$total" "$RUN_S" "$PLOT_S" "${pngs% }"
done
TOTAL=$(add 0 "$(now)" "$T0")
printf "| **total** | | | | | **%.1f** | %d failed |\n" "$TOTAL" "$failed" >> "$TABLE"
printf "make_all.sh: %s figures in %.1f s (FIG_SIZE=%s), %d failed; table %s\n" "$(echo $ONLY | wc -w)" "$TOTAL" "$SIZE" "$failed" "$TABLE"
exit "$failed"
