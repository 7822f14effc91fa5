#!/usr/bin/python3
"""Negative tests of plot_check.py (run by tests/scenes/plots.sh): small figure
scripts, each breaking one rule, must be rejected naming the rule, and a figure
that keeps every rule must pass (in-process, plot_check.run_and_check); through
the command line, a bad figure exits non-zero and the good one 0.
usage: plot_check_selftest.py <work dir>"""
import os
import subprocess
import sys

here = os.path.dirname(os.path.abspath(__file__))
work = sys.argv[1] if len(sys.argv) > 1 else "."
os.makedirs(work, exist_ok=True)

HEAD = """import sys
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np
E = np.logspace(-3, 3, 10)
w = np.linspace(0.87, 2.6, 10)
"""
TAIL = "\nfig.savefig(sys.argv[1], dpi=40)\n"

CASES = {
    # name: (script body, expected message or None for a pass)
    "empty_panel": ("""
fig, ax = plt.subplots(1, 2)
ax[0].plot([1, 2], [1, 2])
ax[0].set(xlabel="x", ylabel="y")
ax[1].set(xlabel="x", ylabel="y", title="nothing here")
""", "holds no finite data (rule 1"),
    "all_nan_mesh": ("""
fig, ax = plt.subplots()
ax.pcolormesh(E, w, np.full((10, 10), np.nan), shading="nearest")
ax.set(xlabel="E*", ylabel="omega")
""", "holds no finite data (rule 1"),
    # the sweep figure's old 0-1 panel: linear 'nearest' cell edges of a log
    # grid go negative, the log axis autoscales to one decade above the last
    # edge (891 .. 11220) and shows one column of a 10 x 10 grid
    "empty_log_axis_mesh": ("""
fig, ax = plt.subplots()
ax.pcolormesh(E, w, np.random.default_rng(1).random((10, 10)), shading="nearest")
ax.set(xscale="log", xlabel="E*", ylabel="omega", title="0-1 test")
""", "outside the limits"),
    "line_outside_limits": ("""
fig, ax = plt.subplots()
ax.plot(np.arange(11.0), np.arange(11.0))
ax.set(xlim=(0, 5), xlabel="x", ylabel="y")
""", "outside the limits"),
    "scatter_outside_log_limits": ("""
fig, ax = plt.subplots()
ax.scatter([1e-2, 1e2], [1, 2])
ax.set(xscale="log", xlim=(1, 1e3), xlabel="x", ylabel="y")
""", "outside the limits"),
    "two_series_no_legend": ("""
fig, ax = plt.subplots()
ax.plot([1, 2], [1, 2], label="insulated")
ax.plot([1, 2], [2, 3], label="interface")
ax.set(xlabel="E", ylabel="omega")
""", "has no legend (rule 4"),
    "legend_names_undrawn_series": ("""
fig, ax = plt.subplots()
ax.plot([1, 2], [1, 2], label="insulated")
ax.plot([], [], "ro", label="unstable")
ax.set(xlabel="E", ylabel="omega")
ax.legend()
""", "names no drawn series"),
    "legend_misses_a_series": ("""
fig, ax = plt.subplots()
a, = ax.plot([1, 2], [1, 2], label="insulated")
ax.plot([1, 2], [2, 3], label="interface")
ax.set(xlabel="E", ylabel="omega")
ax.legend(handles=[a])
""", "missing from the legend"),
    "broken_axis_upper_alone": ("""
fig, ax = plt.subplots(2, 1)
ax[0].plot(E, 4 * w, "-")
ax[0].set(xscale="log", ylabel="omega (above)", gid="broken_axis_upper")
ax[1].plot(E, w, "-")
ax[1].set(xscale="log", xlabel="E", ylabel="omega")
""", "has no x label (rule 3"),
    "no_x_label": ("""
fig, ax = plt.subplots(2, 1, sharex=True)
ax[0].plot([1, 2], [1, 2]); ax[0].set(ylabel="corr")
ax[1].plot([1, 2], [1, 2]); ax[1].set(xlabel="periods", ylabel="MCR")
""", "has no x label (rule 3"),
    # rule 5: a map without its colour bar (the old space-time map of plot_simulate.py)
    "mesh_without_colourbar": ("""
fig, ax = plt.subplots()
ax.pcolormesh(np.logspace(-3.3, 3.3, 11), np.linspace(0.8, 2.7, 11), np.random.default_rng(1).random((10, 10)))
ax.set(xscale="log", xlabel="E*", ylabel="omega")
""", "without a colour bar (rule 5"),
    "image_without_colourbar": ("""
fig, ax = plt.subplots(1, 2)
ax[0].imshow(np.random.default_rng(1).random((20, 10)).T, aspect="auto", origin="lower", extent=[0, 100, 0.5, 10.5])
ax[0].set(xlabel="t", ylabel="site")
m = ax[1].imshow(np.random.default_rng(2).random((20, 10)).T, aspect="auto", origin="lower", extent=[0, 100, 0.5, 10.5])
fig.colorbar(m, ax=ax[1])
ax[1].set(xlabel="t", ylabel="site")
""", "without a colour bar (rule 5"),
    # rule 6: numbered event markers (the FEP's ~20 overlapping triangles)
    "event_markers_overlap": ("""
fig, ax = plt.subplots(1, 2)
ax[0].plot(E, w, "-")
x, y = [1.0, 1.05, 30.0], [1.5, 1.5, 2.0]
ax[0].plot(x, y, "o", ms=13, ls="none", gid="event_markers", label="Hamiltonian-Hopf onset")
for n, (a, b) in enumerate(zip(x, y), 1):
    ax[0].text(a, b, str(n), gid=f"event_number {n}")
ax[0].set(xscale="log", xlabel="E", ylabel="omega")
ax[1].set_axis_off()
for n in (1, 2, 3):
    ax[1].text(0, 1 - 0.1 * n, f"{n} HH+", gid=f"event_row {n}")
""", "overlap (rule 6"),
    "event_marker_without_number": ("""
fig, ax = plt.subplots()
ax.plot(E, w, "-")
ax.plot([1.0, 100.0], [1.5, 2.0], "o", ms=13, ls="none", gid="event_markers", label="branch point")
ax.text(1.0, 1.5, "1", gid="event_number 1")
ax.set(xscale="log", xlabel="E", ylabel="omega")
""", "carries 0 numbers (rule 6"),
    "event_missing_from_table": ("""
fig, ax = plt.subplots(1, 2)
ax[0].plot(E, w, "-")
ax[0].plot([1.0, 100.0], [1.5, 2.0], "o", ms=13, ls="none", gid="event_markers", label="branch point")
ax[0].text(1.0, 1.5, "1", gid="event_number 1")
ax[0].text(100.0, 2.0, "2", gid="event_number 2")
ax[0].set(xscale="log", xlabel="E", ylabel="omega")
ax[1].set_axis_off()
ax[1].text(0, 0.9, "1 BP", gid="event_row 1")
""", "the events table lists"),
    # rule 7: point labels (the work-precision points)
    "point_labels_overlap": ("""
fig, ax = plt.subplots()
ax.loglog([1e-6, 1.1e-6], [0.1, 0.1], "o-", label="rk 5dp")
ax.annotate("tol 1e-6", (1e-6, 0.1), xytext=(5, 3), textcoords="offset points", gid="point_label")
ax.annotate("tol 1e-8", (1.1e-6, 0.1), xytext=(5, 3), textcoords="offset points", gid="point_label")
ax.set(xlabel="error", ylabel="wall", xlim=(1e-9, 1e-3))
""", "overlap (rule 7"),
    "point_label_covers_marker": ("""
fig, ax = plt.subplots()
ax.loglog([1e-6, 1e-8], [0.1, 0.3], "o-", label="rk 5dp")
ax.annotate("tol 1e-6", (1e-6, 0.1), xytext=(0, 0), textcoords="offset points", gid="point_label")
ax.annotate("tol 1e-8", (1e-8, 0.3), xytext=(5, 3), textcoords="offset points", gid="point_label")
ax.set(xlabel="error", ylabel="wall", xlim=(1e-9, 1e-3))
""", "covers the marker at (1e-06, 0.1) of 'rk 5dp' (rule 7"),
    "point_label_off_the_points": ("""
fig, ax = plt.subplots()
ax.loglog([1e-6, 1e-8], [0.1, 0.3], "o-", label="rk 5dp")
ax.annotate("tol 1e-6", (1e-6, 0.1), xytext=(5, 3), textcoords="offset points", gid="point_label")
ax.annotate("tol 1e-8", (1e-7, 0.3), xytext=(5, 3), textcoords="offset points", gid="point_label")
ax.set(xlabel="error", ylabel="wall")
""", "stands beside no point of the panel's lines (rule 7"),
    "point_without_label": ("""
fig, ax = plt.subplots()
ax.loglog([1e-6, 1e-8], [0.1, 0.3], "o-", label="rk 5dp")
ax.annotate("tol 1e-6", (1e-6, 0.1), xytext=(5, 3), textcoords="offset points", gid="point_label")
ax.set(xlabel="error", ylabel="wall")
""", "has no label (rule 7", {"point_labels": True}),
    # --grid: the Floquet figure's old 1 x 4 strip
    "strip_not_grid": ("""
fig, ax = plt.subplots(1, 4, figsize=(20.8, 4.8))
for a in ax:
    a.plot([1, 2], [1, 2])
    a.set(xlabel="omega", ylabel="|mu|")
""", "not 2 x 2 (--grid", {"grid": "2x2"}),
    "wide_grid": ("""
fig, ax = plt.subplots(2, 2, figsize=(20, 4))
for a in ax.flat:
    a.plot([1, 2], [1, 2])
    a.set(xlabel="omega", ylabel="|mu|")
""", "strip (--grid", {"grid": "2x2"}),
    # --sites: the histories drawn are not the sites asked for
    "other_sites": ("""
fig, ax = plt.subplots()
for k, n in enumerate((50, 51)):
    ax.plot(np.arange(10.0), -2.4 * k + np.sin(np.arange(10.0)), label=f"site {n}", gid=f"site {n}")
ax.set(xlabel="t", ylabel="site")
ax.legend()
""", "draws sites [50, 51], not [26, 50, 51] (--sites", {"sites": [26, 50, 51]}),
    "good": ("""
fig, ax = plt.subplots(1, 2)
m = ax[0].pcolormesh(np.logspace(-3.3, 3.3, 11), np.linspace(0.8, 2.7, 11), np.random.default_rng(1).random((10, 10)))
fig.colorbar(m, ax=ax[0], label="MCR")
ax[0].plot(E, w, "w-", label="insulated")
ax[0].plot(E[:3], w[:3], "ro", label="unstable")
ax[0].axvline(12, color="k", label="E = 12")
ax[0].set(xscale="log", xlabel="E*", ylabel="omega", xlim=(10**-3.3, 10**3.3), ylim=(0.8, 2.7))
ax[0].legend()
ax[1].semilogy(np.arange(1, 11), E, "o")
ax[1].axhline(1, color="0.5")
ax[1].set(xlabel="site", ylabel="RMS")
""", None),
    # the new elements kept: maps with colour bars, numbered markers apart with their table, labelled
    # points apart, a 2 x 2 grid, an axis broken into two panels (the x label on the lower), the sites asked for
    "good_new_elements": ("""
fig, ax = plt.subplots(2, 2, figsize=(10, 8))
m = ax[0, 0].imshow(np.random.default_rng(1).random((20, 10)).T, aspect="auto", origin="lower", extent=[0, 100, 0.5, 10.5])
fig.colorbar(m, ax=ax[0, 0], label="u")
ax[0, 0].set(xlabel="t", ylabel="site")
ax[0, 1].plot(E, w, "-")
x, y = [1.0, 30.0], [1.5, 2.0]
ax[0, 1].plot(x, y, "o", ms=13, ls="none", gid="event_markers", label="_events")
for n, (a, b) in enumerate(zip(x, y), 1):
    ax[0, 1].text(a, b, str(n), gid=f"event_number {n}")
    ax[0, 1].text(1e-3, 2.5 - 0.1 * n, f"{n} BP", gid=f"event_row {n}")
ax[0, 1].set(xscale="log", xlabel="E", ylabel="omega")
ax[1, 0].loglog([1e-6, 1e-8], [0.1, 0.3], "o-", label="rk 5dp")
for e, t, lab in ((1e-6, 0.1, "tol 1e-6"), (1e-8, 0.3, "tol 1e-8")):
    ax[1, 0].annotate(lab, (e, t), xytext=(5, 3), textcoords="offset points", gid="point_label")
ax[1, 0].set(xlabel="error", ylabel="wall")
for k, n in enumerate((26, 50, 51)):
    ax[1, 1].plot(np.arange(10.0), -2.4 * k + np.sin(np.arange(10.0)), label=f"site {n}", gid=f"site {n}")
ax[1, 1].set(xlabel="t", ylabel="site")
ax[1, 1].legend()
""", None, {"grid": "2x2", "sites": [26, 50, 51], "point_labels": True}),
    # an axis broken into two panels: the upper one declared (gid), sharing the lower one's x axis and label
    "good_broken_axis": ("""
fig, ax = plt.subplots(2, 1, sharex=True)
ax[0].plot(E, 4 * w, "-")
ax[0].set(xscale="log", ylabel="omega (above)", gid="broken_axis_upper")
ax[1].plot(E, w, "-")
ax[1].set(xscale="log", xlabel="E", ylabel="omega")
""", None),
}

