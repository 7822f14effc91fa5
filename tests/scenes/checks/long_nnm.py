#!/usr/bin/python3
"""Checks of the long_nnm scene (tests/scenes/long_nnm.sh); usage: long_nnm.py STEP."""
import os
import shutil
import sys
sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
import h5py
import numpy as np
from scene_check import attr_str, group, main, multipliers, require


def branches():
    """The matrix-free branches of N = 102 and 1002 (and the one resumed from floquet.h5) on the dense N = 102
    branch, GMRES iterations per Newton step that do not grow with N; the matrix-free multipliers on the
    circle, led by the edge mode's pair; N = 102 to E = 20: the dense leading pairs against the full dense
    analysis, the matrix-free route never "stable" where a quadruplet is unstable, no spurious verdict."""
    g = lambda f: group(f, "continuation/insulated")
    D, A, B, F, R = g("dense.h5"), g("mf102.h5"), g("mf1002.h5"), g("floquet.h5"), g("resumed.h5")
    # the resumed branch keeps the points it was given, bit for bit, and goes on along the same family
    n0 = len(F["energy"])
    require(len(R["energy"]) > n0 + 1 and np.array_equal(R["energy"][:n0], F["energy"][:]) and np.array_equal(R["z0"][:n0], F["z0"][:]), len(R["energy"]))
    require(R["energy"][n0] > F["energy"][-1])
    for X in (A, B, R):
        require(X.attrs["reached_energy_max"] == 1)
        # same orbits as the dense route: omega at the mf energies, by 4-point Lagrange interpolation in log E
        led, wd = np.log(D["energy"][:]), D["omega"][:]
        matched, worst = 0, 0.0
        for e, w in zip(X["energy"][:], X["omega"][:]):
            k = min(max(np.searchsorted(led, np.log(e)) - 2, 0), len(led) - 4)
            xs, ys, x = led[k:k + 4], wd[k:k + 4], np.log(e)
            wi = sum(ys[i] * np.prod([(x - xs[j]) / (xs[i] - xs[j]) for j in range(4) if j != i]) for i in range(4))
            worst = max(worst, abs(w - wi) / wi)
            matched += 1
        require(worst < 1e-7, worst)
        require(matched >= 20, matched)
        if X == R: print("resumed branch: %d + %d points on the dense N = 102 branch to %.1e" % (n0, len(R["energy"]) - n0, worst))
        require(X["energy"][-1] <= D["energy"][-1], X["energy"][-1], D["energy"][-1])   # no extrapolation
        # the Krylov count of a resumed run covers its new points only
        per_newton = X.attrs["krylov_iterations"] / X["newton_its"][n0 if X == R else 0:].sum()
        require(per_newton < 20, per_newton)
        print("mf branch:", len(X["energy"]), "points on the dense N = 102 branch to %.1e; GMRES per Newton step" % worst, round(per_newton, 1))
    ka, kb = A.attrs["krylov_iterations"], B.attrs["krylov_iterations"]
    require(kb <= 1.2 * ka + 10, ka, kb)   # N = 1002 needs no more Krylov iterations than N = 102
    mm, w = F["max_modulus"][:], F["omega"][:]
    require(F["multipliers_re"].shape == (len(mm), 1))   # -floquet_mf_nev 1: the leading nontrivial pair
    require(attr_str(F, "floquet_route") == "matrix-free", F.attrs["floquet_route"])
    # matrix-free, all on the circle: no verdict (a complex quadruplet inside the spectrum cannot be excluded)
    require(np.all(np.abs(mm - 1) < 1e-4) and np.all(F["stable"][:] == -1) and F.attrs["floquet_undecided"] == len(mm), mm)
    mu = multipliers(F)
    b = ((mu + 1 / mu) / 2).real
    b_edge = np.cos(2 * np.pi * np.sqrt(3) / w)
    # where the edge pair is distinguishable from the (deflated) trivial pair b = 1, up to E ~ 1
    sel = (1 - b_edge > 1e-6) & (w < 1.76)
    require(sel.sum() >= 6, sel.sum())
    err = np.abs(b[sel, 0] - b_edge[sel]).max()
    require(err < 1e-8, err)
    print("matrix-free Floquet, E <= 1: max |mu| - 1 = %.1e; nontrivial pair = edge mode's to %.1e (%d orbits)" % (np.abs(mm - 1).max(), err, sel.sum()))

    # N = 102 to E = 20: the leading pair against every dense multiplier of the same orbits
    L, D20, M20 = g("lead20.h5"), g("dense20.h5"), g("mf20.h5")
    route = lambda X: attr_str(X, "floquet_route")
    require(route(L) == "dense" and route(M20) == "matrix-free", route(L), route(M20))
    n = len(D20["energy"])
    require(n >= 20 and len(L["energy"]) == n and len(M20["energy"]) == n, n, len(L["energy"]), len(M20["energy"]))
    require(np.allclose(L["energy"][:], D20["energy"][:], rtol=1e-8, atol=0))   # 2 ranks: the same orbits
    mu = multipliers(D20)
    unstable_quads = 0
    for i in range(n):
        m = mu[i][np.argsort(np.abs(mu[i] - 1))][2:]      # the trivial pair: the two nearest 1
        lead = m[np.argmax(np.abs(m))]
        ref_stable = np.abs(lead) <= 1 + 1e-4
        require(abs(L["max_modulus"][i] - np.abs(lead)) < 1e-6, i, L["max_modulus"][i], np.abs(lead))
        require(L["stable"][i] == int(ref_stable) == D20["stable"][i], i, L["stable"][i], D20["stable"][i])
        # the leading pair's Krein signature: that of the same multiplier in the full analysis
        lm = L["multipliers_re"][i, 0] + 1j * L["multipliers_im"][i, 0]
        j = np.argmin(np.abs(mu[i] - lm))
        require(abs(mu[i][j] - lm) < 1e-6 and L["krein"][i, 0] == D20["krein"][i, j], i, lm, L["krein"][i, 0], D20["krein"][i, j])
        require(L["instability"][i] == D20["instability"][i], i, L["instability"][i], D20["instability"][i])
        if not ref_stable:   # the kind: the leading multiplier itself (complex: a Krein-collision quadruplet)
            require(abs(abs(lm) - abs(lead)) < 1e-6 and (abs(lead.imag) > 1e-6) == (abs(lm.imag) > 1e-6), i, lm, lead)
            if abs(lead.imag) > 1e-6:
                unstable_quads += 1
                require(M20["stable"][i] == -1, i, M20["stable"][i])   # matrix-free: never "stable" here
        require(M20["stable"][i] in (-1, 0) and M20["instability"][i] == -1, M20["stable"][i], M20["instability"][i])
    require(unstable_quads >= 3, unstable_quads)   # E = 0.94, 1.86, 3.72 (benchmarks/README.md)
    G = g("largest.h5")
    ng = len(G["energy"])
    require(np.allclose(G["energy"][:], D20["energy"][:ng], rtol=1e-8, atol=0))
    for i in range(ng):   # "unstable" only where the dense route says so, and never the spurious value
        require(G["stable"][i] in (-1, 0) and (G["stable"][i] == -1 or D20["stable"][i] == 0), i, G["stable"][i], D20["stable"][i])
        require(not np.isfinite(G["max_modulus"][i]) or G["max_modulus"][i] < 1.1, i, G["max_modulus"][i])
    require("spurious Ritz values rejected" in open("largest.txt").read())
    print("N = 102 to E = 20: dense leading pairs on 2 ranks = full dense analysis at %d orbits (%d unstable quadruplets); matrix-free: %d not decided"
          % (n, unstable_quads, (M20["stable"][:] == -1).sum()))


