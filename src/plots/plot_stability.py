#!/usr/bin/python3
"""Figure of -study stability (the paper's Fig. 4c): for every case, the loss of
shape 1 - (shape correlation with the NNM) on a log scale and the MCR against
the number of periods, with the Floquet verdict.
usage: plot_stability.py stability.h5 [out.png]"""
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np
import nltopo_plot


def load(path):
    """(/stability, the options) of a -study stability file."""
    run = nltopo_plot.open_run(path)
    return run.stability, run.options


def figure(loaded):
    S, options = loaded
    fig, ax = plt.subplots(2, 1, figsize=(9, 6), sharex=True)
    for g in S.cases:  # case0, case1, ... in order
        a = g.attrs  # the case's attributes (its `energy` the orbit's; the dataset energy is E(t))
        periods = g.t / a["period"]
        lab = (rf"$\omega$ = {a['omega']:.4f}, E = {a['energy']:.3g}: max|$\mu$| = {a['max_modulus']:.5f}"
               f" ({'stable' if a['floquet_stable'] else 'unstable'}), {'persisted' if a['persisted'] else 'lost'}")
        loss = 1 - g.corr
        ax[0].plot(periods, np.where(loss > 0, loss, np.nan), label=lab)
        ax[1].plot(periods, g.mcr)
    corr_min = float(options.get("stability_corr_min", 0.9))
    ax[0].axhline(1 - corr_min, color="k", ls=":", lw=0.8)
    ax[0].set(yscale="log", xlabel="periods", ylabel="1 - shape correlation with the NNM",
              title="perturbed insulated-branch NNMs (dotted: lost above)")
    ax[0].legend(fontsize=7)
    ax[1].set(xlabel="periods", ylabel="MCR")
    fig.tight_layout()
    return fig


if __name__ == "__main__":
    nltopo_plot.main_one_file(__doc__, "stability", "stability", load, figure, dpi=120)