sys.path.insert(0, here)
import matplotlib.pyplot as plt  # noqa: E402
import plot_check  # noqa: E402

failed = []
for name, case in CASES.items():
    body, expect, options = case if len(case) == 3 else case + ({},)
    script = os.path.join(work, f"selftest_{name}.py")
    with open(script, "w") as f:
        f.write(HEAD + body + TAIL)
    png = os.path.join(work, f"selftest_{name}.png")
    try:
        plot_check.run_and_check(script, [png], options, write=False)  # checked, not written (the command-line cases below write)
        rejected, msg = False, "passes"
    except plot_check.PlotCheckError as e:
        rejected, msg = True, str(e)
    plt.close("all")
    ok = (not rejected) if expect is None else (rejected and expect in msg)
    print(f"plot_check selftest {name}: {'ok' if ok else 'WRONG'}: {msg}" + ("" if ok or expect is None else f" (expected: {expect})"))
    if not ok:
        failed.append(name)
# the command line: a non-zero exit naming the rule for a bad figure, 0 for the good one; the options
for name, code, opts, rule in (("empty_log_axis_mesh", 1, [], "rule 2, limits"), ("strip_not_grid", 1, ["--grid", "2x2"], "--grid"),
                               ("good_new_elements", 0, ["--grid", "2x2", "--sites", "26,50,51", "--point-labels"], "")):
    r = subprocess.run([sys.executable, os.path.join(here, "plot_check.py")] + opts + [os.path.join(work, f"selftest_{name}.py"), os.path.join(work, f"cli_{name}.png")],
                       capture_output=True, text=True)
    ok = r.returncode == code and (code == 0 or "plot_check: FAILED" in r.stderr and rule in r.stderr)
    print(f"plot_check selftest (command line) {name}: exit {r.returncode}: {'ok' if ok else 'WRONG: ' + r.stderr.strip()}")
    if not ok:
        failed.append("cli_" + name)
if failed:
    sys.exit(f"plot_check selftest FAILED: {', '.join(failed)}")
bad = sum(1 for c in CASES.values() if c[1] is not None)
print(f"plot_check selftest OK: {bad} bad figures rejected, {len(CASES) - bad} good ones pass")
