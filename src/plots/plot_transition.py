#!/usr/bin/python3
"""Paper Fig. 2a from -study linear -linear_gamma_list (/linear/transition):
the finite lattice's spectrum against the dimerisation gamma, over the infinite
lattice's bands, with the localised (edge and interface) modes in the gap
marked; and the Zak phases of both bands for the left and right unit cells.
usage: plot_transition.py transition.h5 [out.png]"""
import sys
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np
import nltopo_plot


def load(path):
    """/linear/transition of a -study linear file run with -linear_gamma_list."""
    L = nltopo_plot.open_run(path).linear
    if "transition" not in L:
        sys.exit(f"{path} has no /linear/transition (run -study linear with -linear_gamma_list, e.g. options/transition.opts)")
    return L.transition


def draw(T, out):
    """Draws /linear/transition (a view of the reader) into out."""
    g, w, b = T.gamma, T.omega, T.bands_inf
    N, layout = int(T.N), str(T.layout)
    fig, ax = plt.subplots(1, 2, figsize=(12, 4.5))
    # Spectrum: the infinite bands as shaded regions; every finite eigenfrequency a dot,
    # coloured by where it lies (docs/studies/linear.md).
    ax[0].fill_between(g, b[:, 0], b[:, 1], color="C2", alpha=0.15, lw=0, label="acoustic band (infinite lattice)")
    ax[0].fill_between(g, b[:, 2], b[:, 3], color="C1", alpha=0.15, lw=0, label="optical band (infinite lattice)")
    G = np.repeat(g[:, None], N, axis=1)
    tol = 1e-9 * b[:, 3:4]
    in_gap = (w > b[:, 1:2] + tol) & (w < b[:, 2:3] - tol)
    outside = (w < b[:, 0:1] - tol) | (w > b[:, 3:4] + tol)
    bulk = ~(in_gap | outside)
    ax[0].scatter(G[bulk], w[bulk], s=1, color="0.45", label="finite lattice: band modes")
    ax[0].scatter(G[in_gap], w[in_gap], s=5, color="C3", label="in the gap: edge / interface modes")
    ax[0].scatter(G[outside], w[outside], s=5, color="C0", label="outside the bands: interface modes")
    ax[0].set(xlabel=r"$\gamma$", ylabel=r"$\omega$ (rad/time)", title=f"spectrum against gamma (N = {N}, {layout})")
    ax[0].legend(fontsize=7, loc="upper left")
    # Zak phases: both bands of each cell (they coincide; the markers tell them apart). NaN (gamma = 0: gap closed) is a gap in the line.
    zl, zr = T.zak_left, T.zak_right
    every = max(1, len(g) // 20)
    for z, cell, c in ((zl, "left cell (intra $k_2$, inter $k_1$)", "C3"), (zr, "right cell (intra $k_1$, inter $k_2$)", "C0")):
        ax[1].plot(g, z[:, 1], "-", color=c, lw=1.5, marker="o", ms=5, markevery=every, mfc="none", label=f"{cell}, optical")
        ax[1].plot(g, z[:, 0], "--", color=c, lw=1, marker="x", ms=4, markevery=(every // 2, every), label=f"{cell}, acoustic")
    undefined = g[np.isnan(zl).any(axis=1) | np.isnan(zr).any(axis=1)]
    for x in undefined:
        ax[1].axvline(x, color="0.5", ls=":", lw=0.8)
    ax[1].set_yticks([0, np.pi / 2, np.pi])
    ax[1].set_yticklabels(["0", r"$\pi/2$", r"$\pi$"])
    ax[1].set_ylim(-0.5, np.pi + 0.8)
    ax[1].set(xlabel=r"$\gamma$", ylabel="Zak phase (rad)",
              title="Zak phase" + (" (undefined at gamma = " + ", ".join(f"{x:g}" for x in undefined) + ")" if len(undefined) else ""))
    ax[1].legend(fontsize=7, loc="upper center", ncol=2)
    fig.tight_layout()
    fig.savefig(out, dpi=120)
    print("wrote", out)


def main(argv=None):
    p = nltopo_plot.parser(__doc__)
    p.add_argument("h5", help="a -study linear output with /linear/transition")
    p.add_argument("out", nargs="?", help="the PNG (default: <h5 without .h5>_transition.png)")
    a = p.parse_args(argv)
    draw(load(a.h5), a.out or a.h5.replace(".h5", "") + "_transition.png")


if __name__ == "__main__":
    main()
