#!/usr/bin/python3
"""Figure of -study stability (the paper's Fig. 4c): for every case, the loss of
shape 1 - (shape correlation with the NNM) on a log scale and the MCR against
the number of periods, with the Floquet verdict.
usage: plot_stability.py stability.h5 [out.png]"""
import sys
import h5py
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

f = h5py.File(sys.argv[1], "r")
out = sys.argv[2] if len(sys.argv) > 2 else sys.argv[1].replace(".h5", "") + "_stability.png"
cases = sorted(f["stability"].keys(), key=lambda c: int(c[4:]))
fig, ax = plt.subplots(2, 1, figsize=(9, 6), sharex=True)
for c in cases:
    g = f["stability/" + c]
    a = g.attrs
    periods = g["t"][:] / a["period"]
    lab = (rf"$\omega$ = {a['omega']:.4f}, E = {a['energy']:.3g}: max|$\mu$| = {a['max_modulus']:.5f}"
           f" ({'stable' if a['floquet_stable'] else 'unstable'}), {'persisted' if a['persisted'] else 'lost'}")
    loss = 1 - g["corr"][:]
    ax[0].plot(periods, np.where(loss > 0, loss, np.nan), label=lab)
    ax[1].plot(periods, g["mcr"][:])
opts = f.attrs.get("options", b"")
opts = (opts.decode() if isinstance(opts, bytes) else str(opts)).split()
corr_min = float(opts[opts.index("-stability_corr_min") + 1]) if "-stability_corr_min" in opts[:-1] else 0.9
ax[0].axhline(1 - corr_min, color="k", ls=":", lw=0.8)
ax[0].set(yscale="log", xlabel="periods", ylabel="1 - shape correlation with the NNM",
          title="perturbed insulated-branch NNMs (dotted: lost above)")
ax[0].legend(fontsize=7)
ax[1].set(xlabel="periods", ylabel="MCR")
fig.tight_layout()
fig.savefig(out, dpi=120)
print("wrote", out)
