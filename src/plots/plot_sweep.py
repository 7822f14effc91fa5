#!/usr/bin/python3
"""Paper-style forced-response maps of -study sweep (the paper's Fig. 6, and
Fig. 8 for the exponential forcing), over (E*, omega_ext) with the linear bands
dotted and E = 12 dashed:
(a) the nonlinear / linear energy ratio (log colours) with the 0-1 test's
    kcorr = 0.7 contour (chaos, white) when the sweep computed it;
(b) the MCR, points that never reached E* crossed out, points an
    accuracy-aware sweep (-sweep_mcr_tol) found unpredictable dotted (their MCR
    is a twins' mean), with -sweep_lyapunov the chaotic points whose MCR is
    predictable (regime 1) as white crosses, and, when a continuation file is given, its NNM branches
    (the frequency-energy plot) overlaid within the map, Floquet-unstable
    orbits in red;
(c) the 0-1 test's kcorr (only when the sweep computed it).
-letters gives the panels' letters in order ("_": none), e.g. "_c" for the
paper's Fig. 8, whose only map, (c), is the MCR (default "abc").
A refinement level (-sweep_refine_from: /sweep/refined) is drawn from its
scattered samples instead, triangulated in (log E*, omega): (a) the MCR
(linear on each triangle) with the samples marked by their level and the
unpredictable ones dotted, (b) the energy ratio.
usage: plot_sweep.py sweep.h5 [fep.h5] [out.png] [-letters abc]"""
import sys
import matplotlib
matplotlib.use("Agg")
import matplotlib.colors
import matplotlib.patheffects
import matplotlib.pyplot as plt
import numpy as np
import nltopo_plot


def load(sweep_path, fep_path=None):
    """(the sweep run, its /sweep, the continuation's branches or None)."""
    run = nltopo_plot.open_run(sweep_path)
    if run.sweep.shard is not None:  # a shard holds some points only: the map is the merge of all
        sys.exit("plot_sweep.py: %s is shard %d/%d of a sweep (-sweep_shard): plot the merge of its shards (-study merge)"
                 % ((sweep_path,) + run.sweep.shard))
    return run, run.sweep, (nltopo_plot.open_run(fep_path).branches if fep_path else None)


def main(argv=None):
    p = nltopo_plot.parser(__doc__)
    p.add_argument("files", nargs="+", help="sweep.h5, then optionally a continuation output (fep.h5) and the PNG (default <sweep>_map.png)")
    p.add_argument("-letters", "--letters", default="abc", help='the panels\' letters in order, "_" for none (default abc)')
    a = p.parse_args(argv)
    h5 = [x for x in a.files if x.endswith(".h5")]
    outs = [x for x in a.files if not x.endswith(".h5")]
    if not h5:
        p.error("no .h5 file given")
    out = outs[0] if outs else h5[0].replace(".h5", "") + "_map.png"
    run, s, branches = load(h5[0], h5[1] if len(h5) > 1 else None)
    fig = figure(run, s, branches, a.letters) if s.refined is None else refined_figure(run, s, a.letters)
    fig.savefig(out, dpi=120)
    print("wrote", out)


