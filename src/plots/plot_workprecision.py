#!/usr/bin/python3
"""Work-precision diagram of -study workprecision (/workprecision): wall time
against the error of each observable, log-log, one curve per method (its
configurations in order of accuracy, each point labelled by its step or
tolerance: dt 0.2, tol 1e-8, 128 steps/period), the convention of
DifferentialEquations.jl's WorkPrecisionSet; the predictability floor (the
twins' spread) as a shaded band: errors inside it mean nothing.
usage: plot_workprecision.py workprecision.h5 [out.png]
figure(group) builds the figure without saving it (the scene test reads it)."""
import re
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
from matplotlib.transforms import Bbox
import numpy as np
import nltopo_plot

# the panels of each scene (/workprecision attribute scene), in order
PANELS = {"simulate": (("mcr", "MCR"), ("state", "final state z(t_final)"), ("t_off", "cut-off time t_off"), ("energy", "energy after the cut-off")),
          "shooting": (("omega", "orbit frequency omega"), ("closure", "orbit closure |z(T) - z0| / |z0|"), ("max_modulus", "largest Floquet modulus"),
                       ("det", "|det M - 1| (the method's own)"))}


def load(path):
    """/workprecision of a -study workprecision file."""
    return nltopo_plot.open_run(path).workprecision


def panels(g):
    return PANELS[g.get("scene", "simulate")]


def text(x):
    return x.decode() if isinstance(x, bytes) else str(x)


def accuracy_labels(g):
    """The label of each configuration: /workprecision/accuracy, or from the
    options of /workprecision/config (dt, tolerance or steps per period)."""
    if "accuracy" in g:
        return [text(a) for a in g.accuracy]
    out = []
    for c in g.config:
        c = text(c)
        m = re.search(r"-(?:sim|nnm)_ts_rtol (\S+)", c) or re.search(r"-(?:sim|nnm)_ts_atol (\S+)", c)
        if m:
            out.append("tol " + m.group(1))
            continue
        m = re.search(r"-nnm_steps_per_period (\S+)", c)
        if m:
            out.append(m.group(1) + " steps/period")
            continue
        m = re.search(r"-sim_ts_dt (\S+)", c)
        out.append("dt " + m.group(1) if m else c)
    return out


def label_points(ax, xs, ys, labels, colour):
    """Each point's label beside it: right of the point, or left, below or
    above where that one would overlap a label already placed, the legend or
    a marker of any curve (display boxes)."""
    fig = ax.figure
    r = fig.canvas.get_renderer()
    placed = [t.get_window_extent(r) for t in ax.texts if t.get_gid() == "point_label"]
    if ax.get_legend() is not None:
        placed.append(ax.get_legend().get_window_extent(r))
    for line in ax.lines:  # every marker, as a box of its size
        half = line.get_markersize() * fig.dpi / 72 / 2
        for px, py in ax.transData.transform(np.column_stack([line.get_xdata(), line.get_ydata()])):
            placed.append(Bbox.from_extents(px - half, py - half, px + half, py + half))
    for x, y, lab in zip(xs, ys, labels):
        for dx, dy, ha in ((5, 3, "left"), (-5, 3, "right"), (5, -9, "left"), (-5, -9, "right"), (5, 10, "left"), (-5, 10, "right")):
            t = ax.annotate(lab, (x, y), xytext=(dx, dy), textcoords="offset points", fontsize=6, ha=ha, color=colour, gid="point_label")
            box = t.get_window_extent(r)
            if not any(box.overlaps(b) for b in placed):
                break
            t.remove()
        else:
            t = ax.annotate(lab, (x, y), xytext=(5, 3), textcoords="offset points", fontsize=6, ha="left", color=colour, gid="point_label")
            box = t.get_window_extent(r)
        placed.append(box)


def figure(g):
    method = [text(m) for m in g.method]
    wall = g.wall_seconds
    labels = accuracy_labels(g)
    fig, axes = plt.subplots(2, 2, figsize=(12, 8.6))
    curves = []
    for ax, (obs, name) in zip(axes.flat, panels(g)):
        err = g["error_" + obs]
        floor = float(g["spread_" + obs])
        shown = np.maximum(err, 1e-17)  # an exact 0 (a run equal to the reference) at the bottom of the axis
        lo = min(shown.min(), floor if floor > 0 else shown.min()) / 3
        hi = max(shown.max(), floor) * 30  # room on the right for the labels
        for k, m in enumerate(dict.fromkeys(method)):
            idx = [i for i, x in enumerate(method) if x == m]
            idx.sort(key=lambda i: -err[i])  # from the least to the most accurate
            line, = ax.loglog(shown[idx], wall[idx], "o-", color=f"C{k}", label=m)
            curves.append((ax, shown[idx], wall[idx], [labels[i] for i in idx], line.get_color()))
        ax.set_xlim(lo, hi)
        ax.set_ylim(wall.min() / 1.5, wall.max() * 1.5)
        if floor > 0:
            ax.axvspan(lo, floor, color="0.85", zorder=0, label="predictability floor")
        ax.set(xlabel=name if obs == "det" else f"relative error of the {name}", ylabel="wall time (s, median)")
        ax.grid(True, which="major", alpha=0.3)
        ax.legend(fontsize=6, loc="upper right")  # every panel names its curves (tests/scenes/plot_check.py, rule 4)
    ref = g.reference
    conv = "converged" if g.reference_converged else "NOT converged"
    if g.get("scene", "simulate") == "shooting":
        fig.suptitle(f"work-precision of the insulated NNM at E = {g.nnm_energy:g} (Newton and monodromy); points labelled by their setting\n"
                     f"reference: {ref} ({conv})", fontsize=8)
    else:
        fig.suptitle(f"work-precision at E* = {g.energy_star:g}, omega_ext = {g.omega_ext:.4f}; points labelled by their step or tolerance\n"
                     f"reference: {ref} ({conv}); finite-time Lyapunov {g.lyapunov:.3g} /time", fontsize=8)
    fig.tight_layout(rect=(0, 0, 1, 0.95))
    for ax, x, y, labs, colour in curves:  # after the layout: the labels kept apart in display coordinates
        label_points(ax, x, y, labs, colour)
    return fig


if __name__ == "__main__":
    nltopo_plot.main_one_file(__doc__, "workprecision", "workprecision", load, figure, dpi=120)
