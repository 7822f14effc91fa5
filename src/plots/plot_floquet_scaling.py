#!/usr/bin/python3
"""Figure of -study floquet_scaling (docs/studies/floquet_scaling.md): left,
per energy window the envelope (largest |mu| - 1 over the window's orbits)
against the lattice size N on log-log axes, with its fit C N^-p (dashed) and
the window's verdict; right, |mu| - 1 of every orbit against E at each N, the
window edges dotted.
usage: plot_floquet_scaling.py floquet_scaling.h5 [out.png]"""
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np
import nltopo_plot

VERDICT = {0: "stable", 1: "persists", 2: "finite-size", 3: "undetermined"}


def load(path):
    """(/floquet_scaling/windows or None, [(N, energy, |mu| - 1)] per size, floquet_tol) of a -study floquet_scaling file."""
    run = nltopo_plot.open_run(path)
    top = run.floquet_scaling
    sizes = []
    for name in top.groups:
        if name.startswith("cells"):
            g = run.group(top.path + "/" + name)
            sizes.append((int(g.attrs["N"]), g.energy, g.max_modulus - 1))
    sizes.sort(key=lambda s: s[0])
    windows = run.group(top.path + "/windows") if "windows" in top.groups else None
    return windows, sizes, float(top.attrs["floquet_tol"])


def figure(loaded):
    W, sizes, tol = loaded
    fig, ax = plt.subplots(1, 2, figsize=(12, 4.8))
    if W is not None:
        N = W.N
        for k in range(len(W.energy_lo)):
            env = W.envelope[k]
            ok = np.isfinite(env) & (env > tol)
            if not ok.any():
                continue
            lab = (f"E in [{W.energy_lo[k]:g}, {W.energy_hi[k]:g}): p = {W.exponent[k]:.2f}, R$^2$ = {W.r2[k]:.2f}: "
                   f"{VERDICT.get(int(W.verdict[k]), '?')}")
            line, = ax[0].plot(N[ok], env[ok], "o", label=lab)
            if np.isfinite(W.exponent[k]):
                n = np.geomspace(N[ok].min(), N[ok].max(), 20)
                ax[0].plot(n, W.prefactor[k] * n ** -W.exponent[k], "--", color=line.get_color(), lw=1)
        ax[0].legend(fontsize=7)
    ax[0].set(xscale="log", yscale="log", xlabel="N (sites)", ylabel="envelope: max |mu| - 1 over the window",
              title="envelope against N, fit C N^-p dashed")
    for N, E, d in sizes:
        ax[1].plot(E, np.where(d > 0, d, np.nan), ".-", lw=0.7, ms=3, label=f"N = {N}")
    if W is not None:
        for e in np.concatenate([W.energy_lo, W.energy_hi[-1:]]):
            ax[1].axvline(e, color="k", ls=":", lw=0.8)
    ax[1].axhline(tol, color="grey", ls="--", lw=0.8)
    ax[1].set(xscale="log", yscale="log", xlabel="E (energy)", ylabel="|mu| - 1 (largest nontrivial)",
              title="every orbit (dashed: -floquet_tol; dotted: window edges)")
    ax[1].legend(fontsize=7)
    fig.tight_layout()
    return fig


if __name__ == "__main__":
    nltopo_plot.main_one_file(__doc__, "floquet_scaling", "scaling", load, figure, dpi=120)