def figure(run, s, branches=None, letters="abc"):
    letters = (letters + "___")[:3]
    tag = ["" if c == "_" else f"({c}) " for c in letters]
    w, E = s.omega, s.energy
    done = s.done.astype(bool)
    mcr = np.where(done, s.mcr, np.nan)
    kc = np.where(done, s.kcorr, np.nan)
    ratio = np.where(done, s.nl_ratio, np.nan)
    ratio = np.where(ratio > 0, ratio, np.nan)
    has_kc = bool(s.get("kcorr_computed", 0)) and np.isfinite(kc).any()
    Elog = len(E) < 2 or E.min() > 0 and E.max() / E.min() > 20  # the paper's E* axis is logarithmic
    bands = nltopo_plot.bands(s)
    profile = run.options.get("force_profile", "site")
    npan = 3 if has_kc else 2
    fig, ax = plt.subplots(1, npan, figsize=(6.6 * npan, 5.4))


    def decorate(a, e12_label="_E = 12"):
        for lo, hi in bands:
            a.axhline(lo, color="0.6", lw=0.6, ls=":")
            a.axhline(hi, color="0.6", lw=0.6, ls=":")
        if min(a.get_xlim()) < 12 < max(a.get_xlim()):
            a.axvline(12, color="k", ls="--", lw=0.9, label=e12_label)
        a.set(xlabel="E* (energy at the cut-off)", ylabel=r"$\omega_{ext}$ (rad/time)")


    # (a) the nonlinear / linear energy ratio, and where the response is chaotic
    if np.isfinite(ratio).any():
        norm = matplotlib.colors.LogNorm(vmin=np.nanmin(ratio), vmax=max(np.nanmax(ratio), np.nanmin(ratio) * 10))
        pr = nltopo_plot.grid_map(ax[0], E, w, ratio.T, xlog=Elog, cmap="cividis", norm=norm)
        fig.colorbar(pr, ax=ax[0], label="nonlinear / linear potential energy")
    kc_line = ""
    if has_kc and np.isfinite(kc).sum() > 3 and len(E) > 1 and len(w) > 1 and np.nanmax(kc) > 0.7 > np.nanmin(kc):
        ax[0].contour(E, w, kc.T, levels=[0.7], colors="w", linewidths=1.5)
        kc_line = "; white: kcorr = 0.7"
    decorate(ax[0])
    ax[0].set_title(f"{tag[0]}energy ratio{kc_line}", fontsize=10)

    # (b) the MCR with the FEP
    pc = nltopo_plot.grid_map(ax[1], E, w, mcr.T, xlog=Elog, cmap="viridis", vmin=0, vmax=np.nanmax(mcr))
    fig.colorbar(pc, ax=ax[1], label="MCR")
    xlim, ylim = ax[1].get_xlim(), ax[1].get_ylim()
    ee, ww = np.meshgrid(E, w, indexing="ij")
    missed = done & (s.reached == 0)
    if missed.any():
        ax[1].plot(ee[missed], ww[missed], "rx", ms=5, label="E* not reached")
    unpredictable = done & (s.predictable == 0) if "predictable" in s else np.zeros_like(done)
    if unpredictable.any():
        ax[1].plot(ee[unpredictable], ww[unpredictable], ".", color="0.85", ms=2.5, label="unpredictable (twins' mean)")
    chaotic = done & (s.regime == 1) if bool(s.get("lyapunov_computed", 0)) else np.zeros_like(done)
    if chaotic.any():  # -sweep_lyapunov: chaotic, the MCR an ergodic average
        ax[1].plot(ee[chaotic], ww[chaotic], "+", color="w", ms=4, mew=0.8, label="chaotic, MCR predictable (Lyapunov)")
    if branches is not None:  # the FEP, as plot_fep.py draws it: branch colours, unstable stretches by class
        for k, (name, g) in enumerate(branches.items()):
            m = int(g.get("period_multiple", 1))
            x, y = nltopo_plot.clip_to(g.energy, m * g.omega, xlim, ylim)
            if not np.isfinite(x).any():
                continue
            ax[1].plot(x, y, "-", lw=1.5, color=nltopo_plot.branch_colour(k), label=name,
                       path_effects=[matplotlib.patheffects.withStroke(linewidth=3, foreground="w")])  # apart from the map's colours
            cls = nltopo_plot.stability_class(g)
            for c, (label, col, lw) in nltopo_plot.STRETCH.items():
                if (cls == c).any():
                    sx, sy, at = nltopo_plot.stretches(g.energy, m * g.omega, cls == c)
                    sx, sy = nltopo_plot.clip_to(sx, sy, xlim, ylim)
                    if not np.isfinite(sx).any():
                        continue
                    seen = {l.get_label() for l in ax[1].get_lines()}
                    thin = lw < 3
                    ax[1].plot(sx, sy, "-", color=col, lw=lw, solid_capstyle="butt", marker="o" if thin else None, ms=5, mfc="none", mec=col,
                               markevery=[i for i in at if np.isfinite(sx[i])] if thin else None, label=label if label not in seen else "_" + label)
    decorate(ax[1], "E = 12 (paper)")
    ax[1].set_title(f"{tag[1]}MCR of the forced response ({profile} forcing)" + ("; NNM branches" if branches is not None else ""), fontsize=10)
    h, l = ax[1].get_legend_handles_labels()  # the classes' keys last
    order = sorted(range(len(l)), key=lambda i: "unstable" in l[i] or l[i].startswith("E = 12"))
    ax[1].legend([h[i] for i in order], [l[i] for i in order], fontsize=7, loc="upper left", framealpha=0.6)

    # (c) the 0-1 test
    if has_kc:
        pk = nltopo_plot.grid_map(ax[2], E, w, kc.T, xlog=Elog, cmap="magma", vmin=0, vmax=1)
        fig.colorbar(pk, ax=ax[2], label="kcorr (0-1 test, max over sites)")
        decorate(ax[2])
        ax[2].set_title(f"{tag[2]}0-1 test for chaos (1: chaotic)", fontsize=10)
    fig.tight_layout()
    return fig


