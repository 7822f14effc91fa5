#!/usr/bin/python3
"""Checks of the mpi_small scene (tests/scenes/mpi_small.sh); usage: mpi_small.py STEP."""
import glob
import os
import sys
sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
import numpy as np
from scene_check import group, main, require


def ranks_agree():
    """Simulate and linear on 3 ranks (and simulate on 4) equal 1 rank for every layout."""
    for f1 in sorted(glob.glob("s1_*.h5")):
        a, b = group(f1, "simulate"), group(f1.replace("s1_", "s3_"), "simulate")
        require(abs(a.attrs["mcr"] - b.attrs["mcr"]) < 1e-10, f1, a.attrs["mcr"], b.attrs["mcr"])
        require(np.abs(a["rms"][:] - b["rms"][:]).max() < 1e-10, f1)
    for f1 in sorted(glob.glob("l1_*.h5")):
        a, b = group(f1, "linear"), group(f1.replace("l1_", "l3_"), "linear")
        require(np.abs(a["omega"][:] - b["omega"][:]).max() < 1e-12, f1)
    c = group("s4.h5", "simulate").attrs["mcr"]
    require(abs(c - group("s1_interface_2.h5", "simulate").attrs["mcr"]) < 1e-10)
    print("3 and 4 ranks agree with 1 rank")


if __name__ == "__main__":
    main(globals())
