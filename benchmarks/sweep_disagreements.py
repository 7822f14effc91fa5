#!/usr/bin/python3
"""Explain every regular point where two sweep maps disagree: is the old map
wrong, the new one, or is the run unpredictable?

usage: benchmarks/sweep_disagreements.py <nltopo> <base.opts> <reference.h5> <old.h5> <new.h5> [tol, default 1e-3] [old accuracy, default 1e-8]

<base.opts> is the sweep's options file; every map must come from it (the same
grid, lattice and forcing). Regular points are sweep_map_compare.py's (0-1 test
K <= 0.7 in all three maps, the same amplitude S and the same cut-off peak).
At each regular point where old and new differ by more than tol (relative),
the point is rerun as a single simulate (ref: the errors below are against
its first run, not the reference map, whose uncapped steps leave ~1e-8) with the reference integrator (rkn
dep1210, rtol = atol = 1e-13, steps capped at 0.05) and with S perturbed by
k 1e-10 (k = 1, -1, 2): the twin spread (max - min over the four runs,
relative) is the predictability floor of that MCR. A point whose spread
exceeds tol / 10 is unpredictable at that tolerance: its single MCR is one
sample of a distribution, whatever the integrator (a finite-time chaos the
0-1 test's K <= 0.7 did not flag). The same twins with S x (1 + k eps), eps
the old map's accuracy (its rtol = atol), say whether a map of that accuracy
can hold tol at all: where they spread by more than tol, the old map's value
is luck, not accuracy. Elsewhere the reference decides which map is off."""
import os
import subprocess
import sys
import tempfile
import h5py
import numpy as np

nltopo, base, ref_path, old_path, new_path = sys.argv[1:6]
tol = float(sys.argv[6]) if len(sys.argv) > 6 else 1e-3
eps_old = float(sys.argv[7]) if len(sys.argv) > 7 else 1e-8
R, O, N = (h5py.File(p, "r")["sweep"] for p in (ref_path, old_path, new_path))
omega, energy = R["omega"][:], R["energy"][:]
W = np.broadcast_to(omega[None, :], R["mcr"].shape)
regular = np.ones(W.shape, bool)
for S in (R, O, N):
    assert np.array_equal(S["omega"][:], omega) and np.array_equal(S["energy"][:], energy), "the maps have different grids"
    with np.errstate(invalid="ignore"):
        regular &= (S["done"][:] == 1) & (S["failed"][:] == 0) & ~(S["kcorr"][:] > 0.7)
    regular &= np.abs(S["amplitude"][:] / R["amplitude"][:] - 1) <= 1e-9
    regular &= ~((S["reached"][:] == 1) & (np.abs(S["t_off"][:] - R["t_off"][:]) > 0.5 * np.pi / W))
mr, mo, mn = R["mcr"][:], O["mcr"][:], N["mcr"][:]
d = np.abs(mn / mo - 1)
# the single-run reference: the sweep's reference integrator with the steps capped (benchmarks/README.md, rkn)
ref = "-sim_ts_type rkn -sim_ts_rkn_scheme dep1210 -sim_ts_rtol 1e-13 -sim_ts_atol 1e-13 -sim_ts_dt 0.1 -sim_ts_adapt_dt_max 0.05"
# sweep options that a simulate run does not read
drop = ("-sweep_", "-kcorr_", "-study", "-output", "-sim_ts_")
opts = [l.strip() for l in open(base) if l.strip() and not l.startswith("#") and not l.strip().startswith(drop)]
tmp = tempfile.mkdtemp()
base_sim = os.path.join(tmp, "base.opts")
with open(base_sim, "w") as f:
    f.write("\n".join(opts + ["-study simulate", "-sim_sample_dt 0", "-sim_progress 0"]) + "\n")


def mcr(E, w, S):
    out = os.path.join(tmp, "t.h5")
    subprocess.run(f"{nltopo} -options_file {base_sim} -force_energy {E!r} -force_omega {w!r} -force_amplitude {S!r} {ref} -output {out} -output_overwrite",
                   shell=True, check=True, stdout=subprocess.DEVNULL)
    with h5py.File(out, "r") as f:
        return f["simulate"].attrs["mcr"]


print(f"{regular.sum()} regular points; {(regular & (d > tol)).sum()} where {new_path} and {old_path} differ by more than {tol:g}")
print(f"| E* | omega | K (max) | reference map - ref | old - ref | new - ref | new - old | twin spread (1e-10) | twin spread ({eps_old:g}) | verdict |")
print("|---|---|---|---|---|---|---|---|---|---|")
counts = {}
for i, j in zip(*np.nonzero(regular & (d > tol))):
    S = R["amplitude"][i, j]
    m = np.array([mcr(energy[i], omega[j], S * (1 + k * 1e-10)) for k in (0, 1, -1, 2)])
    spread = (m.max() - m.min()) / abs(m[0])
    m8 = np.array([m[0]] + [mcr(energy[i], omega[j], S * (1 + k * eps_old)) for k in (1, -1, 2)])
    spread8 = (m8.max() - m8.min()) / abs(m[0])
    eo, en = abs(mo[i, j] / m[0] - 1), abs(mn[i, j] / m[0] - 1) # against the capped single-run reference
    em = abs(mr[i, j] / m[0] - 1)
    if spread > tol / 10: verdict = "unpredictable"
    elif spread8 > tol: verdict = f"unpredictable at {eps_old:g}"
    elif eo > tol: verdict = "old map off" + (", new too" if en > tol else "") # no accurate map can equal the old one here
    elif en > tol: verdict = "new map off"
    else: verdict = "both within tol of the reference"
    counts[verdict] = counts.get(verdict, 0) + 1
    K = max(float(S_["kcorr"][i, j]) for S_ in (R, O, N))
    print(f"| {energy[i]:.4g} | {omega[j]:.4f} | {K:.2f} | {em:.1e} | {eo:.1e} | {en:.1e} | {d[i, j]:.1e} | {spread:.1e} | {spread8:.1e} | {verdict} |", flush=True)
print("; ".join(f"{k}: {v}" for k, v in counts.items()))
