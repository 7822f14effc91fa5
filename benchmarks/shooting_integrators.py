#!/usr/bin/python3
"""Shooting integrators on the insulated NNM branch to E = 1e3 (options/fep.opts,
-cont_branch insulated): rk 5dp against the symplectic splitting
(-nnm_ts_type symsplit), point by point, on accuracy and cost per continuation
point. Reference: rk 5dp at 512 steps per period. The branch's points sit at
the same energies for every integrator (the step control sees the same
orbits to ~1e-9), so points are compared at equal E.

usage: benchmarks/shooting_integrators.py <build dir> [repeats]
Wall times are medians over interleaved repeats."""
import os, statistics, subprocess, sys, tempfile
import h5py
import numpy as np

build = sys.argv[1] if len(sys.argv) > 1 else "build"
reps = int(sys.argv[2]) if len(sys.argv) > 2 else 3
root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
nltopo = os.path.join(build, "nltopo")
tmp = tempfile.mkdtemp()
configs = [("rk", "5dp", 128), ("symsplit", "bm4", 128), ("symsplit", "bm4", 64), ("symsplit", "bm6", 64)]


def run(ts, scheme, steps, name):
    out = os.path.join(tmp, name)
    extra = ["-nnm_ts_rk_type", scheme] if ts == "rk" else ["-nnm_ts_symsplit_scheme", scheme]
    subprocess.run([nltopo, "-options_file", os.path.join(root, "options", "fep.opts"), "-cont_branch", "insulated", "-cont_verbose", "0",
                    "-nnm_ts_type", ts, *extra, "-nnm_steps_per_period", str(steps), "-output", out, "-output_overwrite"],
                   check=True, capture_output=True)
    g = h5py.File(out, "r")["continuation/insulated"]
    mu = g["multipliers_re"][:] + 1j * g["multipliers_im"][:]
    return dict(seconds=float(g.attrs["seconds"]), E=g["energy"][:], omega=g["omega"][:], mu=mu, det=g["det_error"][:],
                newton=int(g["newton_its"][:].sum()))


ref = run("rk", "5dp", 512, "ref.h5")
print(f"reference: rk 5dp, 512 steps per period, {len(ref['E'])} points to E = {ref['E'][-1]:.4g}; medians of {reps} interleaved runs")
print("| integrator | steps per period | wall (s) | s per point | Newton its | max rel. omega error | max multiplier distance | max abs(det M - 1) |")
print("|---|---|---|---|---|---|---|---|")
times = {c: [] for c in configs}
last = {}
for _ in range(reps):
    for c in configs:
        r = run(*c, "c.h5")
        times[c].append(r["seconds"])
        last[c] = r
for c in configs:
    r = last[c]
    werr = derr = 0.0
    for i, e in enumerate(r["E"]):
        j = int(np.argmin(np.abs(np.log(ref["E"] / e))))
        if abs(np.log(ref["E"][j] / e)) > 1e-6:
            continue  # not at a reference energy
        werr = max(werr, abs(r["omega"][i] - ref["omega"][j]) / ref["omega"][j])
        derr = max(derr, np.abs(r["mu"][i][:, None] - ref["mu"][j][None, :]).min(axis=1).max())
    t = statistics.median(times[c])
    print(f"| {c[0]} {c[1]} | {c[2]} | {t:.2f} | {t / len(r['E']):.3f} | {r['newton']} | {werr:.1e} | {derr:.1e} | {np.nanmax(r['det']):.1e} |")
