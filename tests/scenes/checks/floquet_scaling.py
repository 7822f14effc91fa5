#!/usr/bin/python3
"""Checks of the floquet_scaling scene (tests/scenes/floquet_scaling.sh); usage: floquet_scaling.py STEP."""
import os
import sys
sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
import numpy as np
from scene_check import complete, group, main, require


def fit(N, env, tol, thr):
    """The rule of stability/envelope_fit.cpp, independently: least squares of ln env on ln N over env > tol."""
    ok = np.isfinite(env) & (env > tol)
    if np.isfinite(env).any() and not ok.any():
        return np.nan, 0, 0
    if ok.sum() < 2:
        return np.nan, ok.sum(), 3
    slope, icpt = np.polyfit(np.log(N[ok]), np.log(env[ok]), 1)
    p = -slope
    res = np.log(env[ok]) - (icpt + slope * np.log(N[ok]))
    se = np.sqrt((res ** 2).sum() / (ok.sum() - 2) / ((np.log(N[ok]) - np.log(N[ok]).mean()) ** 2).sum()) if ok.sum() > 2 else 0.0
    verdict = 3 if abs(p - thr) <= se else (1 if p < thr else 2)
    return p, ok.sum(), verdict


def content():
    """s1.h5 (1 rank: three sizes) and s2.h5 (2 ranks: the first two): each size each a branch to E = 2 with the dense route's columns in range
    (PR in [1, N] sites, edge share in [0, 1], the class from the edge share on unstable orbits); each window's envelope
    the largest |mu| - 1 of its orbits, its exponent the log-log least squares of them, the verdict by the documented
    rule, s2.h5's envelopes of B-E orbits only (-scaling_class 2); 2 ranks equal to 1 rank on the sizes both ran."""
    tol = 1e-6  # -floquet_tol's default
    fits = 0
    for path, cells in (("s1.h5", (5, 10, 20)), ("s2.h5", (5, 10))):
        require(complete(path), path)
        top = group(path, "floquet_scaling")
        require(top.attrs["sizes_done"] == len(cells) and abs(top.attrs["floquet_tol"] - tol) < 1e-15, dict(top.attrs))
        thr, cls = top.attrs["persist_exponent"], top.attrs["class"]
        W = group(path, "floquet_scaling/windows")
        N = W["N"][:]
        require(list(N) == [4 * c + 2 for c in cells], N)
        lo, hi = W["energy_lo"][:], W["energy_hi"][:]
        require(list(lo) == [0, 0.5, 1] and list(hi) == [0.5, 1, 2], lo, hi)
        unstable = 0
        for k, c in enumerate(cells):
            g = group(path, "floquet_scaling/cells%d" % c)
            require(g.attrs["N"] == N[k] and g.attrs["cells"] == c, dict(g.attrs))
            E, m, st, cl = g["energy"][:], g["max_modulus"][:], g["stable"][:], g["instability"][:]
            pr, edge = g["leading_participation"][:], g["leading_edge_share"][:]
            require(E[0] < 2e-5 and E[-1] >= 2 and len(E) == g.attrs["points"], E[0], E[-1])
            require(np.all(st == (m <= 1 + tol)), st, m)
            require(np.all((pr >= 1 - 1e-12) & (pr <= N[k] + 1e-9)) and np.all((edge >= 0) & (edge <= 1)), pr, edge)
            u = st == 0
            unstable += u.sum()
            # the class of an unstable orbit from its leading vector's edge share (-floquet_edge_weight 0.75)
            want = np.where(edge > 0.75, 3, np.where(edge < 0.25, 1, 2))
            require(np.all(cl[u] == want[u]) and np.all(cl[~u] == 0), cl, edge)
            mc = np.where((cls > 0) & (cl > 0) & (cl != cls), 1.0, m)  # -scaling_class: other classes count as stable
            for w in range(len(lo)):
                sel = (E >= lo[w]) & (E < hi[w])
                env = (mc[sel].max() - 1) if sel.any() else np.nan
                require(np.isclose(W["envelope"][w, k], env, rtol=0, atol=1e-15, equal_nan=True), w, k, W["envelope"][w, k], env)
        require(unstable >= 3 and cls == (2 if path == "s2.h5" else 0), unstable, cls)  # the branch has B-E quadruplets below E = 2 at these sizes
        for w in range(len(lo)):
            p, n, v = fit(N, W["envelope"][w], tol, thr)
            require(W["npoints"][w] == n and W["verdict"][w] == v, w, W["npoints"][w], n, W["verdict"][w], v)
            require(np.isclose(W["exponent"][w], p, rtol=0, atol=1e-10, equal_nan=True), w, W["exponent"][w], p)
            fits += n >= 2
            if n >= 2:
                C = W["prefactor"][w]
                pred = np.log(C) - p * np.log(N)
                ok = W["envelope"][w] > tol
                require(np.isclose(W["residual"][w], np.sqrt(np.mean((np.log(W["envelope"][w][ok]) - pred[ok]) ** 2)), atol=1e-10), w)
    require(fits >= 3, fits)  # windows with an unstable orbit at two sizes or more: fitted
    for c in (5, 10):
        x, y = group("s1.h5", "floquet_scaling/cells%d" % c), group("s2.h5", "floquet_scaling/cells%d" % c)
        require(len(x["energy"][:]) == len(y["energy"][:]), c)
        require(np.allclose(x["energy"][:], y["energy"][:], rtol=1e-9, atol=0), c)
        require(np.allclose(x["max_modulus"][:], y["max_modulus"][:], rtol=0, atol=1e-9), c)
        require(np.allclose(x["leading_participation"][:], y["leading_participation"][:], rtol=1e-6), c)
    wa = group("s1.h5", "floquet_scaling/windows")
    print("floquet_scaling scene OK: exponents", np.round(wa["exponent"][:], 3), "verdicts", wa["verdict"][:])


if __name__ == "__main__":
    main(globals())
