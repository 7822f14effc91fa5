#!/usr/bin/python3
"""Compare two sweep maps (outputs.md /sweep) point by point, as the issue's
acceptance asks: the MCR must agree wherever the run is not chaotic.

usage: benchmarks/sweep_map_compare.py <reference.h5> <candidate.h5> [kcorr threshold, default 0.7]

Every grid point falls in one class:
- chaotic: the 0-1 test scores K > threshold in either map (model.md: k_corr > 0.7
  marks chaos). Pointwise MCRs of chaotic runs are samples, not digits: the
  class is reported by the distribution of the differences.
- another amplitude: the amplitude rule's S differs. A missed attempt is
  repeated with S scaled by E* / E_peak, and whether an attempt whose energy
  peak grazes E* counts as a miss is as ill-conditioned as the cut-off below:
  the two maps then compare two different runs.
- cut-off on another peak: both runs reached E*, but t_off differs by more than a
  quarter of the forcing period. The energy of a driven run oscillates at
  2 omega, so the cut-off can only move between peaks of E(t) by about
  pi / omega; where a peak grazes E*, a perturbation at the integration
  tolerance decides which peak crosses first, and the MCR jumps with it. The
  map is discontinuous there, whatever the integrator.
- regular: everything else; the relative MCR difference is the accuracy.
Prints one markdown table row per class and the worst regular points."""
import sys
import h5py
import numpy as np

ref_path, cand_path = sys.argv[1], sys.argv[2]
threshold = float(sys.argv[3]) if len(sys.argv) > 3 else 0.7
a, b = h5py.File(ref_path, "r")["sweep"], h5py.File(cand_path, "r")["sweep"]
omega, energy = a["omega"][:], a["energy"][:]
assert np.array_equal(omega, b["omega"][:]) and np.array_equal(energy, b["energy"][:]), "the two maps have different grids"
mcr_a, mcr_b = a["mcr"][:], b["mcr"][:]
toff_a, toff_b = a["t_off"][:], b["t_off"][:]
done = (a["done"][:] == 1) & (b["done"][:] == 1)
reached = done & (a["reached"][:] == 1) & (b["reached"][:] == 1)
W = np.broadcast_to(omega[None, :], mcr_a.shape)
with np.errstate(invalid="ignore"):
    chaotic = done & ((a["kcorr"][:] > threshold) | (b["kcorr"][:] > threshold))
other_s = done & ~chaotic & (np.abs(b["amplitude"][:] / a["amplitude"][:] - 1) > 1e-9)
jump = reached & ~chaotic & ~other_s & (np.abs(toff_a - toff_b) > 0.5 * np.pi / W)
regular = done & ~chaotic & ~other_s & ~jump & (a["failed"][:] == 0) & (b["failed"][:] == 0)
rel = np.abs(mcr_b - mcr_a) / np.abs(mcr_a)

print(f"reference {ref_path}, candidate {cand_path}: {done.sum()} of {mcr_a.size} points done in both, "
      f"{(done & ~reached).sum()} not reaching E* in one of them")
print("| class | points | median rel. MCR difference | max rel. MCR difference |")
print("|---|---|---|---|")
for name, mask in (("regular", regular), ("another amplitude S", other_s), ("cut-off on another peak", jump), (f"chaotic (K > {threshold:g})", chaotic)):
    if mask.sum():
        print(f"| {name} | {mask.sum()} | {np.median(rel[mask]):.1e} | {rel[mask].max():.1e} |")
    else:
        print(f"| {name} | 0 | - | - |")
print("\nregular points by E* decade:")
print("| E* | regular / all | median rel. MCR difference | max | points above 1e-3 |")
print("|---|---|---|---|---|")
decades = np.floor(np.log10(energy) + 1e-9)
for d in np.unique(decades):
    rows = decades == d
    m = regular[rows]
    x = rel[rows][m]
    if x.size:
        print(f"| [1e{int(d)}, 1e{int(d) + 1}) | {m.sum()} / {m.size} | {np.median(x):.1e} | {x.max():.1e} | {(x > 1e-3).sum()} |")
if regular.sum():
    order = np.argsort(rel[regular])[::-1][:5]
    ie, io = np.nonzero(regular)
    print("\nworst regular points (E*, omega, MCR ref, MCR cand, t_off ref, t_off cand):")
    for k in order:
        i, j = ie[k], io[k]
        print(f"  {energy[i]:.4g} {omega[j]:.4f} {mcr_a[i, j]:.8f} {mcr_b[i, j]:.8f} {toff_a[i, j]:.4f} {toff_b[i, j]:.4f}")
if jump.sum():
    dt = np.abs(toff_a - toff_b)[jump] / (np.pi / W[jump])
    print(f"\ncut-off moved by {np.median(dt):.2f} (median) x pi/omega, range {dt.min():.2f}-{dt.max():.2f}")
