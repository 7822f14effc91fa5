# The accuracy-aware sweep (-sweep_mcr_tol 1e-3) on four points of known
# character (the insulated mode forced at its frequency, regular at E* = 1e-2;
# omega = 2.1 at E* = 200, chaotic): 1 and 2 ranks give the same grid; every
# point called predictable agrees with a converged run (rkn dep1210, 1e-13,
# steps <= 0.05, the same S) to the tolerance; an unpredictable point's mcr is
# the mean of the twin runs (recomputed here as single simulate runs with
# S x (1 + k 1e-10)) and mcr_spread their spread, above the tolerance.
source "$(dirname "$0")/common.bash"
OPTS=(-options_file "$SRC/options/sweep_quick.opts" -sweep_omega_list 1.7320508075688772,2.1 -sweep_energy_list 1e-2,200 -sweep_mcr_tol 1e-3)
run1 "${OPTS[@]}" -output a1.h5 | tee a1.txt
run2 "${OPTS[@]}" -output a2.h5 > a2.txt
grep -q "sweep_mcr_tol 0.001: .* integrations" a1.txt

# single simulate runs at each point with the sweep's S: the reference, and the twins at the sweep's integrator
$PY - <<'PYEOF' > runs.txt
import h5py
g = h5py.File("a1.h5", "r")["sweep"]
for i, E in enumerate(g["energy"][:]):
    for j, w in enumerate(g["omega"][:]):
        S = float(g["amplitude"][i, j])
        print(f"ref_{i}_{j} {E!r} {w!r} {S!r} ref")
        if g["predictable"][i, j] == 0:
            n = 4  # -sweep_mcr_twins (default): the first run and 4 twins
            for t in range(n + 1):
                k = 0.0 if t == 0 else (-1.0 if (t - 1) % 2 else 1.0) * ((t - 1) // 2 + 1)
                print(f"twin_{i}_{j}_{t} {E!r} {w!r} {S * (1 + k * 1e-10)!r} twin")
PYEOF
SIM=(-options_file "$SRC/options/simulate.opts" -sim_store_u 0 -sim_sample_dt 0 -sim_progress 0)
while read -r name E W S kind; do
  if [ "$kind" = ref ]; then
    run1 "${SIM[@]}" -force_energy "$E" -force_omega "$W" -force_amplitude "$S" -sim_dt_quartic_energy 0 -sim_ts_type rkn -sim_ts_rkn_scheme dep1210 \
         -sim_ts_rtol 1e-13 -sim_ts_atol 1e-13 -sim_ts_dt 0.1 -sim_ts_adapt_dt_max 0.05 -output "$name.h5" > /dev/null
  else
    run1 "${SIM[@]}" -force_energy "$E" -force_omega "$W" -force_amplitude "$S" -sim_dt_quartic_energy 100 -sim_ts_type symsplit -sim_ts_dt 0.1 \
         -output "$name.h5" > /dev/null
  fi
done < runs.txt

$PY - <<'PYEOF'
import glob
import h5py, numpy as np
a1, a2 = (h5py.File(n, "r")["sweep"] for n in ("a1.h5", "a2.h5"))
for k in ("mcr", "mcr_error", "mcr_spread", "predictable", "mcr_runs", "t_off", "amplitude"):
    assert np.array_equal(a1[k][:], a2[k][:], equal_nan=True), ("np1 vs np2", k)
assert a1.attrs["mcr_tol"] == 1e-3
tol = 1e-3
pred = a1["predictable"][:]
# the insulated mode at E* = 1e-2 is regular and converged; omega = 2.1 at E* = 200 is chaotic (README "The 0-1 test")
assert pred[0, 0] == 1 and a1["mcr_error"][0, 0] <= tol and a1["mcr_spread"][0, 0] == 0, (pred, a1["mcr_error"][:])
assert pred[1, 1] == 0 and np.isnan(a1["mcr_error"][1, 1]), (pred, a1["mcr_error"][:])
for i in range(2):
    for j in range(2):
        m = a1["mcr"][i, j]
        ref = h5py.File(f"ref_{i}_{j}.h5", "r")["simulate"].attrs["mcr"]
        if pred[i, j] == 1 and a1["mcr_error"][i, j] <= tol:
            print(f"point ({i}, {j}) predictable: MCR {m:.8f}, converged {ref:.8f}, rel. diff {abs(m / ref - 1):.1e}, estimate {a1['mcr_error'][i, j]:.1e}")
            assert abs(m / ref - 1) <= tol, (i, j, m, ref)
        elif pred[i, j] == 0:
            twins = [h5py.File(f, "r")["simulate"].attrs["mcr"] for f in sorted(glob.glob(f"twin_{i}_{j}_*.h5"))]
            assert len(twins) == 5 and a1["mcr_runs"][i, j] >= 5, (len(twins), a1["mcr_runs"][i, j])
            spread = max(twins) - min(twins)
            print(f"point ({i}, {j}) unpredictable: MCR {m:.6f} = mean of {len(twins)} twins {np.mean(twins):.6f}, spread {a1['mcr_spread'][i, j]:.2e} "
                  f"({spread:.2e}); one run at reference accuracy: {ref:.6f}")
            assert abs(m - np.mean(twins)) <= 1e-12 * abs(m), (m, np.mean(twins))
            assert abs(a1["mcr_spread"][i, j] - spread) <= 1e-12 and spread > tol * m, (a1["mcr_spread"][i, j], spread)
# the cost card: every rank's integrations summed (np2 too), the same work as the per-point counts
for name, g in (("a1.h5", a1), ("a2.h5", a2)):
    c = h5py.File(name, "r")["cost"].attrs
    assert c["sim_force_evaluations"] == g["rhs_evals"][:].sum(), (name, c["sim_force_evaluations"], g["rhs_evals"][:].sum())
    assert c["sim_integrator"] in (b"symsplit bm4", "symsplit bm4") and c["sim_rejected_steps"] == 0
    assert 0 < c["error_estimate"] <= tol, c["error_estimate"]
print("accuracy-aware sweep OK")
PYEOF
