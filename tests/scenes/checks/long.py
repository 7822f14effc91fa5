#!/usr/bin/python3
"""Checks of the long scene (tests/scenes/long.sh); usage: long.py STEP."""
import os
import sys
sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
import numpy as np
from scene_check import group, main, require


def long_vs_short():
    """N = 1002 on 2 ranks (u at every 10th site) against N = 102: the same cut-off, the same RMS near the interface."""
    L, S = group("long.h5", "simulate"), group("short.h5", "simulate")
    require(L["u"].shape == (1001, 101) and L.attrs["u_stride"] == 10)
    a, b = L.attrs, S.attrs
    require(abs(a["t_off"] - b["t_off"]) < 1e-3 * b["t_off"], a["t_off"], b["t_off"])
    rl, rs = L["rms"][:], S["rms"][:]
    ml, ms = 2 * 250, 2 * 25                       # interface site m (0-based)
    near_l, near_s = rl[ml - 10:ml + 11], rs[ms - 10:ms + 11]
    err = np.abs(near_l - near_s).max() / near_s.max()
    require(err < 1e-3, err)
    print("long (N = 1002, 2 ranks) vs short (N = 102): t_off", a["t_off"], b["t_off"], "RMS near the interface rel. diff", err)


if __name__ == "__main__":
    main(globals())
