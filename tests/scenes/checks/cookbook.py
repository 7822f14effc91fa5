#!/usr/bin/python3
"""Checks of the cookbook scene (tests/scenes/cookbook.sh): one step per line of
README.md's cookbook, each reading one meaningful value of what the line wrote;
usage: cookbook.py STEP STDOUT_FILE FILES_BEFORE_FILE (the line's output and the
listing of the work directory before it ran)."""
import math
import os
import shutil
import sys
sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
import numpy as np
from scene_check import attr_str, complete, group, main, require, same


def _simulate(path):
    return group(path, "simulate").attrs


def _given(path, option, value):
    """The run of path was given option with value (root attribute options)."""
    words = attr_str(group(path), "options").split()
    return any(a == option and b == value for a, b in zip(words, words[1:]))


def forced(out, before):
    """-force_omega 2 -force_energy 10: the run forced at 2 reached E* = 10 (the amplitude rule rescaled S)."""
    a = _simulate("simulate.h5")
    require(a["omega_ext"] == 2.0 and a["energy_star"] == 10.0, a["omega_ext"], a["energy_star"])
    require(a["energy_reached"] == 1 and abs(a["energy_final"] / 10.0 - 1) < 1e-3, a["energy_final"])
    require(0 < a["mcr"] <= 1, a["mcr"])


def gamma_cubic(out, before):
    """-lattice_gamma 0.3 -lattice_cubic 1: given and read, and the run differs from the default lattice's."""
    require(_given("gamma03.h5", "-lattice_gamma", "0.3") and _given("gamma03.h5", "-lattice_cubic", "1"))
    a = _simulate("gamma03.h5")
    require(a["energy_reached"] == 1 and 0 < a["mcr"] <= 1, a["energy_reached"], a["mcr"])
    require(abs(a["mcr"] - 0.3465) > 1e-3, "the default lattice's MCR is 0.3465", a["mcr"])


def damped(out, before):
    """-lattice_damping 0.01 with rk: the energy decays after the cut-off (e^{-c t} over ~500 time units), rk ran."""
    S = group("damped.h5", "simulate")
    E, Es = S["energy"][()], S.attrs["energy_star"]
    require(S.attrs["energy_reached"] == 1 and E[-1] < 0.1 * Es, E[-1], Es)
    require(attr_str(group("damped.h5", "cost"), "sim_integrator").startswith("rk"))


def workprecision(out, before):
    """The work-precision table: at least 3 configurations with finite MCR errors, the cheapest configuration
    meeting -wp_target 1e-6 for the MCR (printed and written), and its figure."""
    W = group("workprecision.h5", "workprecision")
    err = W["error_mcr"][()]
    require(len(err) >= 3 and np.isfinite(err).all() and (err < 1e-3).all(), err)
    R = W["recommended"]
    k = [o.decode() for o in R["observable"][()]].index("mcr")
    best = R["config"][k].decode()
    text = open(out).read()
    require(best and R["error"][k] <= 1e-6 and "cheapest configuration" in text and best in text, best)
    require(os.path.getsize("workprecision_workprecision.png") > 10000)


def branch(out, before):
    """-cont_energy_max 10 is a stop test: the last point lies past 10, the one before below it."""
    E = group("insulated.h5", "continuation/insulated")["energy"][()]
    require(E[-1] >= 10 and E[-2] < 10, E[-3:])
    require(attr_str(group("insulated.h5", "continuation/insulated"), "stop_reason") == "reached -cont_energy_max")
    shutil.copy("insulated.h5", "insulated_to10.h5")  # the resume step compares against it


def resume(out, before):
    """-cont_resume extends the branch to 30: its first points are the earlier run's bit for bit."""
    old = group("insulated_to10.h5", "continuation/insulated")
    new = group("insulated.h5", "continuation/insulated")
    n = len(old["energy"])
    E = new["energy"][()]
    require(E[-1] >= 30 and E[-2] < 30 and len(E) > n, E[-3:], n)
    for k in ("energy", "omega", "z0"):
        require(same(old[k], new[k][:n]), k)
    require(complete("insulated.h5") == 1)


def fast_fep(out, before):
    """-floquet 0: all five branches to E = 1e3, without Floquet datasets."""
    C = group("fep.h5", "continuation")
    names = sorted(C.keys())
    require(names == sorted(["insulated", "interface", "acoustic_top", "optical_bottom", "optical_top"]), names)
    for b in names:
        require(C[b]["energy"][-1] >= 1e3, b, C[b]["energy"][-1])
        require("multipliers_re" not in C[b], b)


def sweep_overlay(out, before):
    """The quick sweep on 2 ranks: every point done and scored; its map drawn with the FEP."""
    S = group("sweep_quick.h5", "sweep")
    require(S["mcr"].shape == (6, 8) and (S["done"][()] == 1).all())
    require(np.isfinite(S["mcr"][()]).all() and np.isfinite(S["kcorr"][()]).all())
    require(os.path.getsize("sweep_quick_map.png") > 10000)


def ranks(out, before):
    """zak.opts on 2 ranks: the linear phases 0 and pi, and a threshold energy between 10 and 100."""
    Z = group("zak.h5", "zak")
    require(abs(Z["phi0_median"][0]) < 0.01 and abs(Z["phipi_median"][0] - math.pi) < 0.01, Z["phi0_median"][0], Z["phipi_median"][0])
    require(10 < Z.attrs["energy_threshold"] < 100, Z.attrs["energy_threshold"])


def long(out, before):
    """simulate_long.opts at N = 10^4 (the size override): the insulated mode's MCR, as at N = 102."""
    S = group("simulate_long.h5", "simulate")
    require(S["rms"].shape == (10002,), S["rms"].shape)
    require(S.attrs["energy_reached"] == 1 and abs(S.attrs["mcr"] - 0.3465) < 2e-3, S.attrs["mcr"])


def figures(out, before):
    """make_all.sh (Fig. 2 at the test size): the figure and the timing table, no failure."""
    require(os.path.getsize("figs/fig2_linear_modes.png") > 10000)
    require(os.path.exists("figs/timings.md"))


def python(out, before):
    """The Python line prints the MCR that simulate.h5 holds."""
    printed = float(open(out).read().split()[-1])
    require(printed == _simulate("simulate.h5")["mcr"], printed)


def help(out, before):
    """-help lists the study's options with their values and writes no file."""
    text = open(out).read()
    require("-force_omega <" in text and "-sim_ts_*" in text and "(None)" not in text)
    require(sorted(os.listdir(".")) == sorted(open(before).read().split() + [os.path.basename(out)]),
            "-help wrote a file", sorted(set(os.listdir(".")) - set(open(before).read().split())))


def log_view(out, before):
    """-log_view: the stage and kernel table on stdout, and the run's output."""
    text = open(out).read()
    require("Solve" in text and "RhsLinear" in text)
    require(_simulate("logview.h5")["energy_reached"] == 1)


if __name__ == "__main__":
    main(globals())
