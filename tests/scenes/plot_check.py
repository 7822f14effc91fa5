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
3. axis labels: non-empty x and y labels (the upper part of an axis broken
   into two panels, gid "broken_axis_upper", has the x label of the panel it
   shares its x axis with).
4. legend: the panel's *labelled artists* are its lines, collections
   (scatters, fills, meshes) and patches whose label is set and does not
   start with '_' and that hold finite data. A panel with two or more
   labelled artists has a legend that names each of them, and every entry of
   a panel's legend is the label of one of its labelled artists (no entry for
   a series that is not drawn, is empty, or belongs to another panel). A panel
   with at most one labelled artist may go without a legend: its axis labels
   and title say what it draws.
5. colour bars: every map (a pcolormesh mesh or an image: the sweep's maps,
   the space-time maps of u) has a colour bar in the figure.
6. numbered markers (the FEP's events): the markers of the lines whose gid is
   "event_markers" each carry a number (a text with gid "event_number <n>"
   at their centre), the numbers are distinct, no two markers' bounding boxes
   overlap in display coordinates, and a table panel of the figure has one
   row (a text with gid "event_row <n>") for each number and no other.
7. point labels (the work-precision points): every text with gid
   "point_label" stands beside a point of a line of its panel, no two of
   them overlap, none covers a marker, and with --point-labels every point of every labelled
   marker line of every panel has one.
A panel with its axes turned off (a table, a note) is checked only for
holding text. Options before the script name what a figure must show:
  --grid RxC        its panels form R rows and C columns, and the figure is
                    no wider than twice its height (the Floquet figure: 2x2);
  --sites a,b,...   every panel that draws site histories (lines with gid
                    "site <n>") draws exactly these sites;
  --point-labels    rule 7 for every point (above).

Writes the figure as the script would.

usage: plot_check.py [--grid RxC] [--sites a,b] [--point-labels] <script.py> [script arguments...]
       plot_check.py --help <script.py> [...]: each script's -h exits 0 and prints its usage
Prints one line per panel; exits non-zero naming the script, the first failing
panel and the rule it breaks. run_and_check(script, args) and
check_figure(fig, script, expect) are importable (plot_check_selftest.py)."""
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
    shared_x = [o for o in ax.figure.axes if ax.get_gid() == "broken_axis_upper" and o is not ax and ax.get_shared_x_axes().joined(ax, o)
                and o.get_xlabel().strip()]
    for axis, text in (("x", ax.get_xlabel() or (shared_x[0].get_xlabel() if shared_x else "")), ("y", ax.get_ylabel())):
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


def panel_name(ax, i):
    return (ax.get_title() or ax.get_title(loc="left") or ax.get_ylabel() or f"panel {i}").replace("\n", " ")


def check_colourbars(ax, name):
    """Rule 5: every mesh and image of the panel has a colour bar in its figure."""
    bars = [a for a in ax.figure.axes if a.get_label() == "<colorbar>"]
    maps = [c for c in ax.collections if isinstance(c, matplotlib.collections.QuadMesh)] + list(ax.get_images())
    for m in maps:
        cb = getattr(m, "colorbar", None)
        if cb is None or cb.ax not in bars:
            raise PlotCheckError(f"panel '{name}': a {type(m).__name__} map without a colour bar (rule 5, colour bars)")
    return len(maps)


def _overlaps(boxes):
    """The first pair (i, j) of overlapping boxes [x0, y0, x1, y1], or None."""
    b = np.asarray(boxes, float).reshape(-1, 4)
    for i in range(len(b)):
        o = (b[i + 1:, 0] < b[i, 2]) & (b[i, 0] < b[i + 1:, 2]) & (b[i + 1:, 1] < b[i, 3]) & (b[i, 1] < b[i + 1:, 3])
        if o.any():
            return i, i + 1 + int(np.flatnonzero(o)[0])
    return None


def _gid_number(artist, prefix):
    gid = artist.get_gid() or ""
    if gid.startswith(prefix + " "):
        try:
            return int(gid[len(prefix) + 1:])
        except ValueError:
            return None
    return None


def check_numbered_markers(fig):
    """Rule 6 over the whole figure; returns the event numbers (empty: no numbered markers)."""
    if fig.get_constrained_layout():  # laid out when drawn; otherwise the transforms hold already
        fig.canvas.draw()
    boxes, numbers = [], []
    for ax in fig.axes:
        texts = {}
        for t in ax.texts:
            n = _gid_number(t, "event_number")
            if n is not None:
                texts.setdefault(n, []).append(ax.transData.transform(t.get_position()))
        for l in ax.get_lines():
            if l.get_gid() != "event_markers":
                continue
            r = 0.5 * l.get_markersize() * fig.dpi / 72
            for xy in ax.transData.transform(np.column_stack([l.get_xdata(), l.get_ydata()]).astype(float)):
                hit = [n for n, ps in texts.items() if any(np.hypot(*(p - xy)) < 0.5 for p in ps)]
                if len(hit) != 1:
                    raise PlotCheckError(f"an event marker at {xy.round(1)} (display) carries {len(hit)} numbers (rule 6, numbered markers)")
                numbers.append(hit[0])
                boxes.append([xy[0] - r, xy[1] - r, xy[0] + r, xy[1] + r])
    if not numbers:
        return []
    if len(set(numbers)) != len(numbers):
        raise PlotCheckError(f"event numbers repeat: {sorted(n for n in set(numbers) if numbers.count(n) > 1)} (rule 6, numbered markers)")
    pair = _overlaps(boxes)
    if pair is not None:
        raise PlotCheckError(f"event markers {numbers[pair[0]]} and {numbers[pair[1]]} overlap (rule 6, numbered markers)")
    rows = [n for ax in fig.axes for t in ax.texts for n in [_gid_number(t, "event_row")] if n is not None]
    if sorted(rows) != sorted(numbers):
        raise PlotCheckError(f"the events table lists {sorted(rows)[:8]}... ({len(rows)} rows) for the markers numbered {sorted(numbers)[:8]}... "
                             f"({len(numbers)}) (rule 6, numbered markers)")
    return sorted(numbers)


def check_point_labels(ax, name, every):
    """Rule 7: point labels stand beside points of the panel's lines, apart; with every, on every point."""
    labels = [t for t in ax.texts if t.get_gid() == "point_label"]
    pts = [(l, np.column_stack([l.get_xdata(), l.get_ydata()]).astype(float)) for l in ax.get_lines()
           if l.get_transform() == ax.transData and l.get_marker() not in (None, "None", "", " ")]
    def at(xy, p):  # the rows of p equal to the point xy
        return (np.abs(p - np.asarray(xy, float)) <= 1e-12 * np.abs(p)).all(axis=1)

    if every:
        for l, p in pts:
            if l.get_label().startswith("_"):
                continue
            for xy in p:
                if not any(at(t.xy, xy[None]).any() for t in labels if hasattr(t, "xy")):
                    raise PlotCheckError(f"panel '{name}': the point {tuple(xy)} of '{l.get_label()}' has no label (rule 7, point labels)")
    for t in labels:
        if not hasattr(t, "xy") or not any(at(t.xy, p).any() for _, p in pts):
            raise PlotCheckError(f"panel '{name}': the label '{t.get_text()}' stands beside no point of the panel's lines (rule 7, point labels)")
    if labels:
        r = ax.figure.canvas.get_renderer()
        boxes = [t.get_window_extent(r) for t in labels]
        pair = _overlaps([list(b.extents) for b in boxes])
        if pair is not None:
            raise PlotCheckError(f"panel '{name}': the labels '{labels[pair[0]].get_text()}' and '{labels[pair[1]].get_text()}' overlap (rule 7, point labels)")
        for l, p in pts:  # nor does a label cover a marker
            half = l.get_markersize() * ax.figure.dpi / 72 / 2
            for (px, py), xy in zip(ax.transData.transform(p), p):
                for t, b in zip(labels, boxes):
                    if b.x0 < px + half and px - half < b.x1 and b.y0 < py + half and py - half < b.y1:
                        raise PlotCheckError(f"panel '{name}': the label '{t.get_text()}' covers the marker at {tuple(xy)} of '{l.get_label()}' (rule 7, point labels)")
    return len(labels)


def check_grid(fig, panels, grid):
    """--grid RxC: the panels' positions form R rows and C columns; the figure is not a strip."""
    rows, cols = (int(x) for x in grid.lower().split("x"))
    ys = sorted({round(ax.get_position().y0, 3) for ax in panels})
    xs = sorted({round(ax.get_position().x0, 3) for ax in panels})
    w, h = fig.get_size_inches()
    if len(panels) != rows * cols or len(ys) != rows or len(xs) != cols:
        raise PlotCheckError(f"{len(panels)} panels in {len(ys)} rows and {len(xs)} columns, not {rows} x {cols} (--grid {grid})")
    if w > 2 * h:
        raise PlotCheckError(f"a {w:g} x {h:g} inch strip (--grid {grid}: at most twice as wide as high)")


def check_sites(panels, sites):
    """--sites: every panel with site histories draws exactly these sites."""
    drawn = 0
    for i, ax in enumerate(panels):
        got = [n for l in ax.get_lines() for n in [_gid_number(l, "site")] if n is not None and artist_has_data(l)]
        if got:
            drawn += 1
            if sorted(got) != sorted(sites):
                raise PlotCheckError(f"panel '{panel_name(ax, i)}' draws sites {sorted(got)}, not {sorted(sites)} (--sites)")
    if not drawn:
        raise PlotCheckError("no panel draws site histories (--sites)")
    return drawn


def check_figure(fig, script="figure", expect=None):
    """Checks every panel of a figure; returns one line per panel. expect:
    {"grid": "2x2", "sites": [..], "point_labels": True} (the options)."""
    expect = expect or {}
    panels = [ax for ax in fig.axes if ax.get_label() != "<colorbar>"]
    if not panels:
        raise PlotCheckError(f"{script}: a figure without panels")
    lines = []
    tag = script.split('/')[-1]
    try:
        for i, ax in enumerate(panels):
            name = panel_name(ax, i)
            if not ax.axison:  # a table or a note
                if not any(t.get_text().strip() for t in ax.texts):
                    raise PlotCheckError(f"panel '{name}' is turned off and holds no text (rule 1, data)")
                lines.append(f"{tag}: panel '{name[:50]}': text only ({len(ax.texts)} texts)")
                continue
            summary = check_panel(ax, name)
            maps = check_colourbars(ax, name)
            labels = check_point_labels(ax, name, expect.get("point_labels", False))
            lines.append(f"{tag}: panel '{name[:50]}': {summary}" + (f", {maps} map(s) with colour bars" if maps else "") +
                         (f", {labels} point labels apart" if labels else ""))
        numbers = check_numbered_markers(fig)
        if numbers:
            lines.append(f"{tag}: {len(numbers)} numbered event markers, none overlapping, each in the events table")
        if "grid" in expect:
            check_grid(fig, panels, expect["grid"])
            lines.append(f"{tag}: panels in a {expect['grid']} grid")
        if "sites" in expect:
            n = check_sites(panels, expect["sites"])
            lines.append(f"{tag}: {n} panel(s) draw exactly sites {expect['sites']}")
    except PlotCheckError as e:
        raise PlotCheckError(f"{script}: {e}") from None
    return lines


def run_and_check(script, args, expect=None, write=True):
    """Runs a plot script with its arguments as its user would (the figures
    caught at savefig and written, unless write is False) and checks every
    figure it saves (expect: check_figure); returns one line per panel,
    raises PlotCheckError naming the first failure."""
    caught = []
    save = matplotlib.figure.Figure.savefig

    def savefig(self, *a, **k):
        caught.append(self)
        return save(self, *a, **k) if write else None

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
        lines += check_figure(fig, script, expect)
    return lines


def check_help(scripts):
    """--help: each script run with -h as its user would (in this process)
    exits 0 and prints its usage; returns one line per script."""
    import contextlib
    import io
    lines = []
    for script in scripts:
        name = os.path.basename(script)
        out = io.StringIO()
        argv, path = sys.argv, list(sys.path)
        sys.argv = [script, "-h"]
        sys.path.insert(0, os.path.dirname(os.path.abspath(script)))
        code = "no exit"
        try:
            with contextlib.redirect_stdout(out):
                runpy.run_path(script, run_name="__main__")
        except SystemExit as e:
            code = e.code
        finally:
            sys.argv, sys.path[:] = argv, path
        if code not in (0, None):
            raise PlotCheckError(f"{name} -h: exit {code}, not 0 (--help)")
        if not out.getvalue().startswith(f"usage: {name}"):
            raise PlotCheckError(f"{name} -h printed no usage: {out.getvalue()[:200]!r} (--help)")
        lines.append(f"{name} -h: exit 0, usage and {len(out.getvalue().splitlines())} lines")
    return lines


def main():
    argv, expect = sys.argv[1:], {}
    if argv and argv[0] == "--help":
        try:
            for line in check_help(argv[1:]):
                print(line)
        except PlotCheckError as e:
            sys.exit(f"plot_check: FAILED: {e}")
        return
    while argv and argv[0].startswith("--"):
        opt = argv.pop(0)
        if opt == "--grid":
            expect["grid"] = argv.pop(0)
        elif opt == "--sites":
            expect["sites"] = [int(x) for x in argv.pop(0).split(",")]
        elif opt == "--point-labels":
            expect["point_labels"] = True
        else:
            sys.exit(f"plot_check: unknown option {opt}")
    try:
        for line in run_and_check(argv[0], argv[1:], expect):
            print(line)
    except PlotCheckError as e:
        sys.exit(f"plot_check: FAILED: {e}")


if __name__ == "__main__":
    main()
