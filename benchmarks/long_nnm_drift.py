#!/usr/bin/python3
"""Hard case: the insulated-branch NNM at omega = 2.1876 (E ~ 96) integrated for
30,000 periods from its orbit (perturbation 1e-6) with a symplectic scheme and
with adaptive Dormand-Prince at two tolerances; energy error in the first and
second half of the run (secular growth shows as a larger second half), wall time.

usage: benchmarks/long_nnm_drift.py <build dir> [periods]"""
import os, subprocess, sys, tempfile, time
import h5py
import numpy as np

build = sys.argv[1] if len(sys.argv) > 1 else "build"
periods = sys.argv[2] if len(sys.argv) > 2 else "30000"
root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
tmp = tempfile.mkdtemp()
base = [os.path.join(build, "nltopo"), "-options_file", os.path.join(root, "options", "stability.opts"), "-stability_omega", "2.1876",
        "-stability_periods", periods, "-stability_perturbation", "1e-6", "-sim_progress", "0"]
T = 2 * np.pi / 2.1876
cases = {
    "basicsymplectic (Verlet, dt = T/64)": ["-sim_ts_type", "basicsymplectic", "-sim_ts_basicsymplectic_type", "2", "-sim_ts_dt", repr(T / 64)],
    "rk 5dp, rtol = atol = 1e-8": ["-sim_ts_rtol", "1e-8", "-sim_ts_atol", "1e-8"],
    "rk 5dp, rtol = atol = 1e-10": [],
}
print(f"| integrator | max rel. energy error, 1st half | 2nd half | end | wall (s) |")
print("|---|---|---|---|---|")
for name, extra in cases.items():
    out = os.path.join(tmp, "d.h5")
    t0 = time.time()
    subprocess.run(base + extra + ["-output", out], check=True, capture_output=True)
    wall = time.time() - t0
    g = h5py.File(out, "r")["stability/case0"]
    E = g["energy"][:]
    err = np.abs(E - E[0]) / E[0]
    h = len(err) // 2
    print(f"| {name} | {err[:h].max():.2e} | {err[h:].max():.2e} | {err[-1]:.2e} | {wall:.1f} |")
    sys.stdout.flush()
