#!/usr/bin/python3
"""Checks of the continuation scene (tests/scenes/continuation.sh); usage: continuation.py STEP."""
import os
import sys
sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
import numpy as np
from scene_check import attr_str, complete, group, main, require


def branches():
    """options/fep.opts at low energy: the five branches start at their linear frequencies (lin.h5), outputs.md
    /continuation, det M = 1, 1 and 2 ranks agree."""
    lin = group("lin.h5", "linear").attrs
    f, g = group("fep1.h5"), group("fep2.h5")
    require(attr_str(f, "study") == "continuation")
    N = 102
    expect = {"insulated": lin["insulated_omega"], "interface": lin["interface_omega"], "acoustic_top": lin["acoustic_top"],
              "optical_bottom": lin["optical_bottom"], "optical_top": lin["optical_top"]}
    for name, w_lin in expect.items():
        b = f["continuation/" + name]
        n = b["energy"].shape[0]
        for d in ("energy", "omega", "period", "mcr", "newton_its"):
            require(b[d].shape == (n,), name, d)
        require(b["z0"].shape == (n, 2 * N))
        require(b.attrs["reached_energy_max"] == 1, name)
        require(abs(b["energy"][0] - 1e-5) < 1e-11)
        require(abs(b["omega"][0] - w_lin) < 1e-6 * w_lin, name, b["omega"][0], w_lin)
        require(np.allclose(b["period"][:] * b["omega"][:], 2 * np.pi))
        for d in ("multipliers_re", "multipliers_im", "krein"):
            require(b[d].shape == (n, 2 * N), name, d)
        require(b["krein"].dtype.kind == "i" and b["stable"].dtype.kind == "i" and b["instability"].dtype.kind == "i")
        require(b["stable"][0] == 1 and abs(b["max_modulus"][0] - 1) < 1e-6, name)   # the linear limit is stable
        # fep.opts shoots with the symplectic splitting: det M = 1 to rounding (Liouville), on 1 and 2 ranks
        for h in (b, g["continuation/" + name]):
            require(h["det_error"].shape == (n,) and h["det_error"][:].max() < 1e-12, name, h["det_error"][:].max())
        c = g["continuation/" + name]
        require(c["energy"].shape == (n,), name)
        require(np.abs(c["omega"][:] - b["omega"][:]).max() < 1e-9, name)
        print(name, "starts at", b["omega"][0], "linear", w_lin)
    print("continuation scene OK")


def mcr_min():
    """-cont_mcr_min 0.3 stops the insulated branch where it delocalizes: at N = 102 its MCR (0.345 for the
    linear mode) falls below 0.3 only as omega nears the optical band bottom (sqrt(3.8) = 1.94936), the
    paper's E ~ 12 threshold."""
    b = group("mcr.h5", "continuation/insulated")
    m, w, e = b["mcr"][:], b["omega"][:], b["energy"][:]
    reason = attr_str(b, "stop_reason")
    require("-cont_mcr_min" in reason and b.attrs["reached_energy_max"] == 0, reason)
    require(m[-1] < 0.3 and np.all(m[:-1] >= 0.3), m)
    require(1.93 < w[-1] < np.sqrt(3.8) + 0.01 and 8 < e[-1] < 13, w[-1], e[-1])
    print("-cont_mcr_min: stopped at E = %.3g, omega %.5f, MCR %.3f" % (e[-1], w[-1], m[-1]))


def killed_checkpoint():
    """A run killed mid-branch (SIGKILL): its checkpoint ck.h5.partial.h5 readable, its points consistent
    across datasets, complete = 0, and no ck.h5; the finished runs complete = 1."""
    require(complete("ck.h5.partial.h5") == 0 and not os.path.exists("ck.h5"))
    b = group("ck.h5.partial.h5", "continuation/insulated")
    n = b.attrs["points"]
    require(n >= 3 and b["energy"].shape == (n,) and b["z0"].shape == (n, 204) and b["multipliers_re"].shape == (n, 1) and b["stable"].shape == (n,))
    require("checkpoint" in attr_str(b, "stop_reason"))
    require(complete("fep1.h5") == 1 and complete("mcr.h5") == 1)
    print("checkpoint of a killed run:", n, "points, complete = 0")


def final_checkpoint():
    """The 2-rank run with checkpoints, run to its end: the final file, complete = 1; its checkpoint removed."""
    require(not os.path.exists("ck2.h5.partial.h5"))
    b = group("ck2.h5", "continuation/insulated")
    require(complete("ck2.h5") == 1 and b.attrs["reached_energy_max"] == 1 and b["multipliers_re"].shape == (b.attrs["points"], 1))
    print("2-rank checkpoints, then the complete file:", b.attrs["points"], "points")


if __name__ == "__main__":
    main(globals())
