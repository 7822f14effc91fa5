#!/usr/bin/python3
"""Simulate cost against lattice length: options/simulate_long.opts (max-norm
step control, S given) with N = 10^3, 10^4, 10^5 sites on 1 rank, plus any
sizes given as cells:ranks pairs. Prints a markdown table: solve time, steps,
time per site per step, and peak memory per rank.

usage: benchmarks/long_scaling.py <build dir> [cells:ranks ...]"""
import os, re, subprocess, sys, tempfile
import h5py

build = sys.argv[1] if len(sys.argv) > 1 else "build"
cases = [tuple(int(x) for x in a.split(":")) for a in sys.argv[2:]] or [(250, 1), (2500, 1), (25000, 1)]
root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
tmp = tempfile.mkdtemp()
env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1", OMPI_MCA_rmaps_base_oversubscribe="1")
print("| N | ranks | solve (s) | steps | ns per site per step | peak memory per rank (MB) |\n|---|---|---|---|---|---|")
for cells, ranks in cases:
    out = os.path.join(tmp, f"l{cells}.h5")
    cmd = ["/usr/bin/time", "-v", "mpiexec", "-n", str(ranks), os.path.join(build, "nltopo"), "-options_file",
           os.path.join(root, "options", "simulate_long.opts"), "-lattice_cells", str(cells), "-sim_progress", "0", "-output", out]
    p = subprocess.run(cmd, check=True, capture_output=True, text=True, env=env)
    rss = int(re.search(r"Maximum resident set size \(kbytes\): (\d+)", p.stderr).group(1)) / 1024
    a = h5py.File(out, "r")["simulate"].attrs
    N = 4 * cells + 2
    t, steps = float(a["solve_seconds"]), int(a["steps"])
    print(f"| {N} | {ranks} | {t:.2f} | {steps} | {1e9 * t * ranks / (N * steps):.1f} | {rss:.0f} |")
