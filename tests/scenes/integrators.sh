# The simulate study with a symplectic and an implicit TS: both run the paper-default
# scene, reach E*, and agree with Dormand-Prince on the MCR.
source "$(dirname "$0")/common.bash"
run1 -options_file "$SRC/options/simulate.opts" -output rk.h5 -sim_store_u 0
run1 -options_file "$SRC/options/simulate.opts" -output sym.h5 -sim_store_u 0 \
     -sim_ts_type basicsymplectic -sim_ts_basicsymplectic_type 2 -sim_ts_dt 0.02
run1 -options_file "$SRC/options/simulate.opts" -output cn.h5 -sim_store_u 0 \
     -sim_ts_type cn -sim_ts_dt 0.05 -sim_ts_adapt_type none
$PY - <<'PYEOF'
import h5py
ref = h5py.File("rk.h5", "r")["simulate"].attrs
for name in ("sym.h5", "cn.h5"):
    a = h5py.File(name, "r")["simulate"].attrs
    assert a["energy_reached"] == 1, name
    assert abs(a["energy_final"] - 1) < 5e-3, (name, a["energy_final"])
    assert abs(a["mcr"] - ref["mcr"]) < 1e-3 * ref["mcr"], (name, a["mcr"], ref["mcr"])
    assert abs(a["t_off"] - ref["t_off"]) < 5, (name, a["t_off"], ref["t_off"])
    print(name, "MCR", a["mcr"], "vs rk5dp", ref["mcr"])
PYEOF
