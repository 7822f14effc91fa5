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
$PY - <<'PYEOF'
import h5py
ref = h5py.File("rk.h5", "r")["simulate"].attrs
s1, s2 = (h5py.File(n, "r")["simulate"].attrs for n in ("split.h5", "split2.h5"))
assert s1["energy_reached"] == 1 and abs(s1["energy_final"] - 1) < 1e-6, s1["energy_final"]
assert abs(s1["mcr"] - ref["mcr"]) < 1e-5 * ref["mcr"], (s1["mcr"], ref["mcr"])
assert abs(s1["t_off"] - ref["t_off"]) < 0.01, (s1["t_off"], ref["t_off"])
assert s1["rhs_evals"] == 6 * s1["steps"] + 2, s1["rhs_evals"]  # 6 per step (FSAL), the start-up and the restart at the cut-off
for k in ("mcr", "t_off", "energy_final"):
    assert abs(s1[k] - s2[k]) <= 1e-10 * abs(s1[k]), (k, s1[k], s2[k])
# two independent methods (MCR errors 8e-8 and 1e-8 against bm6 at dt = 0.01) agree; with
# the trapezoid over rkn's long steps the nl_ratio was 3e-3 off and the MCR 7e-6
k = h5py.File("rkn.h5", "r")["simulate"].attrs
assert k["steps"] < 4000, k["steps"]
assert abs(k["mcr"] - s1["mcr"]) < 3e-7 * s1["mcr"], (k["mcr"], s1["mcr"])
assert abs(k["nl_ratio"] - s1["nl_ratio"]) < 1e-5 * s1["nl_ratio"], (k["nl_ratio"], s1["nl_ratio"])
print("rkn dep86 1e-8:", k["steps"], "steps, MCR", k["mcr"], "nl_ratio", k["nl_ratio"], "vs bm4", s1["nl_ratio"])
print("symsplit bm4: MCR", s1["mcr"], "E_final", s1["energy_final"], "t_off", s1["t_off"], "vs rk5dp", ref["mcr"], ref["t_off"])
for name in ("conv_rk8.h5", "conv_dep1210.h5"):
    a = h5py.File(name, "r")["simulate"].attrs
    assert abs(a["mcr"] / 0.3464668597044 - 1) < 1e-9, (name, a["mcr"])
    print(name, "MCR", a["mcr"], "steps", a["steps"])
for name in ("sym.h5", "cn.h5"):
    a = h5py.File(name, "r")["simulate"].attrs
    assert a["energy_reached"] == 1, name
    assert abs(a["energy_final"] - 1) < 5e-3, (name, a["energy_final"])
    assert abs(a["mcr"] - ref["mcr"]) < 1e-3 * ref["mcr"], (name, a["mcr"], ref["mcr"])
    assert abs(a["t_off"] - ref["t_off"]) < 5, (name, a["t_off"], ref["t_off"])
    print(name, "MCR", a["mcr"], "vs rk5dp", ref["mcr"])
PYEOF
