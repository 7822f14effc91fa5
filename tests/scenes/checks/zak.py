#!/usr/bin/python3
"""Checks of the zak scene (tests/scenes/zak.sh); usage: zak.py STEP."""
import os
import sys
sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
import numpy as np
from scene_check import group, main, require


def low_energy():
    """E* = 0.01, 0.1: phi_0 = 0, phi_pi = pi, theta = pi; 1 and 2 ranks give the same numbers."""
    a, b = group("z1.h5", "zak"), group("z2.h5", "zak")
    for k in ("energy", "phi0_mean", "phi0_median", "phipi_mean", "phipi_median"):
        require(a[k].shape == (2,), k)
        require(np.array_equal(a[k][:], b[k][:]), "np1 vs np2", k)
    require("energy_threshold" in a.attrs)
    require((np.abs(a["phi0_median"][:]) < 0.05).all(), a["phi0_median"][:])
    require((np.abs(a["phipi_median"][:] - np.pi) < 0.05).all(), a["phipi_median"][:])
    require((np.abs(a["phi0_mean"][:]) < 0.2).all() and (np.abs(a["phipi_mean"][:] - np.pi) < 0.2).all())
    require((np.abs(a["theta_median"][:] - np.pi) < 0.05).all())
    require(a.attrs["energy_threshold"] == -1)  # distinct over this low-energy range
    print("zak scene OK: phi_0 median", a["phi0_median"][:], "phi_pi median", a["phipi_median"][:])


def threshold():
    """E* = 5..40, 7 energies log-spaced: the threshold where theta leaves pi lies between 10 and 30.

    docs/studies/zak.md (options/zak.opts, 31 energies): the pi/4 rule puts the threshold between 31.6 and 46.4, the means drift from 10-15;
    the paper reads E ~ 12. Measured on this grid (5, 7.07, 10, 14.1, 20, 28.3, 40): theta of the means
    2.96 2.93 2.80 2.68 2.50 1.98 2.04, threshold 28.3 (last distinct 20). The bracket 10 < E_th < 30 allows
    one grid step (a factor 1.41) either way of both readings and excludes "never" (-1) and "at once" (5)."""
    z = group("zt.h5", "zak")
    e, th = z["energy"][:], z.attrs["energy_threshold"]
    require(e.shape == (7,) and abs(e[0] - 5) < 1e-12 and abs(e[-1] - 40) < 1e-9, e)
    require(10 < th < 30, th)
    i = int(np.argmin(np.abs(e - th)))
    require(abs(e[i] - th) < 1e-9 * th and abs(z.attrs["energy_last_distinct"] - e[i - 1]) < 1e-9 * th)   # grid points
    tol = z.attrs["theta_tol"]
    dist = np.maximum(np.abs(z["theta_mean"][:] - np.pi), np.abs(z["theta_median"][:] - np.pi))
    require((dist[:i] <= tol).all() and dist[i] > tol, dist, tol)   # the rule: the first E* where theta leaves pi by > pi/4
    print("zak threshold: E* = %.4g (last distinct %.4g); theta of the means" % (th, z.attrs["energy_last_distinct"]), np.round(z["theta_mean"][:], 3))


def interrupted():
    """Issue 34, class 9: the interrupted scan's partial output (zi.h5.partial.h5): complete = 0, some runs not done, the
    threshold not determined (NaN) and energy_last_distinct below the first energy not run."""
    from scene_check import complete
    require(complete("zi.h5.partial.h5") == 0)
    z = group("zi.h5.partial.h5", "zak")
    done, e = z["done"][:], z["energy"][:]
    require(done.shape == (400, 2) and 0 < done.sum() < done.size, done.sum())
    require(np.isnan(z.attrs["energy_threshold"]), z.attrs["energy_threshold"])
    first_missing = e[(done == 0).any(axis=1)].min()
    require(z.attrs["energy_last_distinct"] < first_missing, z.attrs["energy_last_distinct"], first_missing)
    print("zak interrupted: %d of %d runs done, threshold not determined above E = %.4g" % (done.sum(), done.size, first_missing))


if __name__ == "__main__":
    main(globals())
