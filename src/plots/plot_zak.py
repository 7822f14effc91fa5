#!/usr/bin/python3
"""Paper-style phase figure of -study zak (the paper's Fig. 5c-d): phi_0 and
phi_pi (mean and median over unit cells and windows, with each window's
median as small markers) against E*, the linear values 0 and pi, the
detected threshold, and the paper's E = 12.
usage: plot_zak.py zak.h5 [out.png]"""
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np
import nltopo_plot


def load(path):
    """/zak of a -study zak file."""
    return nltopo_plot.open_run(path).zak


def figure(z):
    thr = float(z.energy_threshold)
    E = z.energy
    fig, ax = plt.subplots(1, 2, figsize=(12, 4.6), sharey=True)
    for a, stat, letter in zip(ax, ("median", "mean"), "cd"):  # the paper's Fig. 5c-d (a-b: plot_zak_runs.py)
        for key, color, label in (("phi0", "tab:blue", r"$\phi_0$ ($\mu = 0$, band bottom)"), ("phipi", "tab:red", r"$\phi_\pi$ ($\mu = \pi$, band top)")):
            a.semilogx(E, z[f"{key}_{stat}"], "o-", color=color, ms=4, label=label)
            wm = z[f"{key}_window_median"]
            for k in range(wm.shape[1]):
                a.semilogx(E, wm[:, k], ".", color=color, alpha=0.25 + 0.75 * k / max(1, wm.shape[1] - 1), ms=3)
        for y in (0, np.pi):
            a.axhline(y, color="0.6", lw=0.6, ls=":")
        a.axvline(12, color="k", ls="--", lw=0.8, label="E = 12 (paper)")
        if thr > 0:
            a.axvline(thr, color="tab:green", lw=1.2, label=f"threshold here: E = {thr:.3g}")
        a.set(xlabel="E*", ylabel=rf"{stat} of phase(even) - phase(odd) per cell", title=f"({letter}) {stat} over unit cells and windows", ylim=(-np.pi / 2, 1.5 * np.pi))
        a.set_yticks([-np.pi / 2, 0, np.pi / 2, np.pi, 1.5 * np.pi])
        a.set_yticklabels([r"$-\pi/2$", "0", r"$\pi/2$", r"$\pi$", r"$3\pi/2$"])
    for a in ax:
        a.legend(fontsize=7, loc="lower left")
    fig.tight_layout()
    return fig


if __name__ == "__main__":
    nltopo_plot.main_one_file(__doc__, "zak", "phase", load, figure, dpi=120)
