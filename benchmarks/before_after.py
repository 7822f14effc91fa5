#!/usr/bin/python3
"""Times two nltopo binaries (e.g. before and after a refactor) on the same
scenes, interleaved in one run, and checks that they compute the same numbers.

Scenes: the paper-default forced run (options/simulate.opts, as shipped) and
the insulated branch of options/fep.opts (with its Floquet multipliers).

usage: benchmarks/before_after.py <nltopo before> <nltopo after> [repeats]
Prints medians of the wall time of each scene (the root attribute
wall_seconds), the ratio after/before, and the largest difference of the
results (MCR and energy; branch omega and max |multiplier|)."""
import os, statistics, subprocess, sys, tempfile
import h5py, numpy as np

before, after = sys.argv[1], sys.argv[2]
reps = int(sys.argv[3]) if len(sys.argv) > 3 else 5
root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
tmp = tempfile.mkdtemp()

scenes = {
    "simulate.opts": (["-options_file", os.path.join(root, "options", "simulate.opts"), "-sim_progress", "0"],
                      lambda f: np.array([f["simulate"].attrs["mcr"], f["simulate"].attrs["energy_final"]])),
    "fep.opts insulated": (["-options_file", os.path.join(root, "options", "fep.opts"), "-cont_branch", "insulated", "-cont_verbose", "0"],
                           lambda f: np.concatenate([f["continuation/insulated/omega"][:], f["continuation/insulated/max_modulus"][:]])),
}

def run(binary, args, tag):
    out = os.path.join(tmp, tag + ".h5")
    subprocess.run([binary] + args + ["-output", out, "-output_overwrite"], check=True, capture_output=True)
    f = h5py.File(out, "r")
    return float(f.attrs["wall_seconds"]), f

print("| scene | before (s) | after (s) | after / before | largest result difference |")
print("|---|---|---|---|---|")
for name, (args, values) in scenes.items():
    tb, ta, diff = [], [], 0.0
    for _ in range(reps):  # interleaved: both see the same machine noise
        t, fb = run(before, args, "b"); tb.append(t); vb = values(fb); fb.close()
        t, fa = run(after, args, "a"); ta.append(t); va = values(fa); fa.close()
        diff = max(diff, float(np.max(np.abs(va - vb) / np.maximum(np.abs(vb), 1e-300))) if va.shape == vb.shape else float("inf"))
    mb, ma = statistics.median(tb), statistics.median(ta)
    print(f"| {name} | {mb:.3f} | {ma:.3f} | {ma / mb:.3f} | {diff:.1e} (relative) |")
