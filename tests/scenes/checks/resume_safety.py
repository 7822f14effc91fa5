#!/usr/bin/python3
"""Checks of the resume_safety scene (tests/scenes/resume_safety.sh); usage: resume_safety.py STEP FILE."""
import os
import sys
sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
import h5py
from scene_check import attr_str, complete, group, main, require, study_of


def code_default_changed(path):
    """Make path a file written when the code default was -nnm_ts_type rk: its effective options (which
    include the defaults) with -nnm_ts_type symsplit replaced."""
    with h5py.File(path, "r+") as f:
        e = attr_str(f, "effective_options")
        require("-nnm_ts_type symsplit\n" in e and "-lattice_k 1\n" in e, e)   # defaults included
        f.attrs["effective_options"] = e.replace("-nnm_ts_type symsplit", "-nnm_ts_type rk")


def resumed(path):
    """The resumed continuation: complete, with more than the 3 points it was given."""
    require(complete(path) == 1 and group(path, "continuation/insulated").attrs["points"] > 3)


def study(path):
    """Print the study that wrote path, for the shell."""
    print(study_of(path))


def format_version_0(path):
    """Makes path a format-0 file: no format_version attribute (as files written before it existed)."""
    with h5py.File(path, "a") as f:
        require("format_version" in f.attrs)
        del f.attrs["format_version"]


if __name__ == "__main__":
    main(globals())
