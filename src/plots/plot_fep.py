#!/usr/bin/python3
"""Paper-style frequency-energy plot of -study continuation: omega vs energy of
every branch over the linear bands (shaded), the MCR of each orbit, and the
flagged modal interactions.  usage: plot_fep.py fep.h5 [out.png]"""
import sys
import h5py
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np
import nltopo_plot

f = h5py.File(sys.argv[1], "r")
out = sys.argv[2] if len(sys.argv) > 2 else sys.argv[1].replace(".h5", "") + "_fep.png"
bands = nltopo_plot.bands(f["continuation"])
fig, ax = plt.subplots(1, 2, figsize=(13, 5))
for lo, hi in bands:
    ax[0].axhspan(lo, hi, color="0.9")
for name, grp in f["continuation"].items():
    E, w, mcr = grp["energy"][:], grp["omega"][:], grp["mcr"][:]
    line, = ax[0].semilogx(E, w, ".-", ms=3, label=f"{name} ({grp.attrs['points']} pts)")
    ax[1].semilogx(E, mcr, ".-", ms=3, color=line.get_color(), label=name)
    if "stable" in grp:  # unstable orbits in red, as in the paper's figure
        bad = grp["stable"][:] == 0
        ax[0].plot(E[bad], w[bad], "o", mfc="none", mec="r", ms=5)
    inter = grp["interactions"][:].astype(int) if "interactions" in grp else []
    if len(inter):
        ax[0].plot(E[inter], w[inter], "x", color=line.get_color(), ms=8)
ax[0].axvline(12, color="k", ls="--", lw=0.8)
ax[0].set(xlabel="energy E", ylabel=r"$\omega$ (rad/s)", title="NNM branches (red o: Floquet-unstable; x: modal interaction; grey: bands)")
ax[0].legend(fontsize=8)
ax[1].axvline(12, color="k", ls="--", lw=0.8, label="E = 12 (paper)")
ax[1].set(xlabel="energy E", ylabel="MCR of u0", title="localisation along the branches")
ax[1].legend(fontsize=8)
fig.tight_layout()
fig.savefig(out, dpi=120)
print("wrote", out)
