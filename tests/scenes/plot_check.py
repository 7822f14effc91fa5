#!/usr/bin/python3
"""Content check of an nltopo plot script's figure (docs/testing.md): runs
the script as its user would, catches every figure at savefig, and checks
every panel (every axes but colorbars) against four rules:

1. data: the panel holds data -- a line, scatter, fill, mesh or image with
   finite values.
2. limits: its axis limits cover its finite data: the points of its lines and
   scatters, the vertices of its fills, the centres of the mesh cells
   (pcolormesh) that hold finite values, and the extent of its images (log
   axes: the positive part). Reference lines and spans drawn in axes
   coordinates (axhline, axvline, axhspan, axvspan) are not data. A log axis
   that autoscaled past its mesh (the empty 1e3..1e4 axis of a mesh whose
   linear cell edges go negative) fails here.
3. axis labels: non-empty x and y labels.
4. legend: the panel's *labelled artists* are its lines, collections
   (scatters, fills, meshes) and patches whose label is set and does not
   start with '_' and that hold finite data. A panel with two or more
   labelled artists has a legend that names each of them, and every entry of
   a panel's legend is the label of one of its labelled artists (no entry for
   a series that is not drawn, is empty, or belongs to another panel). A panel
   with at most one labelled artist may go without a legend: its axis labels
   and title say what it draws.

Writes the figure as the script would.

usage: plot_check.py <script.py> [script arguments...]
Prints one line per panel; exits non-zero naming the script, the first failing
panel and the rule it breaks. run_and_check(script, args) and
check_figure(fig) are importable (plot_check_selftest.py)."""
import os
import runpy
import sys
import matplotlib
matplotlib.use("Agg")
import matplotlib.collections
import matplotlib.figure
import matplotlib.image
import matplotlib.lines
import matplotlib.patches
import numpy as np


class PlotCheckError(AssertionError):
    pass


def _data_coords(artist, ax):
    return artist.get_transform() == ax.transData


def finite_points(ax):
    """(x, y) of the data-coordinate lines, scatters and fills of a panel, and
    the centres of its mesh cells that hold finite values."""
    pts = []
    for l in ax.get_lines():
        if not _data_coords(l, ax):  # axhline / axvline: axes coordinates
            continue
        x, y = np.asarray(l.get_xdata(), float), np.asarray(l.get_ydata(), float)
        if x.size == 1 and y.size > 1:
            x = np.full_like(y, x[0])
        pts.append(np.column_stack([np.broadcast_to(x, y.shape), y]))
    for c in ax.collections:
        if isinstance(c, matplotlib.collections.QuadMesh):
            if not _data_coords(c, ax):
                continue
            xy = np.asarray(c.get_coordinates(), float)  # (ny + 1, nx + 1, 2) vertices
            centres = 0.25 * (xy[:-1, :-1] + xy[1:, :-1] + xy[:-1, 1:] + xy[1:, 1:])
            arr = c.get_array()
            if arr is None:
                continue
            vals = np.ma.filled(np.ma.asarray(arr, float), np.nan).reshape(centres.shape[:2])
            pts.append(centres[np.isfinite(vals)])
        elif isinstance(c, matplotlib.collections.PathCollection):  # scatters
            if c.get_offset_transform() == ax.transData and len(c.get_offsets()):
                pts.append(np.asarray(c.get_offsets(), float))
        elif isinstance(c, matplotlib.collections.PolyCollection) and _data_coords(c, ax):  # fill_between
            for p in c.get_paths():
                pts.append(np.asarray(p.vertices, float))
    for im in ax.get_images():
        x0, x1, y0, y1 = im.get_extent()
        if np.isfinite(np.asarray(im.get_array(), float)).any():
            pts.append(np.array([[x0, y0], [x1, y1]], float))
    p = np.concatenate(pts) if pts else np.zeros((0, 2))
    return p[np.isfinite(p).all(axis=1)]


def artist_has_data(a):
    """True if an artist of a panel draws at least one finite value."""
    if isinstance(a, matplotlib.lines.Line2D):
        x, y = np.asarray(a.get_xdata(), float), np.asarray(a.get_ydata(), float)
        if x.size == 0 or y.size == 0:
            return False
        try:
            x, y = np.broadcast_arrays(x, y)
        except ValueError:
            return False
        return bool((np.isfinite(x) & np.isfinite(y)).any())
    if isinstance(a, matplotlib.collections.PathCollection) and len(a.get_offsets()):  # scatter
        return bool(np.isfinite(np.asarray(a.get_offsets(), float)).all(axis=1).any())
    if isinstance(a, matplotlib.collections.Collection):  # meshes, fills, line collections
        arr = a.get_array()
        if arr is not None:
            return bool(np.isfinite(np.ma.filled(np.ma.asarray(arr, float), np.nan)).any())
        return any(len(p.vertices) and np.isfinite(p.vertices).all(axis=1).any() for p in a.get_paths())
    if isinstance(a, matplotlib.patches.Patch):
        return True
    if isinstance(a, matplotlib.image.AxesImage):
        return bool(np.isfinite(np.asarray(a.get_array(), float)).any())
    return False


