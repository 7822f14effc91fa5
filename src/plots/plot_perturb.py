#!/usr/bin/python3
"""Paper-style perturbation figure of -study perturb: for each kind (chiral,
achiral), the ensemble mean MCR (band: +- one standard deviation over the
realisations) against E* for every level delta, and the linear insulated
frequency of every realisation against delta.
usage: plot_perturb.py perturb.h5 [out.png]"""
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np
import nltopo_plot


def load(path):
    """/perturb of a -study perturb file."""
    return nltopo_plot.open_run(path).perturb


def figure(P):
    kinds = sorted(P.kinds, key=lambda k: (k != "chiral", k))  # chiral left, as in the paper
    fig, ax = plt.subplots(2, len(kinds), figsize=(6 * len(kinds), 8.5), squeeze=False)
    for c, kind in enumerate(kinds):
        g = P[kind]
        d, E, mcr, w = g.delta, g.energy, g.mcr, g.insulated_omega
        for i, di in enumerate(d):
            m, s = np.nanmean(mcr[i], axis=1), np.nanstd(mcr[i], axis=1)
            line, = ax[0, c].semilogx(E, m, "o-", ms=3, label=f"delta = {di:g}")
            ax[0, c].fill_between(E, m - s, m + s, color=line.get_color(), alpha=0.15)
        ax[0, c].axvline(12, color="k", ls="--", lw=0.8)
        ax[0, c].set(xlabel="E*", ylabel="MCR (ensemble mean +- std)", title=f"{kind}: {mcr.shape[2]} realisations per delta")
        ax[0, c].legend(fontsize=7)
        for i, di in enumerate(d):
            ax[1, c].plot(np.full(w.shape[1], di), w[i] - np.sqrt(3), "k.", ms=4)
        ax[1, c].axhline(0, color="tab:red", lw=0.8, label=r"$\sqrt{3}$ (unperturbed)")
        ax[1, c].ticklabel_format(axis="y", useOffset=False, style="sci", scilimits=(-3, 3))
        ax[1, c].set(xlabel="delta", ylabel=r"linear insulated $\omega - \sqrt{3}$ (rad/s)", title=f"{kind}: linear insulated frequency of each realisation")
        ax[1, c].legend(fontsize=7)
    fig.tight_layout()
    return fig


if __name__ == "__main__":
    nltopo_plot.main_one_file(__doc__, "perturb", "perturb", load, figure, dpi=120)
