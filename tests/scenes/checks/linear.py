#!/usr/bin/python3
"""Checks of the linear scene (tests/scenes/linear.sh); usage: linear.py STEP."""
import os
import sys
sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
import math
import numpy as np
from scene_check import attr_str, group, main, require, same


def spectrum():
    """options/linear.opts: outputs.md /linear, the insulated frequency sqrt(3), the band edges, the Zak phases,
    orthonormal eigenvectors of K; 1 and 2 ranks agree."""
    f, g = group("lin1.h5"), group("lin2.h5")
    for k in ("study", "version", "options", "wall_seconds"):
        require(k in f.attrs, k)
    require(attr_str(f, "study") == "linear")
    L = f["linear"]
    N = 102
    require(L["omega"].shape == (N,) and L["modes"].shape == (N, N))
    w = L["omega"][:]
    require(np.all(np.diff(w) >= 0), "omega ascending")
    a = L.attrs
    require(abs(a["insulated_omega"] - math.sqrt(3)) < 1e-10)
    require(1.9494 <= a["optical_bottom"] < 1.96, a["optical_bottom"])
    require(2.23 < a["optical_top"] <= 2.23607, a["optical_top"])
    require(1.47 < a["acoustic_top"] <= 1.48325, a["acoustic_top"])
    require(abs(a["interface_omega"] - 2.27) < 0.01, a["interface_omega"])
    B = L["bloch"]
    require(abs(B.attrs["zak_left_optical"] - math.pi) < 1e-8)
    require(abs(B.attrs["zak_right_optical"]) < 1e-8)
    require(abs(B["omega_optical"][:].min() - math.sqrt(3.8)) < 1e-3 and abs(B["omega_optical"][:].max() - math.sqrt(5)) < 1e-12)
    # modes are orthonormal eigenvectors of the spec's K
    K = 3 * np.eye(N)
    for i in range(1, N):
        kb = (0.6 if i % 2 else 1.4) if i <= 50 else (1.4 if i % 2 else 0.6)
        K[i - 1, i] = K[i, i - 1] = -kb
    X = L["modes"][:]
    require(np.abs(X @ X.T - np.eye(N)).max() < 1e-10)
    require(np.abs(X @ K - (w ** 2)[:, None] * X).max() < 1e-10)
    # 1 and 2 ranks give the same answer
    M = g["linear"]
    require(np.abs(M["omega"][:] - w).max() < 1e-12)
    require(np.abs(M["modes"][:] - X).max() < 1e-8)
    require(np.abs(M["insulated_mode"][:] - L["insulated_mode"][:]).max() < 1e-10)
    print("linear scene OK")


def transition():
    """The topological transition (options/transition.opts, paper Fig. 2a): shapes, Zak phases 0/pi/NaN, the
    gamma = 0.4 row = /linear/omega of the plain run, closed forms at gamma = 0 and +-1, the interface mode;
    1 and 2 ranks bit for bit."""
    f, g, lin = group("tr1.h5"), group("tr2.h5"), group("lin1.h5")
    require("transition" not in lin["linear"], "a plain linear run writes no /linear/transition")
    T = f["linear/transition"]
    N, ng = 102, 201
    require(T["gamma"].shape == (ng,) and T["omega"].shape == (ng, N) and T["zak_left"].shape == (ng, 2) and T["zak_right"].shape == (ng, 2))
    gam, w, zl, zr = T["gamma"][:], T["omega"][:], T["zak_left"][:], T["zak_right"][:]
    require(np.abs(gam - np.linspace(-1, 1, ng)).max() < 1e-15)
    require(gam[100] == 0.0 and np.array_equal(gam, -gam[::-1]))
    require(np.all(np.diff(w, axis=1) >= 0), "each row ascending")
    # Zak phases: left cell pi for gamma > 0 and 0 for gamma < 0, right cell the reverse, NaN at gamma = 0 (gap closed)
    pos, neg = gam > 0, gam < 0
    for z, (hi, lo) in ((zl, (pos, neg)), (zr, (neg, pos))):
        require(np.abs(z[hi] - math.pi).max() < 1e-10 and np.abs(z[lo]).max() < 1e-10)
        require(np.isnan(z[100]).all() and np.isfinite(np.delete(z, 100, axis=0)).all())
    # the spectrum at gamma = 0.4 is /linear/omega of the plain run (options/linear.opts)
    i = int(np.argmin(abs(gam - 0.4)))
    require(gam[i] == 0.4)
    require(np.abs(w[i] - lin["linear/omega"][:]).max() < 1e-12, np.abs(w[i] - lin["linear/omega"][:]).max())
    # the rest of the file is the plain study's
    require(np.abs(f["linear/omega"][:] - lin["linear/omega"][:]).max() == 0)
    # closed forms (model.md, k = 1, gamma0 = 1, k_hat = 3): gamma = 0 a uniform chain, 3 - 2 cos(j pi / (N + 1));
    # gamma = -1 decoupled dimers (1 and 5, 50 each) and two isolated sites (3);
    # gamma = 1 dimers, the trimer around the interface site (3 -+ 2 sqrt(2), 3) and the isolated site 1
    chain = np.sort(3 - 2 * np.cos(np.arange(1, N + 1) * math.pi / (N + 1)))
    require(np.abs(w[100] ** 2 - chain).max() < 1e-12)
    require(np.abs(w[0] ** 2 - np.sort([1.0] * 50 + [3.0] * 2 + [5.0] * 50)).max() < 1e-12)
    require(np.abs(w[-1] ** 2 - np.sort([1.0] * 49 + [5.0] * 49 + [3.0] * 2 + [3 - 2 * math.sqrt(2), 3 + 2 * math.sqrt(2)])).max() < 1e-12)
    require((T["lambda_min"][:] > 0).all())
    # the interface mode above the optical band exists for gamma > 0 only (the stiff-stiff interface site;
    # at gamma = 0.01 its decay length, about 1/gamma cells, exceeds the 25 cells of a half)
    b = T["bands_inf"][:]
    above = (w > b[:, 3:4] * (1 + 1e-9)).sum(axis=1)
    require((above[gam >= 0.02] == 1).all() and (above[gam <= 0] == 0).all(), above)
    # 1 and 2 ranks give the same numbers, bit for bit
    G = g["linear/transition"]
    for k in T:
        require(same(T[k], G[k]), k)
    print("transition scene OK")


def large_n():
    """N = 10002 (the shift-invert path) on 2 ranks: the insulated and interface frequencies, the band edges."""
    L = group("big.h5", "linear")
    a = L.attrs
    require("modes_selected" in L and L["modes_selected"].shape[1] == 10002)
    require(abs(a["insulated_omega"] - math.sqrt(3)) < 1e-10)
    require(abs(a["interface_omega"] - 2.2702567967) < 1e-8)
    # finite edges converge to the closed form as (pi/N)^2
    for k, inf in (("acoustic_top", math.sqrt(2.2)), ("optical_bottom", math.sqrt(3.8)), ("optical_top", math.sqrt(5.0))):
        require(abs(a[k] - inf) < 1e-5, k, a[k], inf)
    print("large-N linear OK")


if __name__ == "__main__":
    main(globals())
