#!/usr/bin/python3
"""Checks of the sweep scene (tests/scenes/sweep.sh); usage: sweep.py STEP [ARGUMENTS]."""
import os
import sys
sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
import numpy as np
from scene_check import group, main, require, same


def killed_readable():
    """The sweep killed with SIGKILL: its partial output (killed.h5 itself is never written before the
    end) is readable, with points still missing."""
    require(not os.path.exists("killed.h5"))
    d = group("killed.h5.partial.h5", "sweep/done")[:]   # a complete, readable file at any moment
    print("killed sweep: file readable,", int(d.sum()), "of", d.size, "points in the HDF5 file")
    require(d.sum() < d.size, "the sweep finished before it was killed: nothing to test")


def grid_value(axis, index):
    """Print an axis value of the grid (omega or energy at index) for the shell."""
    print(repr(float(group("full1.h5", "sweep")[axis][int(index)])))


def grid():
    """outputs.md /sweep; np1 = np2 = killed + resumed bit for bit, the resume recomputing only the missing
    points; a grid point = the simulate study's run; the 0-1 test at regular and chaotic points."""
    f1, f2, fk = (group(n, "sweep") for n in ("full1.h5", "full2.h5", "killed.h5"))
    no, ne = 4, 4
    for k, shape in (("omega", (no,)), ("energy", (ne,)), ("mcr", (ne, no)), ("t_off", (ne, no)), ("kcorr", (ne, no)),
                     ("nl_ratio", (ne, no)), ("done", (ne, no))):
        require(f1[k].shape == shape, k, f1[k].shape)
    require(f1["done"][:].all() and f1["reached"][:].all())
    require(abs(f1["omega"][0] - np.sqrt(3) / 2) < 1e-12 and abs(f1["energy"][-1] - 100) < 1e-9)
    phys = ("mcr", "t_off", "kcorr", "nl_ratio", "done", "reached", "amplitude", "energy_final", "rescalings", "rhs_evals", "steps")
    for k in phys:
        require(same(f1[k], f2[k]), "np1 vs np2", k)
        require(same(f1[k], fk[k]), "uninterrupted vs resumed", k)
    done_before = int(open("resumed.txt").read().split("resuming killed.h5.partial.h5: ")[1].split()[0])
    require(fk.attrs["points_computed"] == 16 - done_before, fk.attrs["points_computed"], done_before)
    print("resume recomputed", fk.attrs["points_computed"], "of 16 points; grid equal bit for bit (np1, np2, killed + resumed)")
    # the sweep's point equals the simulate study's run
    p = group("point.h5", "simulate").attrs
    for k, kk in (("mcr", "mcr"), ("t_off", "t_off"), ("nl_ratio", "nl_ratio"), ("amplitude", "amplitude")):
        require(f1[k][3, 2] == p[kk], k, f1[k][3, 2], p[kk])
    print("sweep point (E* = %g, omega = %g) == simulate: MCR %.10f" % (f1["energy"][3], f1["omega"][2], p["mcr"]))
    # the quartic share of the potential energy grows with E* at every frequency, and is tiny at E* = 1e-2
    nl = f1["nl_ratio"][:]
    require((nl[0] < 1e-3).all() and (nl[-1] > 10 * nl[0]).all(), nl)
    # The 0-1 test, two-sided (the paper's threshold is 0.7; a regular signal scores ~0, a chaotic one ~1).
    # Measured with -kcorr_record 1500 (the default): the E* = 1e-2 row 0.11 0.29 0.43 0.28, the omega = 0.866
    # column (below the acoustic band: a quasi-static, linear response) 0.11 at E* = 1e-2 and 0.13 at 0.22;
    # omega = 2.02 (optical band) at E* = 100: 0.97; kc.h5: sqrt(3) at 1e-2 0.08, 2.1 at E* = 200 0.99.
    # The bars leave >= 0.17 to every measured value: a nearly linear run's score depends on the record
    # (benchmarks/README.md: 0.39 over 1500 s, 0.06 over 3000 s at E* = 1e-3), a chaotic run's does not (0.93-0.99).
    k = f1["kcorr"][:]
    require((k[0] < 0.7).all(), k[0])                        # the nearly linear row: nowhere chaotic
    require((k[:2, 0] < 0.3).all(), k[:2, 0])                # regular: below the acoustic band, E* <= 0.2
    require(abs(f1["omega"][2] - 2.0207) < 1e-4 and k[3, 2] > 0.7, k[3, 2])   # chaotic: optical band, E* = 100
    kc = group("kc.h5", "sweep")
    require(kc["reached"][:].all() and kc["energy"][1] == 200 and abs(kc["omega"][1] - 2.1) < 1e-12)
    require(kc["kcorr"][0, 0] < 0.3, kc["kcorr"][:])         # the insulated mode at E* = 1e-2: periodic (MCR 0.345)
    require(abs(kc["mcr"][0, 0] - 0.345) < 0.01, kc["mcr"][0, 0])   # ... and it is the localised mode (linear MCR 0.345)
    require(kc["kcorr"][1, 1] > 0.7, kc["kcorr"][:])         # omega = 2.1 (optical band 1.95-2.24) at E* = 200: chaotic
    print("kcorr: regular %.3f %.3f %.3f (< 0.3), chaotic %.3f %.3f (> 0.7)" % (k[0, 0], k[1, 0], kc["kcorr"][0, 0], k[3, 2], kc["kcorr"][1, 1]))
    # -sweep_lyapunov at the same two points: the periodic response grows its tangent vector by less than e^1 over the
    # window (lambda x window; regular motion: polynomially), the chaotic one by e^70 (lambda ~ 0.1 per unit time), converged
    # to 10 % between the window's first half and the whole; regime 0 and 1 (chaotic; not checked for predictability)
    lam, half, reg = kc["lyapunov"][:], kc["lyapunov_half"][:], kc["regime"][:]
    window = 1000 - kc["t_off"][:]
    require(abs(lam[0, 0] * window[0, 0]) < 1 and reg[0, 0] == 0, lam, reg)
    require(lam[1, 1] * window[1, 1] > 40 and abs(lam[1, 1] - half[1, 1]) < 0.1 * lam[1, 1] and reg[1, 1] == 1, lam, half, reg)
    require(kc.attrs["lyapunov_computed"] == 1 and (reg >= 0).all(), reg)
    print("lyapunov x window: regular %.2f, chaotic %.1f (first half %.4f, whole %.4f)" % (lam[0, 0] * window[0, 0], lam[1, 1] * window[1, 1],
                                                                                       half[1, 1], lam[1, 1]))


