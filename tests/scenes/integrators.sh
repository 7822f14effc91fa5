# The simulate study with a symplectic and an implicit TS: both run the paper-default
# scene, reach E*, and agree with Dormand-Prince on the MCR. nltopo's own symsplit
# (Blanes-Moan order 4, dt = 0.2) on 1 and 2 ranks: the cut-off located at E*, the
# energy kept there to 1e-6 after it (rk 5dp 1e-8 drifts by 5e-5), the MCR within
# 1e-5 of rk 5dp's, and the same run on 2 ranks.
source "$(dirname "$0")/common.bash"
run1 -options_file "$SRC/options/simulate.opts" -output rk.h5 -sim_store_u 0 -sim_ts_type rk -sim_ts_dt 0.01
run1 -options_file "$SRC/options/simulate.opts" -output sym.h5 -sim_store_u 0 \
     -sim_ts_type basicsymplectic -sim_ts_basicsymplectic_type 2 -sim_ts_dt 0.02
run1 -options_file "$SRC/options/simulate.opts" -output cn.h5 -sim_store_u 0 \
     -sim_ts_type cn -sim_ts_dt 0.05 -sim_ts_adapt_type none
run1 -options_file "$SRC/options/simulate.opts" -output split.h5 -sim_store_u 0 -sim_ts_type symsplit -sim_ts_symsplit_scheme bm4 -sim_ts_dt 0.2
run2 -options_file "$SRC/options/simulate.opts" -output split2.h5 -sim_store_u 0 -sim_ts_type symsplit -sim_ts_symsplit_scheme bm4 -sim_ts_dt 0.2
# rkn 8(6) at 1e-8: ~0.4-long steps, the window integrals on its stages
run1 -options_file "$SRC/options/simulate_rkn.opts" -output rkn.h5 -sim_store_u 0
# the MCR follows the tolerance: rk 8vr and rkn 12(10) at 1e-12, uncapped, within 1e-9 of the
# converged value (benchmarks/README.md "The MCR window to the accuracy of the run")
CONV=(-options_file "$SRC/options/simulate.opts" -sim_store_u 0 -sim_sample_dt 0 -sim_progress 0 -force_amplitude 0.03895012425830892
      -sim_ts_rtol 1e-12 -sim_ts_atol 1e-12)
run1 "${CONV[@]}" -sim_ts_type rk -sim_ts_rk_type 8vr -output conv_rk8.h5 > /dev/null
run1 "${CONV[@]}" -sim_ts_type rkn -sim_ts_rkn_scheme dep1210 -output conv_dep1210.h5 > /dev/null
$PY "$CHECKS/integrators.py" methods
