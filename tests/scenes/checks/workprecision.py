#!/usr/bin/python3
"""Checks of the workprecision scene (tests/scenes/workprecision.sh); usage: workprecision.py STEP."""
import os
import sys
sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
import numpy as np
from scene_check import attr_str, group, main, rel, require


def amplitude():
    """Print the forcing amplitude S the study used, for the shell."""
    print(repr(float(group("wp1.h5", "workprecision").attrs["amplitude"])))


def errors():
    """outputs.md /workprecision at 1 and 2 ranks; at least 3 methods x 3 accuracies, a converged reference, a
    floor below 1e-8; the reported errors equal those of the same configurations run by -study simulate
    against a separate 1e-13 reference (within 10 %)."""
    g1, g2 = (group(n, "workprecision") for n in ("wp1.h5", "wp2.h5"))
    nc = g1["config"].shape[0]
    obs = ("mcr", "t_off", "nl_ratio", "energy", "state")
    for g in (g1, g2):
        for k in ["config", "method", "accuracy", "wall_seconds", "rhs_evals", "steps"] + ["error_" + o for o in obs]:
            require(g[k].shape == (nc,), k, g[k].shape)
        for o in obs:
            require(np.isfinite(g.attrs["spread_" + o]), o)
        require("dep1210" in attr_str(g, "reference"))
        require(g.attrs["reference_converged"] == 1)
        require((g["wall_seconds"][:] > 0).all() and (g["rhs_evals"][:] > 0).all() and (g["steps"][:] > 0).all())
    method = [m.decode() for m in g1["method"][:]]
    acc = {m: {a.decode() for a, mm in zip(g1["accuracy"][:], method) if mm == m} for m in set(method)}
    require(len(acc) >= 3 and all(len(a) >= 3 for a in acc.values()), acc)
    # a regular run: the twins agree far below any integrator's error
    require(g1.attrs["spread_mcr"] < 1e-8, g1.attrs["spread_mcr"])
    # 1 and 2 ranks: the same integrations (errors equal up to the order of the reductions)
    for o in ("mcr", "t_off", "energy", "state"):
        e1, e2 = g1["error_" + o][:], g2["error_" + o][:]
        # rounding of the reductions (~1e-12 in each observable) and, through it, an adaptive step now and then
        require(np.all(np.abs(e1 - e2) <= 1e-4 * np.abs(e1) + 2e-11), o, e1, e2)
    # independent: each configuration as -study simulate against a 1e-13 reference with steps <= 0.0125
    ref = group("ref.h5", "simulate").attrs
    cfg = [c.decode() for c in g1["config"][:]]
    for name, key in (("c_bm4.h5", "-sim_ts_symsplit_scheme bm4 -sim_ts_dt 0.4"), ("c_rk.h5", "-sim_ts_rk_type 5dp -sim_ts_rtol 1e-6"),
                      ("c_dep86.h5", "-sim_ts_rkn_scheme dep86 -sim_ts_rtol 1e-8")):
        i = [k for k, c in enumerate(cfg) if key in c][0]
        s = group(name, "simulate").attrs
        for o, a in (("mcr", "mcr"), ("t_off", "t_off"), ("energy", "energy_final")):
            independent = abs(s[a] - ref[a]) / abs(ref[a])
            reported = g1["error_" + o][i]
            print(f"{cfg[i]}: {o} error reported {reported:.3e}, independent {independent:.3e}")
            require(rel(reported, independent) < 0.1, cfg[i], o, reported, independent)
    print("workprecision scene OK:", nc, "configurations,", len(acc), "methods, floor", g1.attrs["spread_mcr"])


def recommended():
    """-wp_target 1e-6: /workprecision/recommended names, per observable, the configuration of least median wall
    time among those whose error meets the target (recomputed here from the file), and the run printed it."""
    W = group("wp2.h5")["workprecision"]
    R = W["recommended"]
    require(abs(R.attrs["target"] - 1e-6) < 1e-18)
    configs = [c.decode() for c in W["config"][:]]
    wall = W["wall_seconds"][:]
    out = open("wp2.txt").read()
    names = [o.decode() for o in R["observable"][:]]
    require(len(names) >= 3 and "mcr" in names, names)
    met = 0
    for k, name in enumerate(names):
        err = W["error_" + name][:]
        ok = np.isfinite(err) & (err <= 1e-6)
        got = R["config"][k].decode()
        if not ok.any():
            require(got == "" and abs(R["error"][k] - np.nanmin(err)) <= 1e-12 * np.nanmin(err), name)
            continue
        met += 1
        best = min(np.flatnonzero(ok), key=lambda i: wall[i])
        require(got == configs[best] and R["error"][k] == err[best] and R["wall_seconds"][k] == wall[best], name, got, configs[best])
        require(got in out, "the run printed the recommendation", name)
    require(met >= 2, "some configuration meets 1e-6", met)


if __name__ == "__main__":
    main(globals())