def groups():
    """-sweep_group_size 2 on 2 ranks equals the 1-rank map to rounding (issue 36: 1e-10 relative)."""
    a, b = group("grp1.h5", "sweep"), group("grp2.h5", "sweep")
    require(a["done"][:].all() and b["done"][:].all())
    worst = 0
    for k in ("mcr", "t_off", "nl_ratio", "energy_final", "amplitude", "lyapunov", "lyapunov_half"):
        x, y = a[k][:], b[k][:]
        d = np.max(np.abs(x - y) / np.maximum(np.abs(x), 1e-300))
        require(d < 1e-10 or np.max(np.abs(x - y)) < 1e-14, k, x, y)
        worst = max(worst, d)
    require((a["regime"][:] == b["regime"][:]).all() and (a["steps"][:] == b["steps"][:]).all())
    print("rank groups: 1 rank vs groups of 2, largest relative difference %.1e" % worst)


def failed_points():
    """A softening lattice diverging at E* = 50: those points flagged failed (mcr NaN), the others computed."""
    s = group("fail.h5", "sweep")
    require((s["failed"][:] == [[0, 0], [1, 1]]).all() and s["done"][:].all())
    require(np.isfinite(s["mcr"][0]).all() and np.isnan(s["mcr"][1]).all())
    print("failed points flagged:", s["failed"][:].tolist())


def damped():
    """Damping c = 0.01 is honoured by the sweep: after the cut-off every point loses energy, at least as
    exp(-2 c (t_final - t_off)) allows and no slower than the virial bound exp(-c (t_final - t_off))
    (checks/simulate.py damped)."""
    s = group("damped.h5", "sweep")
    E, ef, toff = s["energy"][:], s["energy_final"][:], s["t_off"][:]
    dt = 1000 - toff
    require((toff > 0).all(), toff)
    r = ef / E[:, None]
    require((r > np.exp(-0.02 * dt)).all() and (r < 1.02 * np.exp(-0.01 * dt)).all(), r)
    print("damped sweep: E_final / E* =", r.round(4).tolist())


if __name__ == "__main__":
    main(globals())