def make_old_files():
    """Make the -floquet_mf files written before the verdicts (no floquet_route, krein or instability; stable = 1
    meant only max |mu| <= 1 + tol) from mf20.h5: old_mf.h5, and old_mf_noopt.h5 without -floquet_mf_dense_max."""
    for name, strip_option in (("old_mf.h5", False), ("old_mf_noopt.h5", True)):
        shutil.copy("mf20.h5", name)
        with h5py.File(name, "r+") as f:
            g = f["continuation/insulated"]
            for k in ("krein", "instability"): del g[k]
            for a in ("floquet_route", "floquet_undecided"): del g.attrs[a]
            st = np.ones_like(g["stable"][:]); del g["stable"]; g["stable"] = st
            if strip_option:   # an old file has no -floquet_mf_dense_max: at N = 102 this run's route is dense
                o = attr_str(f, "options")
                f.attrs["options"] = np.bytes_(o.replace(" -floquet_mf_dense_max 0", ""))


def old_file_resumed():
    """An old -floquet_mf file resumed: its stable = 1 is no verdict, every orbit not decided, no class."""
    R = group("resumed_mf.h5", "continuation/insulated")
    n0 = len(group("mf20.h5", "continuation/insulated/energy"))
    require(len(R["energy"]) > n0)
    # the old stable = 1 is not a verdict: not decided; no class was computed
    require(np.all(R["stable"][:] == -1) and np.all(R["instability"][:] == -1) and R.attrs["floquet_undecided"] == len(R["energy"]), R["stable"][:])
    print("resumed an old -floquet_mf file: %d orbits, all not decided" % len(R["energy"]))


def localized():
    """The localized route through the continuation (N = 202, E <= 1, 1 and 2 ranks): a verdict per orbit,
    stable-to(delta) or unstable-localized confirmed on the undamped lattice, its bound |mu| - 1 and e-folding
    time 1/ln|mu|; the same verdicts at 2 ranks."""
    A = group("loc1.h5", "continuation/insulated")
    B = group("loc2.h5", "continuation/insulated")
    require(attr_str(A, "floquet_route") == "localized")
    v, bound, efold, mm = A["verdict"][:], A["verdict_bound"][:], A["verdict_efold"][:], A["max_modulus"][:]
    reasons = [r.decode() if isinstance(r, bytes) else str(r) for r in A["verdict_reason"][:]]
    require(set(v.tolist()) <= {1, 3} and (v == 1).sum() >= 2 and (v == 3).sum() >= 5, v)   # the lowest orbits stable-to, E ~ 0.2-1 B-E
    u = v == 1
    require(np.allclose(bound[u], mm[u] - 1, rtol=1e-12) and np.allclose(efold[u], 1 / np.log(mm[u]), rtol=1e-12), bound[u])
    require(all("confirmed on the undamped lattice" in r for r, x in zip(reasons, u) if x), reasons)
    require(np.all(A["instability"][:][u] >= 2))   # localized: B-E or E-E
    # stable-to(delta): delta is at least -floquet_tol (1e-4) and no more than 1e-3 (the resolution)
    require(np.all((bound[~u] >= 1e-4) & (bound[~u] <= 1e-3) & np.isinf(efold[~u])), bound[~u])
    require(np.array_equal(v, B["verdict"][:]) and np.allclose(bound, B["verdict_bound"][:], rtol=1e-8, atol=1e-12), B["verdict"][:], B["verdict_bound"][:])
    print("localized route: %d stable-to, %d unstable-localized (|mu| - 1 up to %.2e), the same at 2 ranks" % ((v == 3).sum(), u.sum(), bound[u].max()))


if __name__ == "__main__":
    main(globals())
