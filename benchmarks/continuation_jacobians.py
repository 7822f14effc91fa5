#!/usr/bin/python3
"""NNM continuation (N = 102) with each shooting Jacobian: dense (monodromy
from the variational equations), mf (tangent-linear MATSHELL + GMRES) and
-nnm_snes_mf (finite differences + GMRES), on the insulated and interface
branches from E = 1e-5 to 1e3, shot with rk 5dp (-nnm_ts_type rk, the code
default when the table in benchmarks/README.md was measured). Each case runs
under a wall-time limit.

usage: benchmarks/continuation_jacobians.py <build dir> [limit seconds] [branches...]"""
import os, subprocess, sys, tempfile, time
import h5py

build = sys.argv[1] if len(sys.argv) > 1 else "build"
limit = float(sys.argv[2]) if len(sys.argv) > 2 else 300
branches = sys.argv[3:] or ["insulated", "interface"]
nltopo = os.path.join(build, "nltopo")
tmp = tempfile.mkdtemp()
krylov = ["-nnm_ksp_type", "gmres", "-nnm_pc_type", "none", "-nnm_ksp_gmres_restart", "400", "-nnm_ksp_max_it", "400"]
choices = {
    "dense": ["-nnm_jacobian", "dense"],
    "mf": ["-nnm_jacobian", "mf", "-nnm_ksp_gmres_restart", "400", "-nnm_ksp_max_it", "400"],
    "snes_mf": ["-nnm_jacobian", "dense", "-nnm_snes_mf"] + krylov,
}
print("| branch | Jacobian | points | E reached | Newton its (total) | wall (s) | s/point | result |")
print("|---|---|---|---|---|---|---|---|")
for br in branches:
    for name, extra in choices.items():
        out = os.path.join(tmp, f"{br}_{name}.h5")
        cmd = [nltopo, "-study", "continuation", "-cont_branch", br, "-cont_verbose", "0", "-nnm_ts_type", "rk", "-output", out] + extra
        t0 = time.time()
        try:
            r = subprocess.run(cmd, capture_output=True, text=True, timeout=limit)
            wall = time.time() - t0
            if r.returncode != 0:
                print(f"| {br} | {name} | - | - | - | {wall:.1f} | - | failed: {r.stderr.strip()[:80]} |")
                continue
            g = h5py.File(out, "r")["continuation/" + br]
            n, its = int(g.attrs["points"]), int(g["newton_its"][:].sum())
            stop = g.attrs["stop_reason"]
            stop = stop.decode() if isinstance(stop, bytes) else stop
            print(f"| {br} | {name} | {n} | {g['energy'][-1]:.4g} | {its} | {wall:.1f} | {wall / n:.3f} | {stop} |")
        except subprocess.TimeoutExpired:
            print(f"| {br} | {name} | - | - | - | >{limit:.0f} | - | killed at the {limit:.0f} s limit |")
        sys.stdout.flush()
