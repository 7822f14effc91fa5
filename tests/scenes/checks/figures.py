#!/usr/bin/python3
"""Checks of the figures scene (tests/scenes/figures.sh); usage: figures.py STEP ARGUMENTS."""
import glob
import os
import sys
sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
import numpy as np
from scene_check import group, main, require


def drawn_data(plots):
    """The panels drawn beside the studies' own results (plots: src/plots, for nltopo_plot): Fig. 5a-b's
    simulate runs repeat zak runs exactly and show the linear phases at the lowest E*; Fig. 8a-b's profile is
    the exponential fit the sweep ran with."""
    sys.path.insert(0, plots)
    import nltopo_plot
    # Fig. 5a-b: each simulate run repeats a zak run: its E* on the zak grid, the same
    # MCR, and the plot's dimer phases over the zak windows give the zak window medians
    z = group("out/data/zak.h5", "zak")
    runs = sorted(glob.glob("out/data/zak_run_*.h5"))
    require(len(runs) >= 4, runs)
    low = {}
    for name in runs:
        S = group(name, "simulate")
        edge = "0" if S.attrs["omega_ext"] == z.attrs["omega0"] else "pi"
        require(S.attrs["omega_ext"] == z.attrs["omega" + edge], name)
        k = int(np.flatnonzero(z["energy"][:] == S.attrs["energy_star"])[0])  # exactly a grid energy
        mcr_zak = z["mcr" + edge][k]
        require(abs(S.attrs["mcr"] - mcr_zak) <= 1e-9 * mcr_zak, name, S.attrs["mcr"], mcr_zak)
        t, u, w = S["t"][:], S["u"][:], S.attrs["omega_ext"]
        zwin = z["phi%s_window_median" % edge][k]
        wins = nltopo_plot.zak_windows(t, S.attrs["t_off"], int(z.attrs["samples_per_period"]), len(zwin))
        med = [np.median(nltopo_plot.dimer_phases(t[i], u[i], w)) for i in wins]
        require(np.allclose(med, zwin, rtol=0, atol=1e-6), name, med, zwin)
        if k == 0:
            low[edge] = med[-1]
    print("fig 5a-b: %d runs repeat the zak runs (MCR to 1e-9, window medians to 1e-6); lowest E*: phi_0 = %.4f, phi_pi = %.4f" % (len(runs), low["0"], low["pi"]))
    require(abs(low["0"]) < 0.1 and abs(low["pi"] - np.pi) < 0.1, low)  # in phase at mu = 0, out of phase at mu = pi
    # Fig. 8a-b: the profile the exponential sweep ran with: a e^{b |n - m|} (-1)^{n/2} on the
    # even sites (1-based n, m = N/2), b = ln(k2/k1)/2 at the defaults, equal to the linear insulated mode there
    s = group("out/data/sweep_exponential.h5", "sweep")
    eta, phi = s["force_eta"][:], s["insulated_mode"][:]
    a, b = s.attrs["force_exp_a"], s.attrs["force_exp_b"]
    N = len(eta)
    n = np.arange(1, N + 1)
    even = n % 2 == 0
    require(not eta[~even].any())
    require(np.allclose(eta[even], a * np.exp(b * np.abs(n[even] - N // 2)) * (-1.0) ** (n[even] // 2), rtol=1e-12, atol=0))
    require(abs(b - 0.5 * np.log(3 / 7)) < 1e-8, b)
    require(np.abs(eta - phi).max() < 1e-6 * np.abs(phi).max(), np.abs(eta - phi).max())
    print("fig 8a-b: eta on the %d even sites, a = %.6f, b = %.6f, max |eta - phi| = %.2g" % (even.sum(), a, b, np.abs(eta - phi).max()))


if __name__ == "__main__":
    main(globals())
