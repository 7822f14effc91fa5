#!/usr/bin/python3
"""Work-precision diagram of -study workprecision (outputs.md /workprecision):
wall time against the error of each observable, log-log, one curve per method
(its configurations in order of accuracy), the convention of
DifferentialEquations.jl's WorkPrecisionSet; the predictability floor (the
twins' spread) as a shaded band: errors inside it mean nothing.
usage: plot_workprecision.py workprecision.h5 [out.png]
figure(h5file) builds the figure without saving it (the scene test reads it)."""
import sys
import h5py
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

# the panels of each scene (/workprecision attribute scene), in order
PANELS = {"simulate": (("mcr", "MCR"), ("state", "final state z(t_final)"), ("t_off", "cut-off time t_off"), ("energy", "energy after the cut-off")),
          "shooting": (("omega", "orbit frequency omega"), ("closure", "orbit closure |z(T) - z0| / |z0|"), ("max_modulus", "largest Floquet modulus"),
                       ("det", "|det M - 1| (the method's own)"))}


def panels(f):
    return PANELS[text(f["workprecision"].attrs.get("scene", "simulate"))]


def text(x):
    return x.decode() if isinstance(x, bytes) else str(x)


def figure(f):
    g = f["workprecision"]
    a = g.attrs
    method = [text(m) for m in g["method"][:]]
    wall = g["wall_seconds"][:]
    fig, axes = plt.subplots(2, 2, figsize=(11, 8))
    for ax, (obs, name) in zip(axes.flat, panels(f)):
        err = g["error_" + obs][:]
        floor = float(a["spread_" + obs])
        shown = np.maximum(err, 1e-17)  # an exact 0 (a run equal to the reference) at the bottom of the axis
        for m in dict.fromkeys(method):
            idx = [i for i, x in enumerate(method) if x == m]
            idx.sort(key=lambda i: -err[i])  # from the least to the most accurate
            ax.loglog(shown[idx], wall[idx], "o-", label=m)
        lo = min(shown.min(), floor if floor > 0 else shown.min()) / 3
        hi = max(shown.max(), floor) * 3
        ax.set_xlim(lo, hi)
        ax.set_ylim(wall.min() / 1.5, wall.max() * 1.5)
        if floor > 0:
            ax.axvspan(lo, floor, color="0.85", zorder=0, label="predictability floor")
        ax.set(xlabel=name if obs == "det" else f"relative error of the {name}", ylabel="wall time (s, median)")
        ax.grid(True, which="major", alpha=0.3)
    for ax in axes.flat:  # every panel names its curves (tests/scenes/plot_check.py, rule 4)
        ax.legend(fontsize=6)
    ref = text(a["reference"])
    conv = "converged" if a["reference_converged"] else "NOT converged"
    if text(a.get("scene", "simulate")) == "shooting":
        fig.suptitle(f"work-precision of the insulated NNM at E = {a['nnm_energy']:g} (Newton and monodromy)\nreference: {ref} ({conv})", fontsize=8)
    else:
        fig.suptitle(f"work-precision at E* = {a['energy_star']:g}, omega_ext = {a['omega_ext']:.4f}\nreference: {ref}"
                     f" ({conv}); finite-time Lyapunov {a['lyapunov']:.3g} /s", fontsize=8)
    fig.tight_layout()
    return fig


if __name__ == "__main__":
    path = sys.argv[1]
    out = sys.argv[2] if len(sys.argv) > 2 else path.replace(".h5", "") + "_workprecision.png"
    with h5py.File(path, "r") as f:
        figure(f).savefig(out, dpi=120)
    print("wrote", out)
