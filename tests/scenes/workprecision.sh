# -study workprecision (options/workprecision.opts, the paper-default run at E* = 1):
# outputs.md /workprecision at 1 and 2 ranks; at least 3 methods x 3 accuracies,
# a converged reference and a floor below 1e-8; the errors it reports equal the
# errors of the same configurations run by -study simulate against a separate
# 1e-13 reference (within 10 %); the plot holds every configuration's numbers.
source "$(dirname "$0")/common.bash"
run1 -options_file "$SRC/options/workprecision.opts" -output wp1.h5 | tee wp1.txt
# at 2 ranks one repeat and one twin (a 102-site run is latency-bound there: messages at every force
# evaluation); the errors compared below do not depend on either
# -wp_target: the cheapest configuration meeting it per observable, printed and written (checks/workprecision.py recommended)
run2 -options_file "$SRC/options/workprecision.opts" -output wp2.h5 -wp_repeats 1 -wp_twins 1 -wp_target 1e-6 > wp2.txt
S=$($PY "$CHECKS/workprecision.py" amplitude)
# the same configurations as single simulate runs with the S the study used, and an independent reference
SIM=(-options_file "$SRC/options/simulate.opts" -sim_store_u 0 -sim_sample_dt 0 -sim_progress 0 -force_amplitude "$S" -sim_dt_quartic_energy 0)
run1 "${SIM[@]}" -sim_ts_type rkn -sim_ts_rkn_scheme dep1210 -sim_ts_rtol 1e-13 -sim_ts_atol 1e-13 -sim_ts_adapt_dt_max 0.0125 -output ref.h5 > /dev/null
run1 "${SIM[@]}" -sim_ts_type symsplit -sim_ts_symsplit_scheme bm4 -sim_ts_dt 0.4 -output c_bm4.h5 > /dev/null
run1 "${SIM[@]}" -sim_ts_type rk -sim_ts_rk_type 5dp -sim_ts_rtol 1e-6 -sim_ts_atol 1e-6 -output c_rk.h5 > /dev/null
run1 "${SIM[@]}" -sim_ts_type rkn -sim_ts_rkn_scheme dep86 -sim_ts_rtol 1e-8 -sim_ts_atol 1e-8 -output c_dep86.h5 > /dev/null
$PY "$SRC/tests/scenes/plot_check.py" --point-labels "$SRC/src/plots/plot_workprecision.py" wp1.h5 wp.png > /dev/null

$PY "$CHECKS/workprecision.py" errors
$PY "$CHECKS/workprecision.py" recommended
$PY "$SRC/tests/scenes/wp_figure_check.py" "$SRC" wp1.h5