def labelled_artists(ax):
    """[(label, artist)] of the panel's drawn artists with a legend label."""
    out = []
    for a in list(ax.get_lines()) + list(ax.collections) + list(ax.patches) + list(ax.get_images()):
        lab = a.get_label()
        if isinstance(lab, str) and lab and not lab.startswith("_") and artist_has_data(a):
            out.append((lab, a))
    return out


def holds_data(ax):
    if len(finite_points(ax)):
        return True
    for c in ax.collections:  # meshes, contours
        arr = c.get_array()
        if arr is not None and np.isfinite(np.ma.filled(np.ma.asarray(arr, float), np.nan)).any():
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


def check_panel(ax, name):
    """Raises PlotCheckError naming the rule a panel breaks; returns a summary."""
    if not holds_data(ax):
        raise PlotCheckError(f"panel '{name}' holds no finite data (rule 1, data)")
    p = finite_points(ax)
    ok, axis, data, lim = covered(ax, p)
    if not ok:
        raise PlotCheckError(f"panel '{name}': {axis} data {data} outside the limits {lim} (rule 2, limits)")
    for axis, text in (("x", ax.get_xlabel()), ("y", ax.get_ylabel())):
        if not text.strip():
            raise PlotCheckError(f"panel '{name}' has no {axis} label (rule 3, axis labels)")
    labelled = labelled_artists(ax)
    labels = [lab for lab, _ in labelled]
    leg = ax.get_legend()
    entries = [t.get_text() for t in leg.get_texts()] if leg is not None else []
    if len(labelled) > 1 and leg is None:
        raise PlotCheckError(f"panel '{name}' draws {len(labelled)} labelled series ({', '.join(labels)}) but has no legend (rule 4, legend)")
    for e in entries:
        if e not in labels:
            raise PlotCheckError(f"panel '{name}': legend entry '{e}' names no drawn series of this panel (drawn: {labels}) (rule 4, legend)")
    if leg is not None:
        for lab in labels:
            if lab not in entries:
                raise PlotCheckError(f"panel '{name}': series '{lab}' is missing from the legend {entries} (rule 4, legend)")
    return f"{len(p)} points, limits cover them, labels '{ax.get_xlabel()[:20]}' / '{ax.get_ylabel()[:20]}', " + \
        (f"legend of {len(entries)}" if leg is not None else f"{len(labelled)} labelled series, no legend")


def check_figure(fig, script="figure"):
    """Checks every panel of a figure; returns one line per panel."""
    panels = [ax for ax in fig.axes if ax.get_label() != "<colorbar>"]
    if not panels:
        raise PlotCheckError(f"{script}: a figure without panels")
    lines = []
    for i, ax in enumerate(panels):
        name = ax.get_title() or ax.get_ylabel() or f"panel {i}"
        try:
            summary = check_panel(ax, name)
        except PlotCheckError as e:
            raise PlotCheckError(f"{script}: {e}") from None
        lines.append(f"{script.split('/')[-1]}: panel '{name[:50]}': {summary}")
    return lines


def run_and_check(script, args):
    """Runs a plot script with its arguments as its user would (the figures
    caught at savefig and written) and checks every figure it saves; returns
    one line per panel, raises PlotCheckError naming the first failure."""
    caught = []
    save = matplotlib.figure.Figure.savefig

    def savefig(self, *a, **k):
        caught.append(self)
        return save(self, *a, **k)

    argv, path = sys.argv, list(sys.path)
    matplotlib.figure.Figure.savefig = savefig
    sys.argv = [script] + list(args)
    sys.path.insert(0, os.path.dirname(os.path.abspath(script)))  # as when the script is run itself (nltopo_plot)
    try:
        runpy.run_path(script, run_name="__main__")
    finally:
        matplotlib.figure.Figure.savefig = save
        sys.argv, sys.path[:] = argv, path
    if not caught:
        raise PlotCheckError(f"{script} saved no figure")
    lines = []
    for fig in caught:
        lines += check_figure(fig, script)
    return lines


def main():
    try:
        for line in run_and_check(sys.argv[1], sys.argv[2:]):
            print(line)
    except PlotCheckError as e:
        sys.exit(f"plot_check: FAILED: {e}")


if __name__ == "__main__":
    main()
