#!/usr/bin/python3
"""Time histories of forced runs (-study simulate, the paper's Fig. 7): one row
per run, each forced at the insulated NNM's frequency at its E*: (left) the
displacement u(t) of every site over the first 250 s after the cut-off (or
the last 250 s if the run never reached E*), (right) the RMS amplitude of each
site after the cut-off on a log scale, even sites orange and odd sites purple,
with E*, omega_ext and the MCR.
usage: plot_timehistories.py run1.h5 [run2.h5 ...] [out.png] [-window seconds]"""
import sys
import h5py
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np
import nltopo_plot

argv = sys.argv[1:]
window = nltopo_plot.pop_option(argv, "-window", 250.0)
files = [a for a in argv if a.endswith(".h5")]
outs = [a for a in argv if a.endswith(".png")]
out = outs[0] if outs else files[0].replace(".h5", "") + "_histories.png"
runs = sorted((h5py.File(n, "r")["simulate"] for n in files), key=lambda S: S.attrs["energy_star"])
fig, ax = plt.subplots(len(runs), 2, figsize=(13, 2.6 * len(runs)), gridspec_kw={"width_ratios": [2.2, 1]}, squeeze=False)
for r, S in enumerate(runs):
    a = S.attrs
    t = S["t"][:]
    if "u" not in S:
        sys.exit(f"plot_timehistories.py: {S.file.filename} has no /simulate/u (run with -sim_store_u 1)")
    u = S["u"][:]
    t_off = float(a["t_off"])
    t0 = t_off if t_off >= 0 else max(t[0], t[-1] - window)
    sel = (t >= t0) & (t <= t0 + window)
    lim = np.percentile(np.abs(u[sel]), 99.5) or 1.0
    N = u.shape[1]
    ax[r, 0].imshow(u[sel].T, aspect="auto", origin="lower", extent=[t[sel][0], t[sel][-1], 1, N], cmap="RdBu_r", vmin=-lim, vmax=lim,
                    interpolation="nearest")
    ax[r, 0].set(xlabel="t (s)" + (" (after the cut-off)" if t_off >= 0 else " (E* never reached)"), ylabel="site")
    ax[r, 0].set_title(rf"E* = {a['energy_star']:g}: $\omega_{{ext}}$ = {a['omega_ext']:.4f}, u(t) in $\pm${lim:.2g}", fontsize=9)
    rms = S["rms"][:]
    sites = np.arange(1, N + 1)
    ax[r, 1].semilogy(sites[1::2], rms[1::2], "o", color="tab:orange", ms=2.5, label="even sites")
    ax[r, 1].semilogy(sites[0::2], rms[0::2], "o", color="tab:purple", ms=2.5, label="odd sites")
    ax[r, 1].set(xlabel="site", ylabel="RMS u after the cut-off")
    ax[r, 1].set_title(f"MCR = {a['mcr']:.3f}" + ("" if a["energy_reached"] else " (E* not reached)"), fontsize=9)
    ax[r, 1].legend(fontsize=7, loc="lower left")
fig.tight_layout()
fig.savefig(out, dpi=110)
print("wrote", out)
