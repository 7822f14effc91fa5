#!/usr/bin/python3
"""Checks of the signals scene (tests/scenes/signals.sh); usage: signals.py STEP [ARGUMENTS]."""
import os
import sys
sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
from scene_check import complete, group, main, require, same


def elapsed(t0, t1):
    """Print t1 - t0 (seconds since the epoch, date +%s.%N) to 0.01 s."""
    print(round(float(t1) - float(t0), 2))


def partial(path):
    """An interrupted run's output is marked complete = 0."""
    require(complete(path) == 0, path)


def complete_output(path):
    """A run that finished (e.g. with its stdout closed under it) leaves its output complete = 1."""
    require(complete(path) == 1, path)


def branch_points(path, label):
    """Print how many points branch label of the continuation output path holds."""
    print(int(group(path, "continuation/" + label)["energy"].shape[0]))


def done_points(path):
    """Print how many points of the sweep in path are done."""
    print(int(group(path, "sweep/done")[:].sum()))


def sweep_resumed(done_before):
    """The 2-rank sweep stopped by SIGTERM after done_before of its 32 points and resumed: complete, equal to
    the uninterrupted sweep bit for bit, only the missing points computed."""
    a, f = group("sw_full.h5"), group("sw_int.h5")
    require(complete("sw_full.h5") == 1 and complete("sw_int.h5") == 1)
    s, r = a["sweep"], f["sweep"]
    for k in ("mcr", "t_off", "kcorr", "nl_ratio", "done", "reached", "amplitude", "energy_final", "rescalings", "rhs_evals", "steps"):
        require(same(s[k], r[k]), "interrupted + resumed vs uninterrupted", k)
    n0 = int(done_before)
    require(r.attrs["points_computed"] == 32 - n0, r.attrs["points_computed"], n0)
    print("sweep: SIGTERM after %d of 32 points, resume computed %d; mcr, t_off, kcorr, nl_ratio equal bit for bit" % (n0, 32 - n0))


def branch_resumed(full, resumed, *keys):
    """The continuation stopped by SIGTERM and resumed: complete, its insulated branch's datasets keys equal
    to the uninterrupted run's bit for bit."""
    a, b = group(full), group(resumed)
    require(complete(resumed) == 1)
    x, y = a["continuation/insulated"], b["continuation/insulated"]
    for k in keys:
        require(same(x[k], y[k]), "resumed vs uninterrupted", k, x[k].shape, y[k].shape)
    print("%s: %d points, %s equal bit for bit" % (resumed, x["energy"].shape[0], ", ".join(keys)))


def first_case_kept():
    """The stability study stopped by SIGTERM during its second case keeps the first."""
    s = group("st_int.h5.partial.h5", "stability")
    require(list(s.keys()) == ["case0"] and s.attrs["cases_done"] == 1)


if __name__ == "__main__":
    main(globals())
