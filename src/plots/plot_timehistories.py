#!/usr/bin/python3
"""Time histories of forced runs (-study simulate with -sim_store_u 1, the
paper's Fig. 7): one row per run (sorted by E*), each forced at the insulated
NNM's frequency at its E*, over the first -window time units after the
cut-off (the last ones if the run never reached E*):
(left)   the space-time map of u(t) of every site, with its colour bar;
(middle) u(t) of the chosen sites (--sites, 1-based; default: the interface
         cell's sites m-1, m, m+1 and a bulk site halfway to the left end),
         each scaled to its largest |u| (written beside it) and offset,
         even sites orange, odd sites purple, as in the paper;
(right)  the RMS amplitude of every site after the cut-off (log scale), the
         chosen sites ringed, with E*, omega_ext and the MCR.
usage: plot_timehistories.py run1.h5 [run2.h5 ...] [out.png] [--sites 50,51,52] [--window 250]"""
import sys
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np
import nltopo_plot


def load(paths):
    """(path, /simulate, -lattice_layout) of each run, sorted by E*."""
    runs = []
    for p in paths:
        run = nltopo_plot.open_run(p)
        S = run.simulate
        if "u" not in S:
            sys.exit(f"plot_timehistories.py: {p} has no /simulate/u (run with -sim_store_u 1)")
        runs.append((p, S, run.options.get("lattice_layout", "interface")))
    return sorted(runs, key=lambda r: float(r[1].energy_star))


def default_sites(N, layout):
    """The sites drawn without --sites (1-based): the interface cell (m = N/2,
    with m-1 and m+1) or the edge cell of an edge layout, and a bulk site."""
    if layout == "left":
        near = [1, 2, 3]
    elif layout == "right":
        near = [N - 2, N - 1, N]
    else:
        m = N // 2
        near = [m - 1, m, m + 1]
    bulk = 2 * max(1, round(N / 8)) if layout != "left" else N - 2 * max(1, round(N / 8))
    return sorted(set(near + [bulk]))


def parse_sites(text):
    try:
        sites = [int(x) for x in text.split(",") if x.strip()]
    except ValueError:
        sys.exit(f"plot_timehistories.py: --sites takes 1-based site numbers separated by commas, got '{text}'")
    if not sites:
        sys.exit("plot_timehistories.py: --sites is empty")
    return sites


def histories(ax, t, u, sites, sel):
    """u(t) of each site over sel, scaled to its largest |u| and offset by 2.4 per site."""
    yt, ytl = [], []
    for k, n in enumerate(sites):
        x = u[sel, n - 1]
        big = float(np.abs(x).max()) or 1.0
        y0 = -2.4 * k
        ax.plot(t[sel], y0 + x / big, "-", lw=0.6, color=nltopo_plot.site_colour(n), label=f"_site {n}", gid=f"site {n}")  # named by the y ticks
        yt.append(y0)
        ytl.append(f"{n}\n|u| ≤ {big:.2g}")
    ax.set_yticks(yt)
    ax.set_yticklabels(ytl, fontsize=7)
    for lab, n in zip(ax.get_yticklabels(), sites):
        lab.set_color(nltopo_plot.site_colour(n))
    ax.set_ylim(-2.4 * (len(sites) - 1) - 1.3, 1.3)


def figure(runs, sites=None, window=250.0):
    fig, ax = plt.subplots(len(runs), 3, figsize=(17, 2.9 * len(runs) + 0.4), gridspec_kw={"width_ratios": [2.1, 2, 1.1]}, squeeze=False)
    for r, (path, S, layout) in enumerate(runs):
        t, u = S.t, S.u
        N = u.shape[1]
        chosen = sites or default_sites(N, layout)
        bad = [n for n in chosen if not 1 <= n <= N]
        if bad:
            sys.exit(f"plot_timehistories.py: --sites {bad} outside 1..{N} (sites are 1-based) in {path}")
        t_off = float(S.t_off)
        t0 = t_off if t_off >= 0 else max(t[0], t[-1] - window)
        sel = (t >= t0) & (t <= t0 + window)
        after = f" (from the cut-off at {t_off:.1f})" if t_off >= 0 else " (E* never reached: the last samples)"
        lim = nltopo_plot.space_time(fig, ax[r, 0], t, u, sel)
        ax[r, 0].set(xlabel="t" + after, ylabel="site")
        ax[r, 0].set_title(rf"E* = {S.energy_star:g}, $\omega_{{ext}}$ = {S.omega_ext:.4f}: u(t) of every site (colours clipped at $\pm${lim:.2g})", fontsize=9)
        histories(ax[r, 1], t, u, chosen, sel)
        ax[r, 1].set(xlabel="t" + after, ylabel="site: u / max|u| (offset)")
        ax[r, 1].set_title("u(t) of sites " + ", ".join(str(n) for n in chosen) + " (even orange, odd purple)", fontsize=9)
        nltopo_plot.rms_by_parity(ax[r, 2], S.rms, ms=2.5)
        ax[r, 2].plot(chosen, S.rms[np.asarray(chosen) - 1], "o", ms=7, mfc="none", mec="k", mew=0.8, label="drawn sites")
        ax[r, 2].set(xlabel="site", ylabel="RMS u after the cut-off")
        ax[r, 2].set_title(f"RMS per site: MCR = {S.mcr:.3f}" + ("" if S.energy_reached else " (E* not reached)"), fontsize=9)
        ax[r, 2].legend(fontsize=7, loc="upper right")
    fig.tight_layout()
    return fig


def main(argv=None):
    p = nltopo_plot.parser(__doc__)
    p.add_argument("files", nargs="+", help="-study simulate outputs (.h5), then optionally the PNG (.png; default <first>_histories.png)")
    p.add_argument("--sites", help="1-based sites to draw, e.g. 50,51,52,26 (default: the interface cell and a bulk site)")
    p.add_argument("--window", "-window", type=float, default=250.0, help="time drawn after the cut-off (default 250)")
    a = p.parse_args(argv)
    h5 = [f for f in a.files if f.endswith(".h5")]
    png = [f for f in a.files if f.endswith(".png")]
    if not h5:
        p.error("no .h5 file given")
    out = png[0] if png else h5[0].replace(".h5", "") + "_histories.png"
    figure(load(h5), parse_sites(a.sites) if a.sites else None, a.window).savefig(out, dpi=110)
    print("wrote", out)


if __name__ == "__main__":
    main()
