#!/usr/bin/python3
"""Checks of the sweep_refine scene (tests/scenes/sweep_refine.sh); usage: sweep_refine.py STEP [ARGUMENTS]."""
import os
import sys
sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
import h5py
import numpy as np
from scene_check import main, require

WALL = {"seconds"}
FIELDS = None  # the per-point fields: every 1-D dataset of /sweep/refined but the coordinates


def samples(path):
    """{(energy_index, omega_index) on the file's lattice: {field: value}}, the lattice depth, and
    whether the file holds K. A grid file: its points, depth 0."""
    with h5py.File(path, "r") as f:
        s = f["sweep"]
        kcorr = int(s.attrs["kcorr_computed"]) == 1
        if "refined" in s:
            r = s["refined"]
            ei, wi = r["energy_index"][()], r["omega_index"][()]
            names = [k for k in r if k not in ("omega_index", "energy_index")]
            vals = {k: r[k][()] for k in names}
            out = {(int(ei[k]), int(wi[k])): {n: vals[n][k] for n in names} for k in range(len(ei))}
            return out, int(r.attrs["depth"]), kcorr
        ne, no = len(s["energy"]), len(s["omega"])
        names = [k for k in s if s[k].shape == (ne, no)]
        vals = {k: s[k][()] for k in names}
        out = {(e, w): {n: vals[n][e, w] for n in names} for e in range(ne) for w in range(no)}
        for (e, w), p in out.items():
            p["omega"], p["energy"], p["level"] = s["omega"][()][w:w + 1][0], s["energy"][()][e:e + 1][0], np.int32(0)
        return out, 0, kcorr


def expected(prev, mcr, kc, ratio, budget):
    """The new points (lattice coordinates one depth below prev's), by the rule of
    docs/studies/sweep.md, computed here independently of the C++."""
    pts, depth, kcorr = samples(prev)
    D = depth + 1
    have = {(2 * e, 2 * w): p for (e, w), p in pts.items()}
    ne = 1 + 2 * max(e for e, _ in pts)
    no = 1 + 2 * max(w for _, w in pts)
    cells = []
    for d in range(D):
        s = 2 ** (D - d)
        for e in range(0, ne - s, s):
            for w in range(0, no - s, s):
                c = [(e, w), (e, w + s), (e + s, w), (e + s, w + s)]
                if not all(x in have for x in c) or (e + s // 2, w + s // 2) in have:
                    continue
                p = [have[x] for x in c]
                pred = [int(q["predictable"]) for q in p]
                if pred.count(0) == 4:
                    continue
                prio, over = 0.0, False
                m = [float(q["mcr"]) for q in p]
                spread = max(float(q["mcr_spread"]) for q in p)
                dm = max(m) - min(m)
                if dm > mcr and dm > spread:
                    over, prio = True, max(prio, dm / max(mcr, spread))
                if kcorr:
                    k = [float(q["kcorr"]) for q in p]
                    if all(np.isfinite(k)) and max(k) - min(k) > kc:
                        over, prio = True, max(prio, (max(k) - min(k)) / kc)
                r = [float(q["nl_ratio"]) for q in p]
                if all(x > 0 for x in r):
                    dr = np.log(max(r)) - np.log(min(r))
                    if dr > ratio:
                        over, prio = True, max(prio, dr / ratio)
                if 0 in pred and 1 in pred:
                    over, prio = True, max(prio, 1.0)
                if over:
                    cells.append((-prio, d, e, w))
    cells.sort()
    new = []
    for _, d, e, w in cells:
        h = 2 ** (D - d - 1)
        cand = [(e, w + h), (e + 2 * h, w + h), (e + h, w), (e + h, w + 2 * h), (e + h, w + h)]
        fresh = [x for x in cand if x not in have and x not in new]
        if budget and len(new) + len(fresh) > budget:
            break
        new += fresh
    return set(new), have, len(cells)


def level(prev, path, mcr="0.02", kc="0.3", ratio="1", budget="0"):
    """path, a refinement level of prev: its new points are exactly those of the cells over the
    thresholds (recomputed here), prev's points are carried over bit for bit, levels and
    coordinates agree with the lattice, and the Python reader reads it."""
    new, have, over = expected(prev, float(mcr), float(kc), float(ratio), int(budget))
    got, depth, _ = samples(path)
    _, dprev, _ = samples(prev)
    require(depth == dprev + 1, depth, dprev)
    require(set(got) == set(have) | new, "new points differ", sorted(set(got) - set(have) - new), sorted(new - set(got)))
    with h5py.File(path, "r") as f:
        r = f["sweep/refined"]
        require(int(r.attrs["points_new"]) == len(new) and int(r.attrs["cells_over"]) == over, int(r.attrs["points_new"]), len(new))
        require(int(f.attrs["complete"]) == 1 and int(f["sweep"].attrs["points_computed"]) == len(new))
    for x, p in have.items():
        for k, v in p.items():
            same = np.asarray(v).tobytes() == np.asarray(got[x][k]).tobytes() if k != "level" else int(v) == int(got[x][k])
            require(k in WALL or same, "carried point differs", x, k, v, got[x][k])
    for (e, w), p in got.items():
        lev = 0
        while lev < depth and (e % 2 ** (depth - lev) or w % 2 ** (depth - lev)):
            lev += 1
        require(int(p["level"]) == lev and int(p["done"]) == 1, (e, w), p["level"], lev)
    sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "..", "python"))
    import nltopo
    s = nltopo.Run(path).sweep
    require(s.refined is not None and len(s.refined["mcr"]) == len(got) and s.triangulation().triangles.shape[0] > 0)
    require(nltopo.Run(prev).sweep.refined is None or dprev > 0)
    print("%s: %d points (%d carried bit for bit from %s, %d new = the %d cells over the thresholds%s), depth %d"
          % (path, len(got), len(have), prev, len(new), over, ", up to the budget %s" % budget if budget != "0" else "", depth))
    with h5py.File(path, "r") as f:
        leaves = int(f["sweep/refined"].attrs["leaves"])
    # the test can fail: some leaves refined, some not (the budget cuts a level short)
    require(0 < len(new) and 0 < over < leaves if budget == "0" else 0 < len(new) <= int(budget) < 5 * over, "degenerate selection", len(new), over, leaves)


