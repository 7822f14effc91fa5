#!/usr/bin/python3
"""The stability verdicts of options/fep_long.opts on a shortened lattice,
against the full dense Floquet analysis of the same orbits (issue 20).

Usage: floquet_verdicts.py BUILD_DIR [cells] [energy_max] [ranks]
Runs fep_long.opts with -lattice_cells cells to energy_max three ways:
  lead  -floquet_mf as shipped (the dense leading pairs where 2N <= -floquet_mf_dense_max),
  full  -floquet_mf 0 (every multiplier, eigenvector and Krein signature),
  mf    -floquet_mf_dense_max 0 (matrix-free),
then prints one line per orbit (E, omega, the full analysis' largest
nontrivial |mu|, the leading pair's, their difference, the three verdicts
and the two classes) and a summary: largest difference, orbits with the same
verdict and class, verdicts per route, wall time per route.
Default: cells 25, E 20, 1 rank (the scene test long_nnm checks the same at
N = 102 on 2 ranks). docs/long-lattices.md quotes cells 25 to E = 100."""
import os
import subprocess
import sys
import tempfile
import time

import h5py
import numpy as np

build = sys.argv[1]
cells = sys.argv[2] if len(sys.argv) > 2 else "25"
emax = sys.argv[3] if len(sys.argv) > 3 else "20"
ranks = int(sys.argv[4]) if len(sys.argv) > 4 else 1
src = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
exe = os.path.join(build, "nltopo")
env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1", OMPI_MCA_rmaps_base_oversubscribe="1")
work = tempfile.mkdtemp(prefix="floquet_verdicts_")
base = ["-options_file", os.path.join(src, "options/fep_long.opts"), "-lattice_cells", cells, "-cont_energy_max", emax, "-cont_checkpoint_seconds", "0"]
routes = {"lead": [], "full": ["-floquet_mf", "0"], "mf": ["-floquet_mf_dense_max", "0"]}
g, secs = {}, {}
for name, extra in routes.items():
    out = os.path.join(work, name + ".h5")
    cmd = ([exe] if ranks == 1 else ["mpiexec", "-n", str(ranks), exe]) + base + extra + ["-output", out]
    t0 = time.time()
    subprocess.run(cmd, check=True, env=env, stdout=subprocess.DEVNULL)
    secs[name] = time.time() - t0
    g[name] = h5py.File(out, "r")["continuation/insulated"]
L, F, M = g["lead"], g["full"], g["mf"]
n = len(F["energy"])
assert len(L["energy"]) == n == len(M["energy"]), "the three runs followed different branches"
mu = F["multipliers_re"][:] + 1j * F["multipliers_im"][:]
name = {1: "stable", 0: "unstable", -1: "not decided"}
cls = {-1: "-", 0: "-", 1: "B-B", 2: "B-E", 3: "E-E"}
worst, same = 0.0, 0
print("%10s %9s %12s %12s %8s  %-9s %-9s %-11s %s" % ("E", "omega", "full |mu|", "lead |mu|", "diff", "full", "lead", "mf", "class full/lead"))
for i in range(n):
    m = mu[i][np.argsort(np.abs(mu[i] - 1))][2:]   # the trivial pair: the two nearest 1
    ref = np.abs(m).max()
    d = abs(L["max_modulus"][i] - ref)
    worst = max(worst, d)
    same += L["stable"][i] == F["stable"][i] and L["instability"][i] == F["instability"][i]
    print("%10.4g %9.6f %12.9f %12.9f %8.1e  %-9s %-9s %-11s %s/%s" % (F["energy"][i], F["omega"][i], ref, L["max_modulus"][i], d, name[int(F["stable"][i])],
          name[int(L["stable"][i])], name[int(M["stable"][i])], cls[int(F["instability"][i])], cls[int(L["instability"][i])]))
count = lambda X, v: int((X["stable"][:] == v).sum())
print("N = %d, %d orbits to E = %.4g: largest |lead - full| = %.1e; same verdict and class at %d of %d"
      % (len(F["z0"][0]) // 2, n, F["energy"][-1], worst, same, n))
for k, X in (("lead", L), ("full", F), ("mf", M)):
    print("  %-4s %7.1f s: %d stable, %d unstable, %d not decided" % (k, secs[k], count(X, 1), count(X, 0), count(X, -1)))
