# -study workprecision (options/workprecision.opts, the paper-default run at E* = 1):
# outputs.md /workprecision at 1 and 2 ranks; at least 3 methods x 3 accuracies,
# a converged reference and a floor below 1e-8; the errors it reports equal the
# errors of the same configurations run by -study simulate against a separate
# 1e-13 reference (within 10 %); the plot holds every configuration's numbers.
source "$(dirname "$0")/common.bash"
run1 -options_file "$SRC/options/workprecision.opts" -output wp1.h5 | tee wp1.txt
# at 2 ranks one repeat and one twin (a 102-site run is latency-bound there: messages at every force
# evaluation); the errors compared below do not depend on either
run2 -options_file "$SRC/options/workprecision.opts" -output wp2.h5 -wp_repeats 1 -wp_twins 1 > wp2.txt
S=$($PY -c "import h5py; print(repr(float(h5py.File('wp1.h5', 'r')['workprecision'].attrs['amplitude'])))")
# the same configurations as single simulate runs with the S the study used, and an independent reference
SIM=(-options_file "$SRC/options/simulate.opts" -sim_store_u 0 -sim_sample_dt 0 -sim_progress 0 -force_amplitude "$S" -sim_dt_quartic_energy 0)
run1 "${SIM[@]}" -sim_ts_type rkn -sim_ts_rkn_scheme dep1210 -sim_ts_rtol 1e-13 -sim_ts_atol 1e-13 -sim_ts_adapt_dt_max 0.0125 -output ref.h5 > /dev/null
run1 "${SIM[@]}" -sim_ts_type symsplit -sim_ts_symsplit_scheme bm4 -sim_ts_dt 0.4 -output c_bm4.h5 > /dev/null
run1 "${SIM[@]}" -sim_ts_type rk -sim_ts_rk_type 5dp -sim_ts_rtol 1e-6 -sim_ts_atol 1e-6 -output c_rk.h5 > /dev/null
run1 "${SIM[@]}" -sim_ts_type rkn -sim_ts_rkn_scheme dep86 -sim_ts_rtol 1e-8 -sim_ts_atol 1e-8 -output c_dep86.h5 > /dev/null
$PY "$SRC/tests/scenes/plot_check.py" "$SRC/src/plots/plot_workprecision.py" wp1.h5 wp.png > /dev/null

$PY - "$SRC" <<'PYEOF'
import h5py, numpy as np
g1, g2 = (h5py.File(n, "r")["workprecision"] for n in ("wp1.h5", "wp2.h5"))
nc = g1["config"].shape[0]
obs = ("mcr", "t_off", "nl_ratio", "energy", "state")
for g in (g1, g2):
    for k in ["config", "method", "accuracy", "wall_seconds", "rhs_evals", "steps"] + ["error_" + o for o in obs]:
        assert g[k].shape == (nc,), (k, g[k].shape)
    for o in obs:
        assert np.isfinite(g.attrs["spread_" + o]), o
    assert "dep1210" in g.attrs["reference"].decode() if isinstance(g.attrs["reference"], bytes) else "dep1210" in g.attrs["reference"]
    assert g.attrs["reference_converged"] == 1
    assert (g["wall_seconds"][:] > 0).all() and (g["rhs_evals"][:] > 0).all() and (g["steps"][:] > 0).all()
method = [m.decode() for m in g1["method"][:]]
acc = {m: {a.decode() for a, mm in zip(g1["accuracy"][:], method) if mm == m} for m in set(method)}
assert len(acc) >= 3 and all(len(a) >= 3 for a in acc.values()), acc
# a regular run: the twins agree far below any integrator's error
assert g1.attrs["spread_mcr"] < 1e-8, g1.attrs["spread_mcr"]
# 1 and 2 ranks: the same integrations (errors equal up to the order of the reductions)
for o in ("mcr", "t_off", "energy", "state"):
    e1, e2 = g1["error_" + o][:], g2["error_" + o][:]
    # rounding of the reductions (~1e-12 in each observable) and, through it, an adaptive step now and then
    assert np.all(np.abs(e1 - e2) <= 1e-4 * np.abs(e1) + 2e-11), (o, e1, e2)
# independent: each configuration as -study simulate against a 1e-13 reference with steps <= 0.0125
ref = h5py.File("ref.h5", "r")["simulate"].attrs
cfg = [c.decode() for c in g1["config"][:]]
for name, key in (("c_bm4.h5", "-sim_ts_symsplit_scheme bm4 -sim_ts_dt 0.4"), ("c_rk.h5", "-sim_ts_rk_type 5dp -sim_ts_rtol 1e-6"),
                  ("c_dep86.h5", "-sim_ts_rkn_scheme dep86 -sim_ts_rtol 1e-8")):
    i = [k for k, c in enumerate(cfg) if key in c][0]
    s = h5py.File(name, "r")["simulate"].attrs
    for o, a in (("mcr", "mcr"), ("t_off", "t_off"), ("energy", "energy_final")):
        independent = abs(s[a] - ref[a]) / abs(ref[a])
        reported = g1["error_" + o][i]
        print(f"{cfg[i]}: {o} error reported {reported:.3e}, independent {independent:.3e}")
        assert abs(reported / independent - 1) < 0.1, (cfg[i], o, reported, independent)
print("workprecision scene OK:", nc, "configurations,", len(acc), "methods, floor", g1.attrs["spread_mcr"])
PYEOF
$PY "$SRC/tests/scenes/wp_figure_check.py" "$SRC" wp1.h5
