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
TAIL = "\nfig.savefig(sys.argv[1])\n"

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
    "no_x_label": ("""
fig, ax = plt.subplots(2, 1, sharex=True)
ax[0].plot([1, 2], [1, 2]); ax[0].set(ylabel="corr")
ax[1].plot([1, 2], [1, 2]); ax[1].set(xlabel="periods", ylabel="MCR")
""", "has no x label (rule 3"),
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
}

sys.path.insert(0, here)
import matplotlib.pyplot as plt  # noqa: E402
import plot_check  # noqa: E402

failed = []
for name, (body, expect) in CASES.items():
    script = os.path.join(work, f"selftest_{name}.py")
    with open(script, "w") as f:
        f.write(HEAD + body + TAIL)
    png = os.path.join(work, f"selftest_{name}.png")
    try:
        plot_check.run_and_check(script, [png])
        rejected, msg = False, "passes"
    except plot_check.PlotCheckError as e:
        rejected, msg = True, str(e)
    plt.close("all")
    ok = (not rejected) if expect is None else (rejected and expect in msg)
    print(f"plot_check selftest {name}: {'ok' if ok else 'WRONG'}: {msg}" + ("" if ok or expect is None else f" (expected: {expect})"))
    if not ok:
        failed.append(name)
# the command line: a non-zero exit naming the rule for a bad figure, 0 for the good one
for name, code in (("empty_log_axis_mesh", 1), ("good", 0)):
    r = subprocess.run([sys.executable, os.path.join(here, "plot_check.py"), os.path.join(work, f"selftest_{name}.py"), os.path.join(work, f"cli_{name}.png")],
                       capture_output=True, text=True)
    ok = r.returncode == code and (code == 0 or "plot_check: FAILED" in r.stderr and "rule 2, limits" in r.stderr)
    print(f"plot_check selftest (command line) {name}: exit {r.returncode}: {'ok' if ok else 'WRONG: ' + r.stderr.strip()}")
    if not ok:
        failed.append("cli_" + name)
if failed:
    sys.exit(f"plot_check selftest FAILED: {', '.join(failed)}")
print(f"plot_check selftest OK: {len(CASES) - 1} bad figures rejected, the good one passes")
