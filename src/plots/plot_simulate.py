#!/usr/bin/python3
"""Paper-style figure of -study simulate: energy history with the cut-off,
space-time displacement map, and RMS per site (log scale) with the MCR.
usage: plot_simulate.py simulate.h5 [out.png]"""
import sys
import h5py
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

f = h5py.File(sys.argv[1], "r")
out = sys.argv[2] if len(sys.argv) > 2 else sys.argv[1].replace(".h5", "") + "_simulate.png"
S = f["simulate"]
a = S.attrs
t, E, rms = S["t"][:], S["energy"][:], S["rms"][:]
fig, ax = plt.subplots(1, 3, figsize=(14, 4))
ax[0].plot(t, E, "k")
if a["t_off"] >= 0:
    ax[0].axvline(a["t_off"], color="C3", ls="--", label=f"cut-off t = {a['t_off']:.1f}")
ax[0].axhline(a["energy_star"], color="0.6", lw=0.8, label=f"E* = {a['energy_star']:g}")
ax[0].set(xlabel="t (s)", ylabel="E", title=rf"$\omega_{{ext}}$ = {a['omega_ext']:.4f}, S = {a['amplitude']:.3g}")
ax[0].legend(fontsize=8)
if "u" in S:
    u = S["u"][:]
    lim = np.percentile(np.abs(u), 99.5) or 1
    ax[1].imshow(u.T, aspect="auto", origin="lower", extent=[t[0], t[-1], 1, u.shape[1]], cmap="RdBu_r", vmin=-lim, vmax=lim)
    ax[1].set(xlabel="t (s)", ylabel="site", title="u(t)")
sites = np.arange(1, len(rms) + 1)
ax[2].semilogy(sites[0::2], rms[0::2], "C0o", ms=3, label="odd sites")
ax[2].semilogy(sites[1::2], rms[1::2], "C3o", ms=3, label="even sites")
ax[2].set(xlabel="site", ylabel="RMS u after cut-off", title=f"MCR = {a['mcr']:.4f}")
ax[2].legend(fontsize=8)
fig.tight_layout()
fig.savefig(out, dpi=120)
print("wrote", out)
