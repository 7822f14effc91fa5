#!/usr/bin/python3
"""Checks of the stabilitymap scene (tests/scenes/stabilitymap.sh); usage: stabilitymap.py STEP FILES."""
import os
import sys
sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
import numpy as np
from scene_check import attr_str, group, main, require


def content(path):
    """The map of one size against the truths it does not use: the base branch's own Floquet classes on
    the raster column at the run's p (orbits within 1 % of a curve's crossing left out), the check branch's
    classes (agree: 1 or -1 only, some 1), each check event within 1e-3 of a curve of its kind (and its
    event_curve row names one); every curve through its event (row event_point at p_base, the event's E to
    1e-6) with its test function at zero; region codes 0, 2 or 3; no inconsistent column."""
    top = group(path, "/stabilitymap")
    require(attr_str(top, "parameter") == "-lattice_gamma" and top.attrs["sizes"] == 1 and top.attrs["checks"] == 2, dict(top.attrs))
    p, E, pb = top["p"][:], top["energy"][:], float(top.attrs["p_base"])
    g = group(path, "/stabilitymap/cells5")
    R = g["region"][:]
    require(R.shape == (len(p), len(E)) and set(np.unique(R)) <= {0, 2, 3}, R.shape, np.unique(R))
    require(g.attrs["inconsistent_columns"] == 0, g.attrs["inconsistent_columns"])
    names = attr_str(g, "curves").split(",")
    require(len(names) == len(g["curve_kind"][:]) >= 2, names)
    ev_E, ev_curve = g["event_energy"][:], g["event_curve"][:]
    for row, name in enumerate(names):
        c = group(path, "/stabilitymap/cells5/curves/" + name)
        k = int(c.attrs["event_point"])
        require(np.all(np.abs(c["test"][:]) < 1e-10), name, c["test"][:])
        if g["curve_seed"][row] == -1:
            e = int(g["curve_event"][row])
            # (the event is located to -cont_bif_tol 1e-7 in omega; the curve refines it to g = 0)
            require(c["p"][k] == pb and abs(c["energy"][k] / ev_E[e] - 1) < 1e-6 and ev_curve[e] == row, name, c["energy"][k], ev_E[e])
    # the raster column at p_base against the branch's own classes
    i = int(np.argmin(np.abs(p - pb)))
    require(abs(p[i] - pb) < 1e-12, p[i], pb)
    bE, bI = g["branch_energy"][:], g["branch_instability"][:]
    crossings = [c for name in names for c in crossings_at(group(path, "/stabilitymap/cells5/curves/" + name), pb)]
    compared = 0
    for e_, cls in zip(bE, bI):
        if e_ < E[0] or e_ > E[-1] or any(abs(x / e_ - 1) < 0.01 for x in crossings):
            continue
        j = int(np.argmin(np.abs(np.log(E / e_))))
        if any(min(E[j], e_) <= x <= max(E[j], e_) for x in crossings):
            continue  # a boundary between the orbit and its raster row
        require(R[i, j] == cls, "orbit E %g class %d, raster (%g, %g) %d" % (e_, cls, p[i], E[j], R[i, j]))
        compared += 1
    require(compared >= 3, compared)
    for k in (0, 1):  # the checks at gamma 0.42 and 0.41 (at 2 ranks one per group of ranks, merged in order)
        ch = group(path, "/stabilitymap/checks/check%d" % k)
        a = ch["agree"][:]
        require(set(np.unique(a)) <= {-1, 1} and (a == 1).sum() >= 3, k, a)
        off, cur = ch["event_offset"][:], ch["event_curve"][:]
        require(len(off) >= 1 and np.all(off < 1e-3) and np.all(cur >= 0) and np.all(cur < len(names)), k, off, cur)
        print("stabilitymap: %d curves, raster column at p_base matches %d branch orbits, check %d (gamma %g): %d orbits agree, %d events on "
              "curves (largest offset %.1e)" % (len(names), compared, k, ch.attrs["p"], (a == 1).sum(), len(off), off.max()))


def crossings_at(c, pc):
    """The energies where curve c crosses p = pc (linear in ln E between its points)."""
    p, E = c["p"][:], c["energy"][:]
    out = []
    for k in range(len(p) - 1):
        if (p[k] - pc) * (p[k + 1] - pc) <= 0 and p[k] != p[k + 1]:
            t = (pc - p[k]) / (p[k + 1] - p[k])
            out.append(float(np.exp((1 - t) * np.log(E[k]) + t * np.log(E[k + 1]))))
    return out


def ranks(a_path, b_path):
    """1 and 2 ranks: the same curves (rows to 5e-8 relative) and the same raster."""
    a, b = group(a_path, "/stabilitymap/cells5"), group(b_path, "/stabilitymap/cells5")
    require(attr_str(a, "curves") == attr_str(b, "curves"), attr_str(a, "curves"), attr_str(b, "curves"))
    require(np.array_equal(a["region"][:], b["region"][:]), "region rasters differ")
    worst = 0.0
    for name in attr_str(a, "curves").split(","):
        x, y = group(a_path, "/stabilitymap/cells5/curves/" + name), group(b_path, "/stabilitymap/cells5/curves/" + name)
        require(x["p"].shape == y["p"].shape, name, x["p"].shape, y["p"].shape)
        for f in ("p", "energy", "omega"):
            worst = max(worst, float(np.max(np.abs(x[f][:] - y[f][:]) / np.abs(x[f][:]))))
    require(worst <= 5e-8, worst)  # (rows on the curve to -cont_codim2_tol; their places along it drift with rounding, as in codim2.py)
    print("stabilitymap 1 vs 2 ranks: same curves (largest relative difference %.1e) and raster" % worst)


if __name__ == "__main__":
    main(globals())
