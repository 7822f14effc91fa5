# The accuracy-aware sweep (-sweep_mcr_tol 1e-3, the step rule
# -sweep_mcr_dt_phase 0.36 -sweep_mcr_dt_energy 15) on four points of known character (the
# insulated mode forced at its frequency, regular at E* = 1e-2; omega = 2.1 at
# E* = 200, chaotic): 1 and 2 ranks give the same grid; each point's step is
# the rule's (or a halving of it); every point called predictable agrees with a
# converged run (rkn dep1210, 1e-13, steps <= 0.05, the same S) to the
# tolerance; an unpredictable point's mcr is the mean of the probe's runs
# (recomputed here as single simulate runs at its step mcr_dt with
# S x (1 + k 1e-10), k = 0, 1, -1, 2, -2) and mcr_spread their spread, above
# the tolerance.
source "$(dirname "$0")/common.bash"
OPTS=(-options_file "$SRC/options/sweep_quick.opts" -sweep_omega_list 1.7320508075688772,2.1 -sweep_energy_list 1e-2,200 -sweep_mcr_tol 1e-3 -sweep_mcr_dt_phase 0.36 -sweep_mcr_dt_energy 15)
run1 "${OPTS[@]}" -output a1.h5 | tee a1.txt
run2 "${OPTS[@]}" -output a2.h5 > a2.txt
grep -q "sweep_mcr_tol 0.001: .* integrations" a1.txt

# single simulate runs at each point with the sweep's S: the reference, and the twins at the sweep's integrator
$PY "$CHECKS/sweep_accuracy.py" runs > runs.txt
SIM=(-options_file "$SRC/options/simulate.opts" -sim_store_u 0 -sim_sample_dt 0 -sim_progress 0)
while read -r name E W S kind DT; do
  if [ "$kind" = ref ]; then
    run1 "${SIM[@]}" -force_energy "$E" -force_omega "$W" -force_amplitude "$S" -sim_dt_quartic_energy 0 -sim_ts_type rkn -sim_ts_rkn_scheme dep1210 \
         -sim_ts_rtol 1e-13 -sim_ts_atol 1e-13 -sim_ts_dt 0.1 -sim_ts_adapt_dt_max 0.05 -output "$name.h5" > /dev/null
  else
    run1 "${SIM[@]}" -force_energy "$E" -force_omega "$W" -force_amplitude "$S" -sim_dt_quartic_energy 0 -sim_ts_type symsplit -sim_ts_dt "$DT" \
         -output "$name.h5" > /dev/null
  fi
done < runs.txt

$PY "$CHECKS/sweep_accuracy.py" accuracy
