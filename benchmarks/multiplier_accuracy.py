#!/usr/bin/python3
"""Floquet multipliers of the insulated-branch NNM at omega = 2.1876 (E ~ 96)
against the integration accuracy (fixed RK 5(4) steps per period): largest
distance of each multiplier set from the 1024-step reference, |det M - 1|, and
the largest |mu| (the orbit is Floquet-stable: 1 up to the error).

usage: benchmarks/multiplier_accuracy.py <build dir>"""
import os, subprocess, sys, tempfile, time
import h5py
import numpy as np

build = sys.argv[1] if len(sys.argv) > 1 else "build"
root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
tmp = tempfile.mkdtemp()
res = {}
for n in (64, 128, 256, 512, 1024):
    out = os.path.join(tmp, f"m{n}.h5")
    t0 = time.time()
    subprocess.run([os.path.join(build, "nltopo"), "-options_file", os.path.join(root, "options", "stability.opts"), "-stability_omega", "2.1876",
                    "-stability_periods", "1", "-nnm_steps_per_period", str(n), "-sim_progress", "0", "-output", out], check=True, capture_output=True)
    g = h5py.File(out, "r")["stability/case0"]
    res[n] = (g["multipliers_re"][:] + 1j * g["multipliers_im"][:], time.time() - t0)
ref = res[1024][0]
print("| steps per period | max distance to the 1024-step multipliers | abs(det M - 1) | max abs(mu) - 1 | wall (s) |")
print("|---|---|---|---|---|")
for n, (mu, wall) in res.items():
    d = max(np.min(np.abs(ref - m)) for m in mu)
    print(f"| {n} | {d:.2e} | {abs(np.prod(mu) - 1):.2e} | {np.abs(mu).max() - 1:.2e} | {wall:.1f} |")
