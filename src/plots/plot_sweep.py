#!/usr/bin/python3
"""Paper-style forced-response map of -study sweep: the MCR over (E*, omega_ext)
with the linear bands marked, the 0-1 test's kcorr = 0.7 contour (chaos), points
that never reached E* crossed out, points an accuracy-aware sweep
(-sweep_mcr_tol) found unpredictable dotted (their MCR is a twins' mean), and,
when a continuation file is given, its
NNM branches (the frequency-energy plot) overlaid.
usage: plot_sweep.py sweep.h5 [fep.h5] [out.png]"""
import sys
import h5py
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np
import nltopo_plot

args = [a for a in sys.argv[1:] if a.endswith(".h5")]
outs = [a for a in sys.argv[1:] if not a.endswith(".h5")]
f = h5py.File(args[0], "r")
fep = h5py.File(args[1], "r") if len(args) > 1 else None
out = outs[0] if outs else args[0].replace(".h5", "") + "_map.png"
s = f["sweep"]
w, E = s["omega"][:], s["energy"][:]
done = s["done"][:].astype(bool)
mcr = np.where(done, s["mcr"][:], np.nan)
kc = np.where(done, s["kcorr"][:], np.nan)
bands = nltopo_plot.bands(s)

fig, ax = plt.subplots(1, 2, figsize=(13, 5.2))
pc = ax[0].pcolormesh(E, w, mcr.T, shading="nearest", cmap="viridis", vmin=0, vmax=np.nanmax(mcr))
fig.colorbar(pc, ax=ax[0], label="MCR")
if s.attrs.get("kcorr_computed", 0) and np.isfinite(kc).sum() > 3 and len(E) > 1 and len(w) > 1:
    ax[0].contour(E, w, kc.T, levels=[0.7], colors="w", linewidths=1.2)
missed = done & (s["reached"][:] == 0)
if missed.any():
    ee, ww = np.meshgrid(E, w, indexing="ij")
    ax[0].plot(ee[missed], ww[missed], "rx", ms=5, label="E* not reached")
for lo, hi in bands:
    for a in ax:
        a.axhline(lo, color="0.6", lw=0.6, ls=":")
        a.axhline(hi, color="0.6", lw=0.6, ls=":")
unpredictable = done & (s["predictable"][:] == 0) if "predictable" in s else np.zeros_like(done)
if unpredictable.any():
    ee, ww = np.meshgrid(E, w, indexing="ij")
    ax[0].plot(ee[unpredictable], ww[unpredictable], ".", color="0.85", ms=2.5, label="unpredictable (twins' mean)")
if fep is not None:
    for name, grp in fep["continuation"].items():
        ax[0].plot(grp["energy"][:], grp["omega"][:], "-", lw=1.4, label=name)
ax[0].axvline(12, color="k", ls="--", lw=0.8)
ax[0].set(xscale="log", xlabel="E*", ylabel=r"$\omega_{ext}$ (rad/s)", title="MCR of the forced response (white: kcorr = 0.7; dotted: bands)",
          ylim=(w.min(), w.max()), xlim=(E.min(), E.max()))
if fep is not None or missed.any() or unpredictable.any():
    ax[0].legend(fontsize=7, loc="upper left")
pk = ax[1].pcolormesh(E, w, kc.T, shading="nearest", cmap="magma", vmin=0, vmax=1)
fig.colorbar(pk, ax=ax[1], label="kcorr (0-1 test, max over sites)")
ax[1].set(xscale="log", xlabel="E*", ylabel=r"$\omega_{ext}$ (rad/s)", title="0-1 test for chaos")
if not s.attrs.get("kcorr_computed", 0):
    ax[1].text(0.5, 0.5, "not computed (run with -sweep_kcorr)", transform=ax[1].transAxes, ha="center")
fig.tight_layout()
fig.savefig(out, dpi=120)
print("wrote", out)
