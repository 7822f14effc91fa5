#!/usr/bin/python3
"""Checks of the codim2 scene (tests/scenes/codim2.sh); usage: codim2.py STEP [ARGUMENTS]."""
import os
import sys
sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
import numpy as np
from scene_check import attr_str, group, main, require

CURVE = "/continuation/insulated/codim2/hh0"
FIELDS = ("p", "energy", "omega", "period", "test")


def curve():
    """The Hamiltonian-Hopf curve of event 0 in -lattice_gamma: kind 5, at least 6 points on each side of the
    event (row event_point, at the run's own gamma 0.4), p increasing along the rows over [0.35, 0.45] (one past each bound), the
    test function zero along it; 1 and 2 ranks give the same curve (rows to 5e-8 relative: their places along it drift with rounding)."""
    a, b = group("c1.h5", CURVE), group("c2.h5", CURVE)
    require(a.attrs["kind"] == 5 and a.attrs["event"] == 0 and attr_str(a, "parameter") == "-lattice_gamma",
            dict(a.attrs))
    k, p = int(a.attrs["event_point"]), a["p"][:]
    require(6 <= k <= len(p) - 7 and p[k] == 0.4, k, p)
    require((np.diff(p) > 0).all() and p[0] < 0.35 <= p[1] and p[-2] <= 0.45 < p[-1], p)  # each side keeps its first point past the bound
    require((np.abs(a["test"][:]) < 1e-10).all(), a["test"][:])
    require(a.attrs["event_point"] == b.attrs["event_point"] and a["p"].shape == b["p"].shape, a["p"].shape, b["p"].shape)
    worst = 0.0
    for f in FIELDS[:4]:
        x, y = a[f][:], b[f][:]
        worst = max(worst, float(np.max(np.abs(x - y) / np.abs(x))))
    # the rows: points on the curve to -cont_codim2_tol; where along it a row lies drifts with rounding (the walk's
    # secant gradients, hence its tangents, differ in the last digits between rank counts): 1e-9 per step at most
    require(worst <= 5e-8, worst)
    # its codim-2 points: no turn in p (p increases along the rows), both ends at the bounds of p (code 0, rows 0 and npts - 1)
    for g in (a, b):
        require(list(g["point_kind"][:]) == [0, 0] and list(g["point_arc"][:]) == [0, len(p) - 1], g["point_kind"][:], g["point_arc"][:])
        require(g["point_p"][0] == g["p"][0] and g["point_energy"][-1] == g["energy"][-1] and g["point_omega"][-1] == g["omega"][-1], g["point_p"][:])
        require(str(g["point_kind"].attrs["codes"]).find("1 turn in p") >= 0, g["point_kind"].attrs["codes"])
    print("codim2 curve: %d points, gamma %.4f .. %.4f, E %.4g .. %.4g; 1 vs 2 ranks: largest relative difference %.2g"
          % (len(p), p[0], p[-1], a["energy"][0], a["energy"][-1], worst))


def points():
    """Print the two rows checked against one-parameter runs, event_point -6 and +6: row, p (repr, full
    precision), E."""
    a = group("c1.h5", CURVE)
    k = int(a.attrs["event_point"])
    for r in (k - 6, k + 6):
        print(r, repr(float(a["p"][r])), repr(float(a["energy"][r])))


def through(row, path):
    """The one-parameter run path (the branch at the curve's p of row) locates a Hamiltonian-Hopf onset (kind 5)
    that begins an instability, as the curve's event does, at the curve's omega to 1e-6 and E to 1e-5 relative."""
    c, r = group("c1.h5", CURVE), int(row)
    ev0 = group("c1.h5", "/continuation/insulated/bifurcations")
    p, e, w = float(c["p"][r]), float(c["energy"][r]), float(c["omega"][r])
    bif = group(path, "/continuation/insulated/bifurcations")
    kind, om, en, di = bif["kind"][:], bif["omega"][:], bif["energy"][:], bif["direction"][:]
    hh = np.flatnonzero(kind == 5)
    require(hh.size > 0, kind)
    j = hh[np.argmin(np.abs(om[hh] - w))]
    dw, de = abs(om[j] - w), abs(en[j] - e) / e
    print("codim2 row %d, -lattice_gamma %r (%s): Hamiltonian-Hopf event %d at omega %.10f (curve %.10f, |d| %.2g), "
          "E %.8g (curve %.8g, relative %.2g)" % (r, p, path, j, om[j], w, dw, en[j], e, de))
    require(di[j] == ev0["direction"][c.attrs["event"]] == 1, di[j])
    require(dw <= 1e-6, dw)
    require(de <= 1e-5, de)


if __name__ == "__main__":
    main(globals())
