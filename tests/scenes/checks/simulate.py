#!/usr/bin/python3
"""Checks of the simulate scene (tests/scenes/simulate.sh); usage: simulate.py STEP."""
import os
import sys
sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
import numpy as np
from scene_check import attr_str, group, main, require


def paper():
    """options/simulate.opts on 1 and 2 ranks: outputs.md /simulate, E* = 1 reached, the insulated mode's MCR,
    the same run on 2 ranks to 1e-8, the cost card."""
    f, g = group("sim1.h5"), group("sim2.h5")
    for k in ("study", "version", "options", "wall_seconds"):
        require(k in f.attrs, k)
    S = f["simulate"]
    N, nt = 102, 1001
    require(S["t"].shape == (nt,) and S["energy"].shape == (nt,) and S["u"].shape == (nt, N) and S["rms"].shape == (N,))
    a = S.attrs
    for k in ("mcr", "t_off", "energy_final", "nl_ratio", "rhs_evals", "steps"):
        require(k in a, k)
    require(a["energy_reached"] == 1 and 0 < a["t_off"] < 1000)
    require(abs(a["energy_final"] - 1.0) < 1e-3, a["energy_final"])
    t, E = S["t"][:], S["energy"][:]
    require(abs(t[-1] - 1000) < 1e-9 and E[0] == 0)
    after = E[t > a["t_off"]]
    require(np.abs(after - a["energy_final"]).max() < 1e-3, "energy conserved after the cut-off")
    # the per-step RMS agrees with the RMS of the 1 s samples over the same window
    u = S["u"][:]
    w = t >= a["window_start"]
    rms_samples = np.sqrt((u[w] ** 2).mean(axis=0))
    require(np.abs(rms_samples - S["rms"][:]).max() < 0.02 * S["rms"][:].max())
    # the insulated mode is excited: even sites dominate around the interface
    rms = S["rms"][:]
    require(rms[51] > 5 * rms[50] and 0.3 < a["mcr"] < 0.4, a["mcr"])
    # 1 and 2 ranks: same MCR to 1e-8, same trajectory
    b = g["simulate"].attrs
    require(abs(a["mcr"] - b["mcr"]) < 1e-8, a["mcr"], b["mcr"])
    require(abs(a["t_off"] - b["t_off"]) < 1e-8)
    require(np.abs(g["simulate/u"][:] - u).max() < 1e-8)
    # the cost card: one solve, the run's own step and evaluation counts
    for n in ("sim1.h5", "sim2.h5"):
        c, r = group(n, "cost").attrs, group(n, "simulate").attrs
        require(c["sim_solves"] == 1 and c["sim_steps"] == r["steps"] and c["sim_force_evaluations"] == r["rhs_evals"], n, dict(c))
        require(attr_str(c, "sim_integrator") == "symsplit bm4" and c["sim_dt_max"] == 0.25 and c["wall_seconds"] > 0)
    print("simulate scene OK: MCR", a["mcr"], "np2 diff", abs(a["mcr"] - b["mcr"]))


def strong():
    """E* = 10: reached after rescaling S (the linear amplitude rule misses it)."""
    a = group("sim10.h5", "simulate").attrs
    require(a["energy_reached"] == 1 and a["amplitude_rescalings"] >= 1, dict(a))
    require(abs(a["energy_final"] - 10) < 1e-2, a["energy_final"])
    print("E* = 10 reached after", a["amplitude_rescalings"], "rescalings of S, S =", a["amplitude"])


def damped():
    """Damping c = 0.01 after the cut-off: dE/dt = -2 c E_kin, so E(t) / E* >= exp(-2 c (t - t_off)) (all energy
    kinetic), and by the virial theorem the mean kinetic share is p / (p + 2) >= 1/2 for potentials of degree
    p >= 2, so E(t) / E* <= about exp(-c (t - t_off)); the energy never grows; 1 and 2 ranks agree."""
    a, b = group("simd1.h5", "simulate"), group("simd2.h5", "simulate")
    A = a.attrs
    require(A["energy_reached"] == 1, dict(A))
    t, E = a["t"][:], a["energy"][:]
    after = t >= A["t_off"]
    ratio = E[-1] / A["energy_star"]
    lower, virial = np.exp(-0.02 * (t[-1] - A["t_off"])), np.exp(-0.01 * (t[-1] - A["t_off"]))
    require(lower < ratio < 1.02 * virial, ratio, lower, virial)
    require(np.all(np.diff(E[after]) <= 1e-12 * E[after][:-1]), "damped energy must never grow after the cut-off")
    require(abs(A["mcr"] - b.attrs["mcr"]) < 1e-8 and np.abs(b["energy"][:] - E).max() < 1e-8)
    print("damped run: E(t_final)/E* =", ratio, "in [exp(-2c dt), exp(-c dt)] =", [lower, virial])


if __name__ == "__main__":
    main(globals())
