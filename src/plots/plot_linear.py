#!/usr/bin/python3
"""Paper-style figure of -study linear: finite-lattice spectrum with the named
modes, infinite-lattice Bloch bands with the Zak phases, and the insulated and
interface mode shapes; with /linear/transition (-linear_gamma_list) also paper
Fig. 2a into <out>_transition.png (plot_transition.py).
usage: plot_linear.py linear.h5 [out.png]"""
import os
import sys
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np
import nltopo_plot


def load(path):
    """/linear of a -study linear file."""
    return nltopo_plot.open_run(path).linear


def figure(L):
    B = L.bloch
    w, a = L.omega, L
    fig, ax = plt.subplots(1, 3, figsize=(13, 4))
    ax[0].plot(np.arange(len(w)), w, ".", color="0.4", label="finite lattice" + ("" if "modes" in L else " (computed subset)"))
    for name, c in (("insulated_omega", "C3"), ("interface_omega", "C0"), ("acoustic_top", "C2"), ("optical_bottom", "C1"), ("optical_top", "C4")):
        if np.isfinite(a[name]):
            ax[0].axhline(a[name], color=c, lw=0.8, label=f"{name} = {a[name]:.4f}")
    N = int(a["N"])
    ax[0].set(xlabel="mode index", ylabel=r"$\omega$ (rad/time)", title=f"linear spectrum, N = {N}")
    ax[0].legend(fontsize=7)
    q = B.q
    ax[1].plot(q, B.omega_acoustic, "C2", label="acoustic")
    ax[1].plot(q, B.omega_optical, "C1", label="optical")
    za, zo = B.zak_left_optical, B.zak_right_optical
    ax[1].set(xlabel=r"$\mu$", ylabel=r"$\omega$", title=f"Bloch bands; Zak (optical): left {za:.3f}, right {zo:.3f}")
    ax[1].legend(fontsize=8)
    sites = np.arange(1, N + 1)
    modes = L.modes if "modes" in L else L.modes_selected
    if "insulated_mode" in L:
        ax[2].plot(sites, L.insulated_mode, "C3.-", ms=3, label=r"insulated ($\sqrt{3}$)")
    i = int(a["interface_index"])
    if i >= 0:
        ax[2].plot(sites, modes[i], "C0.-", ms=3, alpha=0.7, label=f"interface ({w[i]:.4f})")
    ax[2].set(xlabel="site", ylabel="amplitude", title="localised modes")
    ax[2].legend(fontsize=8)
    fig.tight_layout()
    return fig



def main(argv=None):
    p = nltopo_plot.parser(__doc__)
    p.add_argument("h5", help="a -study linear output")
    p.add_argument("out", nargs="?", help="the PNG (default: <h5 without .h5>_linear.png)")
    a = p.parse_args(argv)
    out = a.out or a.h5.replace(".h5", "") + "_linear.png"
    L = load(a.h5)
    figure(L).savefig(out, dpi=120)
    print("wrote", out)
    if "transition" in L:
        sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
        import plot_transition
        base, ext = os.path.splitext(out)
        plot_transition.draw(L.transition, base + "_transition" + (ext or ".png"))


if __name__ == "__main__":
    main()
