# The stability study on two insulated-branch orbits for a few hundred periods:
# orbit found at the asked frequency, Floquet verdicts, persistence recorded.
source "$(dirname "$0")/common.bash"
run1 -options_file "$SRC/options/stability.opts" -stability_omega 1.7320508075688772,1.95 -stability_periods 200 -sim_progress 0 -output st.h5 | tee out.txt
$PY - <<'PYEOF'
import h5py, numpy as np
f = h5py.File("st.h5", "r")["stability"]
a, b = f["case0"].attrs, f["case1"].attrs
assert abs(a["omega"] - np.sqrt(3)) < 1e-6 and a["floquet_stable"] == 1     # the linear limit is stable
assert abs(b["omega"] - 1.95) < 1e-9                                         # the orbit at the asked frequency
for c in (f["case0"], f["case1"]):
    n = c["t"].shape[0]
    assert n >= 20 and c["corr"].shape == (n,) and c["mcr"].shape == (n,)
    assert abs(c["corr"][0]) > 0.99                                           # starts on the orbit (1 % perturbation)
    assert abs(c.attrs["energy_drift"]) < 1e-3   # free run at rtol = atol = 1e-10: the absolute atol dominates at E = 1e-5 (2e-4), 2e-7 at E = 12
    assert c.attrs["persisted"] in (0, 1)
print("stability scene OK", dict(max_mod0=a["max_modulus"], max_mod1=b["max_modulus"], persisted=(a["persisted"], b["persisted"])))
PYEOF
$PY "$SRC/src/plots/plot_stability.py" st.h5 st.png
[ "$(stat -c %s st.png)" -gt 20000 ] || { echo "empty stability figure"; exit 1; }
