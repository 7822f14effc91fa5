#!/usr/bin/python3
"""Adaptive refinement against a uniform grid at the same number of points (issue 36 acceptance,
benchmarks/README.md "Adaptive refinement"). On the window omega in [1.6, 2.1], E* in [1, 100] (log):

  sweep_refine_compare.py run NLTOPO BUDGET BASE_N OUT_PREFIX [extra nltopo options]
      a uniform BASE_N x BASE_N grid, then refinement levels (-sweep_refine_from, each capped by
      -sweep_refine_max_points to the budget left) until BUDGET points or no cell over the thresholds;
      prints the last level's file.
  sweep_refine_compare.py compare REFERENCE UNIFORM REFINED
      mean absolute MCR error over the reference's predictable points of the uniform map and of the
      refined map, each interpolated linearly on its triangulation in (omega, log10 E*)
      (matplotlib.tri.LinearTriInterpolator)."""
import os
import subprocess
import sys
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "python"))
import numpy as np
import nltopo

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..")
WINDOW = ["-sweep_omega_min", "1.6", "-sweep_omega_max", "2.1", "-sweep_energy_min", "1", "-sweep_energy_max", "100",
          "-sweep_kcorr", "0", "-sweep_mcr_tol", "1e-3", "-sweep_progress", "60"]


def run(nltopo_bin, budget, base_n, prefix, *extra):
    mpi = ["nice", "-n", "5", "mpiexec", "-n", "2", nltopo_bin, "-options_file", os.path.join(ROOT, "options/sweep_paper.opts")] + WINDOW + list(extra)
    out = "%s_l0.h5" % prefix
    subprocess.run(mpi + ["-sweep_omega_n", base_n, "-sweep_energy_n", base_n, "-output", out], check=True)
    total, level = int(base_n) ** 2, 0
    while total < int(budget):
        level += 1
        nxt = "%s_l%d.h5" % (prefix, level)
        subprocess.run(mpi + ["-sweep_omega_n", base_n, "-sweep_energy_n", base_n, "-sweep_refine_from", out,
                              "-sweep_refine_max_points", str(int(budget) - total), "-output", nxt], check=True)
        new = int(nltopo.Run(nxt).sweep.refined.attrs["points_new"])
        out, total = nxt, total + new
        if new == 0:
            break
    print("refined: %s, %d points, %d levels" % (out, total, level))


def samples(path):
    s = nltopo.Run(path).sweep
    if s.refined is not None:
        r = s.refined
        return np.asarray(r["omega"]), np.asarray(r["energy"]), np.asarray(r["mcr"])
    e, w = s.axes
    W, E = np.meshgrid(w, e)
    return W.ravel(), E.ravel(), np.asarray(s["mcr"]).ravel()


def error(path, ref):
    import matplotlib.tri as mtri
    w, e, m = samples(path)
    ok = np.isfinite(m)
    tri = mtri.Triangulation(w[ok], np.log10(e[ok]))
    f = mtri.LinearTriInterpolator(tri, m[ok])
    rw, re, rm, rp = ref
    v = np.asarray(f(rw, np.log10(re)))
    good = np.isfinite(v)
    return float(np.mean(np.abs(v[good] - rm[good]))), int(good.sum()), len(m)


def compare(reference, uniform, refined):
    s = nltopo.Run(reference).sweep
    e, w = s.axes
    W, E = np.meshgrid(w, e)
    p = np.asarray(s["predictable"]).ravel() == 1
    ref = (W.ravel()[p], E.ravel()[p], np.asarray(s["mcr"]).ravel()[p], None)
    eu, nu, pu = error(uniform, ref)
    er, nr, pr = error(refined, ref)
    print("reference %s: %d predictable points of %d" % (reference, p.sum(), p.size))
    print("uniform  %s: %d points, mean |MCR error| %.4e over %d reference points" % (uniform, pu, eu, nu))
    print("refined  %s: %d points, mean |MCR error| %.4e over %d reference points" % (refined, pr, er, nr))
    print("refined < uniform: %s (ratio %.3f)" % (er < eu, er / eu))


if __name__ == "__main__":
    {"run": run, "compare": compare}[sys.argv[1]](*sys.argv[2:])
