#!/usr/bin/python3
"""Time series of the half-lattice phase experiment (the paper's Fig. 5a-b):
-study simulate runs that repeat runs of a -study zak file (nltopo_plot.
zak_reruns: the same run, the same samples after the cut-off), (a) forced
with the mu = 0 edge mode of the optical band at its frequency, (b) with the
mu = pi edge mode. Per run one row, offset by E*: the two sites of one unit
cell (2j-1, 2j) over the last periods of the zak study's last window, scaled
to their largest |u|. The cell is the window's median cell: its phase
phase(even) - phase(odd) at omega_ext over the window is the median over the
cells, the window's marker in panels (c, d) (plot_zak.py). In phase at mu = 0,
out of phase at mu = pi while the phase is quantised; neither at high E*.
Each row names E*, the cell, its phase next to the zak study's value for that
window, how many cells lie within pi/4 of the linear value (0 or pi), the zak
median over every window, and the MCR.
usage: plot_zak_runs.py zak.h5 run1.h5 [run2.h5 ...] out.png [-periods n]"""
import sys
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np
import nltopo_plot


def load(zak_path, run_paths):
    """(/zak, {"0": [/simulate], "pi": [/simulate]}: the runs by the band edge they are forced at)."""
    z = nltopo_plot.open_run(zak_path).zak
    edges = {"0": float(z.omega0), "pi": float(z.omegapi)}
    runs = {"0": [], "pi": []}
    for name in run_paths:
        S = nltopo_plot.open_run(name).simulate
        if "u" not in S:
            sys.exit(f"plot_zak_runs.py: {name} has no /simulate/u (run with -sim_store_u 1)")
        w = float(S.omega_ext)
        edge = min(edges, key=lambda e: abs(edges[e] - w))
        if not np.isclose(edges[edge], w, rtol=1e-12):
            sys.exit(f"plot_zak_runs.py: {name} is forced at {w}, at neither edge of {zak_path} ({edges})")
        runs[edge].append(S)
    return z, runs


def main(argv=None):
    p = nltopo_plot.parser(__doc__)
    p.add_argument("files", nargs="+", help="zak.h5, the -study simulate runs (.h5), then optionally the PNG (default <zak>_runs.png)")
    p.add_argument("-periods", "--periods", type=float, default=6.0, help="periods drawn before the end of the last phase window (default 6)")
    a = p.parse_args(argv)
    files = [x for x in a.files if x.endswith(".h5")]
    if len(files) < 2:
        p.error("a zak file and at least one simulate run are needed")
    out = ([x for x in a.files if x.endswith(".png")] or [files[0].replace(".h5", "") + "_runs.png"])[0]
    z, runs = load(files[0], files[1:])
    figure(z, runs, a.periods).savefig(out, dpi=110)
    print("wrote", out)


def figure(z, runs, periods=6.0):
    Ez = z.energy
    spp = int(z.samples_per_period)
    edges = {"0": float(z.omega0), "pi": float(z.omegapi)}
    fig, ax = plt.subplots(1, 2, figsize=(13, 1.6 + 1.5 * max(len(r) for r in runs.values())), squeeze=False)
    for a, (edge, letter, mu) in zip(ax[0], (("0", "a", "0"), ("pi", "b", r"\pi"))):
        rs = sorted(runs[edge], key=lambda S: float(S.energy_star))
        yt, ytl = [], []
        for r, S in enumerate(rs):
            t, u, w = S.t, S.u, float(S.omega_ext)
            E = float(S.energy_star)
            k = int(np.argmin(np.abs(np.log(Ez / E))))
            zwin = z[f"phi{edge}_window_median"][k]
            t_off = float(S.t_off)
            win = nltopo_plot.zak_windows(t, t_off if t_off >= 0 else t[0], spp, len(zwin))[-1]
            phis = nltopo_plot.dimer_phases(t[win], u[win], w)
            j = int(np.argsort(phis)[len(phis) // 2]) + 1  # the median cell (an odd count of cells: a cell's own value)
            near = int((np.abs(phis - (0 if edge == "0" else np.pi)) <= np.pi / 4).sum())
            show = win[t[win] >= t[win[-1]] - periods * 2 * np.pi / w]
            odd, even = u[show, 2 * j - 2], u[show, 2 * j - 1]
            scale = max(np.abs(odd).max(), np.abs(even).max()) or 1.0
            y0 = -2.6 * r
            first = r == 0
            x = (t[show] - t[win[-1]]) * w / (2 * np.pi)  # periods before the window's end
            a.plot(x, y0 + odd / scale, "-", color=nltopo_plot.ODD, lw=1.2, label="odd site 2j-1 of the cell" if first else "_")
            a.plot(x, y0 + even / scale, "--", color=nltopo_plot.EVEN, lw=1.2, label="even site 2j" if first else "_")
            reached = "" if S.energy_reached else " (E* not reached)"
            a.text(-periods, y0 + 1.12, rf"E* = {E:.3g}{reached}: cell {j}, $\phi$ = {phis[j - 1]:.2f} (zak {zwin[-1]:.2f}); {near}/{len(phis)} cells within $\pi/4$ of ${mu}$;"
                   rf" all windows: {float(z[f'phi{edge}_median'][k]):.2f}", fontsize=7, va="bottom")
            yt.append(y0)
            ytl.append(f"{E:.3g}")
        a.set_yticks(yt)
        a.set_yticklabels(ytl)
        a.set(xlabel=r"t in periods $2\pi/\omega_{ext}$ before the end of the last phase window (free motion)", ylabel="E* (rows); u / max |u| of the cell")
        a.set_title(rf"({letter}) $\mu = {mu}$: optical band {'bottom' if edge == '0' else 'top'} mode, $\omega_{{ext}}$ = {edges[edge]:.4f}", fontsize=10)
        if rs:
            a.set_ylim(-2.6 * (len(rs) - 1) - 1.3, 2.4)  # room above the first row for the legend
            a.legend(fontsize=7, loc="upper right", ncol=2, framealpha=0.8)
    fig.tight_layout()
    return fig


if __name__ == "__main__":
    main()
