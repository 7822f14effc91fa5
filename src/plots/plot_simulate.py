#!/usr/bin/python3
"""Paper-style figure of -study simulate: (a) the energy history with the
cut-off, (b) the space-time map of the displacement u (sites against t, with
its colour bar; -sim_store_u 1), (c) the RMS amplitude of each site after the
cut-off (log scale; even sites orange, odd sites purple, as in the paper) with
the MCR.
usage: plot_simulate.py simulate.h5 [out.png]"""
import sys
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np
import nltopo_plot


def load(path):
    """/simulate of a -study simulate file."""
    return nltopo_plot.open_run(path).simulate


def figure(S):
    t, E, rms = S.t, S.energy, S.rms
    fig, ax = plt.subplots(1, 3, figsize=(15, 4.2), gridspec_kw={"width_ratios": [1, 1.25, 1]})
    ax[0].plot(t, E, "k")
    if S.t_off >= 0:
        ax[0].axvline(S.t_off, color="C3", ls="--", label=f"cut-off t = {S.t_off:.1f}")
    ax[0].axhline(S.energy_star, color="0.6", lw=0.8, label=f"E* = {S.energy_star:g}")
    ax[0].set(xlabel="t", ylabel="energy E", title=rf"(a) energy: $\omega_{{ext}}$ = {S.omega_ext:.4f}, S = {S.amplitude:.3g}")
    ax[0].legend(fontsize=8)
    if "u" in S:
        nltopo_plot.space_time(fig, ax[1], t, S.u)
        ax[1].set(xlabel="t", ylabel="site", title="(b) displacement u(t) of every site")
    else:
        ax[1].text(0.5, 0.5, "no u(t) stored\n(-sim_store_u 1)", ha="center", va="center", transform=ax[1].transAxes)
        ax[1].set_axis_off()
    nltopo_plot.rms_by_parity(ax[2], rms)
    ax[2].set(xlabel="site", ylabel="RMS u after the cut-off", title=f"(c) RMS per site: MCR = {S.mcr:.4f}")
    ax[2].legend(fontsize=8)
    fig.tight_layout()
    return fig


if __name__ == "__main__":
    nltopo_plot.main_one_file(__doc__, "simulate", "simulate", load, figure, dpi=120)