def base(path, grid):
    """The base grid's datasets of the refinement level path equal the grid file's bit for bit (but the wall times)."""
    with h5py.File(path, "r") as a, h5py.File(grid, "r") as b:
        for k in b["sweep"]:
            require(k in WALL or a["sweep"][k][()].tobytes() == b["sweep"][k][()].tobytes(), "base dataset differs", k)
    print("%s: its /sweep grid datasets = %s bit for bit" % (path, grid))


def incomplete(src, dst):
    """dst: a copy of the grid src with one point marked not done."""
    import shutil
    shutil.copyfile(src, dst)
    with h5py.File(dst, "r+") as f:
        d = f["sweep/done"][()]
        d.flat[0] = 0
        f["sweep/done"][...] = d


def undo_new(src, dst):
    """dst: a copy of the level src with its new points (level = depth) marked not done and complete = 0
    (what an interrupted level leaves at <output>.partial.h5)."""
    import shutil
    shutil.copyfile(src, dst)
    with h5py.File(dst, "r+") as f:
        r = f["sweep/refined"]
        d = r["done"][()]
        d[r["level"][()] == int(r.attrs["depth"])] = 0
        r["done"][...] = d
        f.attrs["complete"] = np.int32(0) if f.attrs["complete"].dtype == np.int32 else 0


def same(path, ref):
    """path equals ref bit for bit in /sweep and /sweep/refined but the wall times."""
    with h5py.File(path, "r") as a, h5py.File(ref, "r") as b:
        for g in ("sweep", "sweep/refined"):
            for k in b[g]:
                if hasattr(b[g][k], "keys"):
                    continue
                require(k in WALL or a[g][k][()].tobytes() == b[g][k][()].tobytes(), "dataset differs", g, k)
        require(int(a.attrs["complete"]) == 1)
        n = int((b["sweep/refined/level"][()] == int(b["sweep/refined"].attrs["depth"])).sum())
    print("%s: the level resumed (%d points computed again) = %s bit for bit" % (path, n, ref))


def plot(path, src):
    """src/plots/plot_sweep.py draws the level path from its samples: panel (a) the MCR on a triangulation
    of every sample (its values the file's), the samples marked by level with the counts of the file."""
    sys.path.insert(0, os.path.join(src, "src", "plots"))
    sys.path.insert(0, os.path.join(src, "python"))
    import plot_sweep
    import nltopo
    run = nltopo.Run(path)
    r = run.sweep.refined
    fig = plot_sweep.refined_figure(run, run.sweep)
    a = fig.axes[0]
    mesh = [c for c in a.collections if hasattr(c, "get_array") and c.get_array() is not None][0]
    require(np.array_equal(np.sort(np.asarray(mesh.get_array())), np.sort(np.asarray(r["mcr"]))), "the map is not the samples' MCR")
    labels = [t.get_text() for t in a.get_legend().get_texts()]
    lev = np.asarray(r["level"])
    want = ["level %d (%d points)" % (k, (lev == k).sum()) for k in range(lev.max() + 1)]
    require(labels[:len(want)] == want, labels, want)
    print("%s: plot_sweep.py draws the MCR of its %d samples triangulated, marked %s" % (path, len(lev), "; ".join(want)))


if __name__ == "__main__":
    main(globals())
