#!/usr/bin/python3
"""Checks of the perturb scene (tests/scenes/perturb.sh); usage: perturb.py STEP."""
import os
import sys
sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
import numpy as np
from scene_check import group, main, require


def ensemble():
    """A small ensemble (delta = 0, 0.05; 3 seeds; E* = 0.1): chiral realisations keep the insulated frequency at
    sqrt(3) (to the 1e-8 hybridisation with the end mode), achiral ones move it; delta = 0 is the unperturbed
    lattice for every seed; 1 and 2 ranks (omega(E) computed, or read from a continuation file) agree."""
    f1, f2 = group("p1.h5", "perturb"), group("p2.h5", "perturb")
    for kind in ("chiral", "achiral"):
        a, b = f1[kind], f2[kind]
        require(a["mcr"].shape == (2, 1, 3) and a["insulated_omega"].shape == (2, 3) and a["delta"].shape == (2,))
        require(np.array_equal(a["insulated_omega"][:], b["insulated_omega"][:]), "np1 vs np2", kind)
        # the two routes to omega(E) interpolate different orbits of the same branch
        require(np.abs(a["omega_ext"][:] - b["omega_ext"][:]).max() < 1e-6, a["omega_ext"][:], b["omega_ext"][:])
        require(np.abs(a["mcr"][:] - b["mcr"][:]).max() < 1e-3)
        m = a["mcr"][:]
        require((m[0] == m[0, 0, 0]).all(), "delta = 0: every seed is the same lattice")
        require(0.3 < m[0, 0, 0] < 0.4, m[0, 0, 0])          # the insulated mode is excited
    w = f1["chiral/insulated_omega"][:]
    require((np.abs(w - np.sqrt(3)) < 1e-8).all(), w - np.sqrt(3))
    wa = f1["achiral/insulated_omega"][:]
    require((np.abs(wa[1] - np.sqrt(3)) > 1e-4).all(), wa[1] - np.sqrt(3))
    require(np.array_equal(f1["chiral/mcr"][0], f1["achiral/mcr"][0]))
    print("perturb scene OK: chiral omega - sqrt 3", np.abs(w - np.sqrt(3)).max(), "achiral", wa[1] - np.sqrt(3))


if __name__ == "__main__":
    main(globals())
