#!/usr/bin/python3
"""Matrix-free continuation of the insulated branch against lattice length:
options/fep_long.opts to E = 10 (default) with N = 102, 1002, 10002 (-lattice_cells 25, 250,
2500), with each preconditioner of -nnm_mf_pc (PCS=parametric,averaged,linear,none by default;
"linear" and "none" rows are limited to 40 and 8 points: inside the band they crawl). Prints a
markdown table: points, energy reached, Newton iterations per point, GMRES
iterations per Newton step (median and max over the points, and overall,
failed attempts included), seconds per point (Floquet off, so that the
column is the shooting alone; -floquet adds its own products).

The band columns are the points with E >= 10 (the optical band edge is at E ~ 11.9).
NP=2 runs each case on 2 MPI ranks (mpiexec, root-safe flags).

usage: [PCS=averaged,linear] [NP=2] benchmarks/long_continuation.py <build dir> [energy_max] [cells ...]"""
import os, subprocess, sys, tempfile
import h5py

build = sys.argv[1] if len(sys.argv) > 1 else "build"
emax = sys.argv[2] if len(sys.argv) > 2 else "10"
cells = [int(c) for c in sys.argv[3:]] or [25, 250, 2500]
root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
tmp = tempfile.mkdtemp()
np_ = int(os.environ.get("NP", "1"))
launch = ["mpiexec", "--oversubscribe", "-n", str(np_)] if np_ > 1 else []
env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
print("| N | ranks | preconditioner | points | E reached | Newton per point | GMRES per Newton step: median / max over points / overall | band (E >= 10): median / max | s per point | stop |\n|---|---|---|---|---|---|---|---|---|---|")
for c in cells:
    for pc in os.environ.get("PCS", "parametric,averaged,linear,none").split(","):
        out = os.path.join(tmp, f"c{c}{pc}.h5")
        cmd = launch + [os.path.join(build, "nltopo"), "-options_file", os.path.join(root, "options", "fep_long.opts"), "-lattice_cells", str(c),
               "-nnm_mf_pc", pc, "-cont_energy_max", emax, "-cont_verbose", "0", "-floquet", "0", "-output", out]
        if pc == "none":  # unpreconditioned GMRES: a short branch only (it stalls, docs/long-lattices.md)
            cmd += ["-cont_max_points", "8"]
        if pc == "linear":  # crawls inside the optical band (docs/long-lattices.md)
            cmd += ["-cont_max_points", "40"]
        p = subprocess.run(cmd, capture_output=True, text=True, env=env)
        if p.returncode != 0 or not os.path.exists(out):
            err = (p.stderr.strip().splitlines() or p.stdout.strip().splitlines() or ["?"])[-1]
            print(f"| {4 * c + 2} | {np_} | {pc} | failed | | | | | | {err} |")
            continue
        g = h5py.File(out, "r")["continuation/insulated"]
        n = int(g.attrs["points"])
        newton = sum(g["newton_its"][:])
        per = sorted(k / max(m, 1) for k, m in zip(g["krylov_its"][:], g["newton_its"][:]))
        band = sorted(k / max(m, 1) for k, m, e in zip(g["krylov_its"][:], g["newton_its"][:], g["energy"][:]) if e >= 10)
        bcol = f"{band[len(band) // 2]:.1f} / {band[-1]:.0f}" if band else "-"
        print(f"| {4 * c + 2} | {np_} | {pc} | {n} | {g['energy'][-1]:.3g} | {newton / n:.1f} | {per[len(per) // 2]:.1f} / {per[-1]:.0f} / {g.attrs['krylov_iterations'] / max(newton, 1):.1f} | {bcol} | "
              f"{g.attrs['seconds'] / n:.3f} | {g.attrs['stop_reason'].decode() if isinstance(g.attrs['stop_reason'], bytes) else g.attrs['stop_reason']} |")
