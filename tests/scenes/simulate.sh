# options/simulate.opts: a paper-default forced run; outputs.md /simulate; MCR equal on 1 and 2 ranks to 1e-8.
source "$(dirname "$0")/common.bash"
run1 -options_file "$SRC/options/simulate.opts" -output sim1.h5 | tee out1.txt
run2 -options_file "$SRC/options/simulate.opts" -output sim2.h5 | tee out2.txt
$PY - <<'PYEOF'
import h5py, numpy as np
f, g = h5py.File("sim1.h5", "r"), h5py.File("sim2.h5", "r")
for k in ("study", "version", "options", "wall_seconds"):
    assert k in f.attrs, k
S = f["simulate"]
N, nt = 102, 1001
assert S["t"].shape == (nt,) and S["energy"].shape == (nt,) and S["u"].shape == (nt, N) and S["rms"].shape == (N,)
a = S.attrs
for k in ("mcr", "t_off", "energy_final", "nl_ratio", "rhs_evals", "steps"):
    assert k in a, k
assert a["energy_reached"] == 1 and 0 < a["t_off"] < 1000
assert abs(a["energy_final"] - 1.0) < 1e-3, a["energy_final"]
t, E = S["t"][:], S["energy"][:]
assert abs(t[-1] - 1000) < 1e-9 and E[0] == 0
after = E[t > a["t_off"]]
assert np.abs(after - a["energy_final"]).max() < 1e-3, "energy conserved after the cut-off"
# the per-step RMS agrees with the RMS of the 1 s samples over the same window
u = S["u"][:]
w = t >= a["window_start"]
rms_samples = np.sqrt((u[w] ** 2).mean(axis=0))
assert np.abs(rms_samples - S["rms"][:]).max() < 0.02 * S["rms"][:].max()
# the insulated mode is excited: even sites dominate around the interface
rms = S["rms"][:]
assert rms[51] > 5 * rms[50] and 0.3 < a["mcr"] < 0.4, a["mcr"]
# 1 and 2 ranks: same MCR to 1e-8, same trajectory
b = g["simulate"].attrs
assert abs(a["mcr"] - b["mcr"]) < 1e-8, (a["mcr"], b["mcr"])
assert abs(a["t_off"] - b["t_off"]) < 1e-8
assert np.abs(g["simulate/u"][:] - u).max() < 1e-8
# the cost card: one solve, the run's own step and evaluation counts
for n in ("sim1.h5", "sim2.h5"):
    c, r = h5py.File(n, "r")["cost"].attrs, h5py.File(n, "r")["simulate"].attrs
    assert c["sim_solves"] == 1 and c["sim_steps"] == r["steps"] and c["sim_force_evaluations"] == r["rhs_evals"], (n, dict(c))
    assert c["sim_integrator"] in (b"symsplit bm4", "symsplit bm4") and c["sim_dt_max"] == 0.25 and c["wall_seconds"] > 0
print("simulate scene OK: MCR", a["mcr"], "np2 diff", abs(a["mcr"] - b["mcr"]))
PYEOF
# Strongly nonlinear E* = 10: the linear amplitude rule misses E* (the lattice
# detunes), the rescaling finds an S that reaches it inside the burst.
run1 -options_file "$SRC/options/simulate.opts" -force_energy 10 -sim_store_u 0 -output sim10.h5 > out10.txt
$PY - <<'PYEOF'
import h5py
a = h5py.File("sim10.h5", "r")["simulate"].attrs
assert a["energy_reached"] == 1 and a["amplitude_rescalings"] >= 1, dict(a)
assert abs(a["energy_final"] - 10) < 1e-2, a["energy_final"]
print("E* = 10 reached after", a["amplitude_rescalings"], "rescalings of S, S =", a["amplitude"])
PYEOF
# Damping (-lattice_damping c, an effect): simulate honours it with an rk
# type. After the cut-off dE/dt = -2 c E_kin: E(t) / E* >= exp(-2 c (t - t_off))
# (all energy kinetic), and by the virial theorem the mean kinetic share is
# p / (p + 2) >= 1/2 for potentials of degree p >= 2, so E(t) / E* <= about
# exp(-c (t - t_off)); 1 and 2 ranks agree.
run1 -options_file "$SRC/options/simulate.opts" -sim_ts_type rk -sim_store_u 0 -sim_t_final 600 -lattice_damping 0.01 -output simd1.h5 > outd1.txt
run2 -options_file "$SRC/options/simulate.opts" -sim_ts_type rk -sim_store_u 0 -sim_t_final 600 -lattice_damping 0.01 -output simd2.h5 > outd2.txt
$PY - <<'PYEOF'
import h5py, numpy as np
a, b = h5py.File("simd1.h5", "r")["simulate"], h5py.File("simd2.h5", "r")["simulate"]
A = a.attrs
assert A["energy_reached"] == 1, dict(A)
t, E = a["t"][:], a["energy"][:]
after = t >= A["t_off"]
ratio = E[-1] / A["energy_star"]
lower, virial = np.exp(-0.02 * (t[-1] - A["t_off"])), np.exp(-0.01 * (t[-1] - A["t_off"]))
assert lower < ratio < 1.02 * virial, (ratio, lower, virial)
assert np.all(np.diff(E[after]) <= 1e-12 * E[after][:-1]), "damped energy must never grow after the cut-off"
assert abs(A["mcr"] - b.attrs["mcr"]) < 1e-8 and np.abs(b["energy"][:] - E).max() < 1e-8
print("damped run: E(t_final)/E* =", ratio, "in [exp(-2c dt), exp(-c dt)] =", [lower, virial])
PYEOF
