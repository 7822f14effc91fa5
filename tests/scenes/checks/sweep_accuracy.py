#!/usr/bin/python3
"""Checks of the sweep_accuracy scene (tests/scenes/sweep_accuracy.sh); usage: sweep_accuracy.py STEP."""
import glob
import os
import sys
sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
import numpy as np
from scene_check import attr_str, group, main, rel, require, same


def runs():
    """Print the simulate runs that check a1.h5 (name E* omega S kind step): at every point the reference with the
    sweep's S; at an unpredictable point also the probe: the run at its step mcr_dt and its 4 twins, S x (1 + k 1e-10)."""
    g = group("a1.h5", "sweep")
    for i, E in enumerate(g["energy"][:]):
        for j, w in enumerate(g["omega"][:]):
            S = float(g["amplitude"][i, j])
            print(f"ref_{i}_{j} {E!r} {w!r} {S!r} ref 0")
            if g["predictable"][i, j] == 0:
                n = 4  # -sweep_mcr_twins (default): the probe's run and 4 twins
                for t in range(n + 1):
                    k = 0.0 if t == 0 else (-1.0 if (t - 1) % 2 else 1.0) * ((t - 1) // 2 + 1)
                    print(f"twin_{i}_{j}_{t} {E!r} {w!r} {S * (1 + k * 1e-10)!r} twin {float(g['mcr_dt'][i, j])!r}")


def rule_step(E, w, top, tol=1e-3, phi=0.36, Eq=15.0):
    """The step rule of -sweep_mcr_dt_phase phi -sweep_mcr_dt_energy Eq (docs/studies/sweep.md): a phase phi per
    step of the forcing and of the hardened bonds (top (E / Eq)^(1/4)), at most 1 / top."""
    return min(min(phi / w, phi / (top * (E / Eq) ** 0.25)) * (tol / 1e-3) ** 0.25, 1 / top)


def accuracy():
    """np1 = np2; the predictable points within -sweep_mcr_tol of the converged runs; an unpredictable point's
    mcr and mcr_spread the mean and spread of its twins; the cost card."""
    a1, a2 = (group(n, "sweep") for n in ("a1.h5", "a2.h5"))
    for k in ("mcr", "mcr_error", "mcr_spread", "mcr_dt", "predictable", "mcr_runs", "t_off", "amplitude"):
        require(same(a1[k], a2[k]), "np1 vs np2", k)
    require(a1.attrs["mcr_tol"] == 1e-3 and a1.attrs["mcr_dt_phase"] == 0.36 and a1.attrs["mcr_dt_energy"] == 15)
    top = float(a1.attrs["optical_top_inf"])
    tol = 1e-3
    pred = a1["predictable"][:]
    # each point's step: the rule's h(E*) where the first run stood (3 runs: it, the check at 2 h, a twin), else a
    # halving of it (the step ladder) or 2 h (the probe of an unpredictable point)
    for i, E in enumerate(a1["energy"][:]):
        for j, w in enumerate(a1["omega"][:]):
            h, dt = rule_step(E, w, top), a1["mcr_dt"][i, j]
            ratio = dt / h
            require(any(abs(ratio - r) <= 1e-12 for r in (2, 1, 0.5, 0.25, 0.125)), i, j, dt, h)
            if pred[i, j] == 1 and a1["mcr_runs"][i, j] == 3:
                require(abs(ratio - 1) <= 1e-12 and a1["mcr_error"][i, j] <= tol / 4, i, j, dt, h, a1["mcr_error"][i, j])
    h00 = rule_step(a1["energy"][0], a1["omega"][0], top)
    require(abs(a1["mcr_dt"][0, 0] / h00 - 1) <= 1e-12 and a1["mcr_runs"][0, 0] == 3, a1["mcr_dt"][0, 0], h00, a1["mcr_runs"][0, 0])
    # the insulated mode at E* = 1e-2 is regular and converged; omega = 2.1 at E* = 200 is chaotic (docs/model.md "The 0-1 test for chaos")
    require(pred[0, 0] == 1 and a1["mcr_error"][0, 0] <= tol and a1["mcr_spread"][0, 0] == 0, pred, a1["mcr_error"][:])
    require(pred[1, 1] == 0 and np.isnan(a1["mcr_error"][1, 1]), pred, a1["mcr_error"][:])
    for i in range(2):
        for j in range(2):
            m = a1["mcr"][i, j]
            ref = group(f"ref_{i}_{j}.h5", "simulate").attrs["mcr"]
            if pred[i, j] == 1 and a1["mcr_error"][i, j] <= tol:
                print(f"point ({i}, {j}) predictable: MCR {m:.8f}, converged {ref:.8f}, rel. diff {rel(m, ref):.1e}, estimate {a1['mcr_error'][i, j]:.1e}")
                require(rel(m, ref) <= tol, i, j, m, ref)
            elif pred[i, j] == 0:
                twins = [group(f, "simulate").attrs["mcr"] for f in sorted(glob.glob(f"twin_{i}_{j}_*.h5"))]
                require(len(twins) == 5 and a1["mcr_runs"][i, j] >= 5, len(twins), a1["mcr_runs"][i, j])
                spread = max(twins) - min(twins)
                print(f"point ({i}, {j}) unpredictable: MCR {m:.6f} = mean of {len(twins)} twins {np.mean(twins):.6f}, spread {a1['mcr_spread'][i, j]:.2e} "
                      f"({spread:.2e}); one run at reference accuracy: {ref:.6f}")
                require(abs(m - np.mean(twins)) <= 1e-12 * abs(m), m, np.mean(twins))
                require(abs(a1["mcr_spread"][i, j] - spread) <= 1e-12 and spread > tol * m, a1["mcr_spread"][i, j], spread)
    # the cost card: every rank's integrations summed (np2 too), the same work as the per-point counts
    for name, g in (("a1.h5", a1), ("a2.h5", a2)):
        c = group(name, "cost").attrs
        require(c["sim_force_evaluations"] == g["rhs_evals"][:].sum(), name, c["sim_force_evaluations"], g["rhs_evals"][:].sum())
        require(attr_str(c, "sim_integrator") == "symsplit bm4" and c["sim_rejected_steps"] == 0)
        require(0 < c["error_estimate"] <= tol, c["error_estimate"])
    print("accuracy-aware sweep OK")


if __name__ == "__main__":
    main(globals())
