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


def corrupt(source, group_name, *changes):
    """Issue 34, class 7: for each change "dataset=value", a copy of source named <stem>_<dataset>_<value>.h5
    (stem: source's name without .h5) with the last value of group_name/dataset set to value (nan, inf, -1, ...)."""
    import shutil
    for change in changes:
        dataset, value = change.split("=")
        path = "%s_%s_%s.h5" % (source[:-3], dataset, value)
        shutil.copyfile(source, path)
        with h5py.File(path, "r+") as f:
            d = f[group_name + "/" + dataset]
            a = d[...]
            require(a.size > 0, "%s of %s is empty" % (dataset, source))
            a.flat[-1] = float(value)
            d[...] = a


SWEEP_REALS = ["mcr", "t_off", "kcorr", "nl_ratio", "amplitude", "energy_final", "seconds", "mcr_error", "mcr_spread", "mcr_dt", "lyapunov", "lyapunov_half"]
SWEEP_INTS = ["reached", "rescalings", "rhs_evals", "steps", "failed", "predictable", "mcr_runs", "regime"]


def journal(source, *changes):
    """Issue 34, class 7: for each change "field=value", a copy of the sweep source named
    jbad_<field>_<value>.h5 whose first point is taken out (done = 0) and written as the line of a journal
    left by a killed run (<copy>.journal.0, the format of studies/sweep_store.cpp), with field set to value."""
    import shutil

    def text(x):
        return x.hex() if x == x and abs(x) != float("inf") else ("nan" if x != x else ("inf" if x > 0 else "-inf"))
    for change in changes:
        field, value = change.split("=")
        path = "jbad_%s_%s.h5" % (field, value)
        shutil.copyfile(source, path)
        with h5py.File(path, "r+") as f:
            g = f["sweep"]
            row = ["0"] + [text(float(value) if r == field else float(g[r][0, 0])) for r in SWEEP_REALS]
            row += [value if i == field else str(int(g[i][0, 0])) for i in SWEEP_INTS]
            d = g["done"][...]
            d[0, 0] = 0
            g["done"][...] = d
        with open(path + ".journal.0", "w") as j:
            j.write(" ".join(row) + "\n")


if __name__ == "__main__":
    main(globals())
