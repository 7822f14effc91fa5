#!/usr/bin/python3
"""The cost of sampling in the shipped forced run: options/simulate.opts as
shipped (u and E sampled every second, progress lines on) against the same
run with -sim_store_u 0 -sim_progress 0, interleaved, and a run with no
samples at all (-sim_sample_dt 0 -sim_progress 0) for scale.

usage: benchmarks/sampling_cost.py <nltopo> [repeats]
Prints the median /simulate solve_seconds of each variant and the ratio
shipped / (no u, no progress). Also checks that the shipped run's MCR and
energies are those of the run without u."""
import os, statistics, subprocess, sys, tempfile
import h5py, numpy as np

binary = sys.argv[1]
reps = int(sys.argv[2]) if len(sys.argv) > 2 else 5
root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
opts = os.path.join(root, "options", "simulate.opts")
tmp = tempfile.mkdtemp()
variants = {
    "shipped": [],
    "no u, no progress": ["-sim_store_u", "0", "-sim_progress", "0"],
    "no samples": ["-sim_sample_dt", "0", "-sim_progress", "0"],
}

def run(extra, tag):
    out = os.path.join(tmp, tag + ".h5")
    subprocess.run([binary, "-options_file", opts] + extra + ["-output", out, "-output_overwrite"], check=True, capture_output=True)
    with h5py.File(out, "r") as f:
        g = f["simulate"]
        e = g["energy"][:] if "energy" in g else np.zeros(0)
        return float(g.attrs["solve_seconds"]), float(g.attrs["mcr"]), e

times = {k: [] for k in variants}
res = {}
for _ in range(reps):  # interleaved: every variant sees the same machine noise
    for k, extra in variants.items():
        t, mcr, e = run(extra, "v%d" % len(res))
        times[k].append(t)
        res[k] = (mcr, e)
med = {k: statistics.median(v) for k, v in times.items()}
for k in variants:
    print(f"{k:20s} solve median {1e3 * med[k]:7.2f} ms  (runs: {', '.join('%.2f' % (1e3 * x) for x in times[k])})")
print(f"shipped / (no u, no progress) = {med['shipped'] / med['no u, no progress']:.3f}")
same = res["shipped"][0] == res["no u, no progress"][0] and np.array_equal(res["shipped"][1], res["no u, no progress"][1])
print("MCR and E samples identical:", same)
