#!/usr/bin/python3
"""Content check of an nltopo plot script's figure (README.md "Tests"): runs
the script as its user would, catches the figure at savefig, and checks every
panel: it holds data (a line, scatter, mesh or image with finite values), and
its axis limits cover the finite data of its lines and scatters (log axes:
the positive part). Reference lines drawn in axes coordinates (axhline,
axvline, axvspan) are not data. Writes the figure as the script would.

usage: plot_check.py <script.py> [script arguments...]
Prints one line per panel; exits non-zero naming the first failing panel."""
import runpy
import sys
import matplotlib
matplotlib.use("Agg")
import matplotlib.collections
import matplotlib.figure
import os
import numpy as np

caught = []
_save = matplotlib.figure.Figure.savefig


def savefig(self, *a, **k):
    caught.append(self)
    return _save(self, *a, **k)


matplotlib.figure.Figure.savefig = savefig
script = sys.argv[1]
sys.argv = sys.argv[1:]
sys.path.insert(0, os.path.dirname(os.path.abspath(script)))  # as when the script is run itself (nltopo_plot)
runpy.run_path(script, run_name="__main__")
assert caught, f"{script} saved no figure"


def finite_points(ax):
    """(x, y) of the data-coordinate lines and scatters of a panel."""
    pts = []
    for l in ax.get_lines():
        if l.get_transform() != ax.transData:  # axhline / axvline: axes coordinates
            continue
        x, y = np.asarray(l.get_xdata(), float), np.asarray(l.get_ydata(), float)
        if x.size == 1 and y.size > 1:
            x = np.full_like(y, x[0])
        pts.append(np.column_stack([np.broadcast_to(x, y.shape), y]))
    for c in ax.collections:  # scatter points in data coordinates
        if isinstance(c, matplotlib.collections.PathCollection) and c.get_offset_transform() == ax.transData and len(c.get_offsets()):
            pts.append(np.asarray(c.get_offsets(), float))
    p = np.concatenate(pts) if pts else np.zeros((0, 2))
    return p[np.isfinite(p).all(axis=1)]


def holds_data(ax):
    if len(finite_points(ax)):
        return True
    for c in ax.collections:  # meshes, contours
        arr = c.get_array()
        if arr is not None and np.isfinite(np.asarray(arr, float)).any():
            return True
    return any(np.isfinite(np.asarray(im.get_array(), float)).any() for im in ax.get_images())


def covered(ax, p):
    for k, (lo, hi), scale in ((0, ax.get_xlim(), ax.get_xscale()), (1, ax.get_ylim(), ax.get_yscale())):
        v = p[:, k]
        if scale == "log":
            v = v[v > 0]
        if not len(v):
            continue
        lo, hi = min(lo, hi), max(lo, hi)
        span = (np.log10(hi) - np.log10(lo)) if scale == "log" and lo > 0 else hi - lo
        tol = 1e-9 * abs(span)
        if scale == "log" and lo > 0:
            if np.log10(v.min()) < np.log10(lo) - tol or np.log10(v.max()) > np.log10(hi) + tol:
                return False, "xy"[k], (v.min(), v.max()), (lo, hi)
        elif v.min() < lo - tol or v.max() > hi + tol:
            return False, "xy"[k], (v.min(), v.max()), (lo, hi)
    return True, None, None, None


for fig in caught:
    panels = [ax for ax in fig.axes if ax.get_label() != "<colorbar>"]
    assert panels, f"{script}: a figure without panels"
    for i, ax in enumerate(panels):
        name = ax.get_title() or ax.get_ylabel() or f"panel {i}"
        assert holds_data(ax), f"{script}: panel '{name}' holds no finite data"
        p = finite_points(ax)
        ok, axis, data, lim = covered(ax, p)
        assert ok, f"{script}: panel '{name}': {axis} data {data} outside the limits {lim}"
        print(f"{script.split('/')[-1]}: panel '{name[:50]}': {len(p)} points, limits cover them")
