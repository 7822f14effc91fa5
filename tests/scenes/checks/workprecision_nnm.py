#!/usr/bin/python3
"""Checks of the workprecision_nnm scene (tests/scenes/workprecision_nnm.sh); usage: workprecision_nnm.py STEP."""
import os
import sys
sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
import numpy as np
from scene_check import attr_str, group, main, rel, require


def shooting():
    """The linear lattice: the reference frequency is an eigenfrequency of K, |mu| = 1, the errors fall at
    each method's order (bm4 4, bm6 6) as the steps per period double, det M = 1 for the splittings; np1 = np2."""
    w = group("lin.h5", "linear/omega")[:]
    g1, g2 = (group(n, "workprecision") for n in ("s1.h5", "s2.h5"))
    a = g1.attrs
    require(attr_str(a, "scene") == "shooting")
    exact = w[np.argmin(np.abs(w - a["reference_omega"]))]
    print("reference omega", a["reference_omega"], "eigenfrequency", exact, "max|mu|", a["reference_max_modulus"])
    require(rel(a["reference_omega"], exact) < 1e-13, a["reference_omega"], exact)
    require(abs(a["reference_max_modulus"] - 1) < 1e-12 and a["reference_converged"] == 1)
    method = [m.decode() for m in g1["method"][:]]
    acc = [x.decode() for x in g1["accuracy"][:]]
    e = g1["error_omega"][:]
    def err(m, n):
        return e[[k for k in range(len(method)) if method[k] == m and acc[k] == f"{n} steps/period"][0]]
    for m, order, steps in (("symsplit bm4", 4, (32, 64, 128)), ("symsplit bm6", 6, (32, 64))):
        for n0, n1 in zip(steps, steps[1:]):
            r = err(m, n0) / err(m, n1)
            print(f"{m}: omega error {n0} -> {n1} steps per period divided by {r:.1f} (2^{order} = {2 ** order})")
            require(0.7 * 2 ** order < r < 1.4 * 2 ** order, m, n0, r)
    det = g1["error_det"][:]
    for k, m in enumerate(method):
        if m.startswith("symsplit"):
            require(det[k] < 1e-12, m, acc[k], det[k])
    # np1 = np2 to rounding; the closure |z_ref(T) - z0| to the orbit's own accuracy, -nnm_snes_atol 1e-12
    # (Newton's last iterate differs between 1 and 2 ranks by the reductions' rounding: 1.9e-13 with OpenBLAS)
    for o, floor in (("omega", 1e-13), ("closure", 1e-12), ("max_modulus", 1e-13), ("det", 1e-13)):
        x, y = g1["error_" + o][:], g2["error_" + o][:]
        require(np.all(np.abs(x - y) <= 1e-6 * np.abs(x) + floor), o, x, y)
    print("workprecision shooting scene OK")


if __name__ == "__main__":
    main(globals())
