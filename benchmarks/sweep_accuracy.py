#!/usr/bin/python3
"""What accuracy costs in time, for forced runs: the quick sweep grid
(options/sweep_quick.opts without the 0-1 test) under several RK schemes and
tolerances, against a tight reference (8vr at 1e-12), on 2 ranks.

usage: benchmarks/sweep_accuracy.py <build dir>
Prints a markdown table: wall time of the grid, RHS evaluations, and the
relative MCR error against the reference over the E* <= 10 rows (above, the
runs are chaotic and no two integrators agree pointwise)."""
import os, subprocess, sys, tempfile, time
import h5py
import numpy as np

build = sys.argv[1] if len(sys.argv) > 1 else "build"
root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
tmp = tempfile.mkdtemp()
env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1", OMPI_MCA_rmaps_base_oversubscribe="1")

def run(name, extra):
    out = os.path.join(tmp, name + ".h5")
    cmd = ["mpiexec", "-n", "2", os.path.join(build, "nltopo"), "-options_file", os.path.join(root, "options", "sweep_quick.opts"),
           "-sweep_kcorr", "0", "-output", out] + extra
    t = time.time()
    subprocess.run(cmd, check=True, capture_output=True, env=env)
    wall = time.time() - t
    s = h5py.File(out, "r")["sweep"]
    return wall, s["mcr"][:], s["rhs_evals"][:].sum(), s["energy"][:]

variants = [("5dp, 1e-8 (paper default)", ["-sim_ts_rk_type", "5dp"]),
            ("5dp, 1e-10", ["-sim_ts_rk_type", "5dp", "-sim_ts_rtol", "1e-10", "-sim_ts_atol", "1e-10"]),
            ("8vr, 1e-8", ["-sim_ts_rk_type", "8vr"]),
            ("8vr, 1e-10", ["-sim_ts_rk_type", "8vr", "-sim_ts_rtol", "1e-10", "-sim_ts_atol", "1e-10"]),
            ("5dp, 1e-8, dsp controller", ["-sim_ts_rk_type", "5dp", "-sim_ts_adapt_type", "dsp"])]
_, ref, _, E = run("ref", ["-sim_ts_rk_type", "8vr", "-sim_ts_rtol", "1e-12", "-sim_ts_atol", "1e-12"])
rows = E <= 10
print("| scheme, rtol = atol | grid wall (s) | RHS evaluations | median rel. MCR error (E* <= 10) | max rel. MCR error (E* <= 10) |")
print("|---|---|---|---|---|")
for name, extra in variants:
    wall, mcr, rhs, _ = run(name.split(",")[0].replace(" ", "_"), extra)
    err = np.abs(mcr[rows] - ref[rows]) / ref[rows]
    print(f"| {name} | {wall:.1f} | {rhs:.3g} | {np.median(err):.1e} | {err.max():.1e} |")