LEVEL_MARKERS = "os^vD<>p*h"
LEVEL_COLOURS = ["w", "r", "orange", "m", "c", "k"]


def refined_figure(run, s, letters="ab"):
    """A refinement level's samples: the MCR and the energy ratio on the triangulation in (log E*, omega)."""
    import matplotlib.tri as mtri
    letters = (letters + "__")[:2]
    tag = ["" if c == "_" else f"({c}) " for c in letters]
    r = s.refined
    E, w, level = np.asarray(r["energy"]), np.asarray(r["omega"]), np.asarray(r["level"])
    ok = np.asarray(r["done"]).astype(bool) & np.isfinite(np.asarray(r["mcr"]))
    E, w, level = E[ok], w[ok], level[ok]
    mcr, ratio = np.asarray(r["mcr"])[ok], np.asarray(r["nl_ratio"])[ok]
    unpredictable = np.asarray(r["predictable"])[ok] == 0
    x = np.log10(E)  # the triangles' corners in (log10 E*, omega), where the map is linear on each
    tri = mtri.Triangulation(x, w)
    bands = nltopo_plot.bands(s)
    fig, ax = plt.subplots(1, 2, figsize=(13.2, 5.4))

    def decorate(a):
        for lo, hi in bands:
            if w.min() <= lo <= w.max():
                a.axhline(lo, color="0.6", lw=0.6, ls=":")
            if w.min() <= hi <= w.max():
                a.axhline(hi, color="0.6", lw=0.6, ls=":")
        a.set(xlim=(x.min(), x.max()), ylim=(w.min(), w.max()), xlabel="log10 E* (energy at the cut-off)", ylabel=r"$\omega_{ext}$ (rad/time)")

    pc = ax[0].tripcolor(tri, mcr, shading="gouraud", cmap="viridis", vmin=0, vmax=np.nanmax(mcr))
    fig.colorbar(pc, ax=ax[0], label="MCR (linear on the triangles)")
    for k in range(int(level.max()) + 1):
        at = level == k
        if at.any():
            ax[0].plot(x[at], w[at], LEVEL_MARKERS[k % len(LEVEL_MARKERS)], ms=max(1.5, 4 - 0.6 * k), mfc="none", mec=LEVEL_COLOURS[k % len(LEVEL_COLOURS)], mew=0.6,
                       label=f"level {k} ({at.sum()} points)")
    if unpredictable.any():
        ax[0].plot(x[unpredictable], w[unpredictable], ".", color="0.85", ms=2.5, label="unpredictable (twins' mean)")
    decorate(ax[0])
    ax[0].legend(fontsize=7, loc="upper left", framealpha=0.8, facecolor="0.5")
    ax[0].set_title(f"{tag[0]}MCR, {ok.sum()} samples to depth {int(r['depth'])} ({run.options.get('force_profile', 'site')} forcing)", fontsize=10)
    pos = ratio > 0
    if pos.all():
        pr = ax[1].tripcolor(tri, np.log10(ratio), shading="gouraud", cmap="cividis")
        fig.colorbar(pr, ax=ax[1], label="log10 (nonlinear / linear potential energy)")
    ax[1].plot(x, w, ".", color="k", ms=1, label="_samples")
    decorate(ax[1])
    ax[1].set_title(f"{tag[1]}energy ratio", fontsize=10)
    fig.tight_layout()
    return fig


if __name__ == "__main__":
    main()
