#!/usr/bin/python3
"""Summarise nltopo outputs through the reader (docs/python.md).

    PYTHONPATH=python /usr/bin/python3 python/examples/read_outputs.py fep.h5 sweep.h5 ...

Prints, for each file, its study, options and what its groups hold: the
branches and their located events, the sweep's maps, the forced run, the
linear bands, and so on. The test suite runs it on a real output of every study
(tests/python/test_reader.py).
"""
import argparse
import sys

import numpy as np

import nltopo


def show_continuation(run):
    for name, b in run.branches.items():
        print(f"  branch {name}: {b.points} orbits, E {b.energy.min():.3g} .. {b.energy.max():.3g}, "
              f"omega {b.omega.min():.6f} .. {b.omega.max():.6f} ({b.stop_reason})")
        if b.floquet:
            unstable = np.count_nonzero(b.stable == 0)
            print(f"    Floquet: {unstable} of {b.points} orbits unstable; classes {sorted(set(b.instability_name))}")
        if b.located:
            for e in b.events:
                what = e.kind_name + (f" {e.resonance[0]}/{e.resonance[1]}" if e.resonance else "")
                print(f"    event {e.index:2d}: {what:24s} E {e.energy:10.4g}  omega {e.omega:.7f}  "
                      f"{e.instability_name:4s} {('ends', 'pass', 'begins')[e.direction + 1]:6s}  |mu| {abs(e.multiplier):.4f}")


def show_linear(run):
    L = run.linear
    edges = L.band_edges
    print(f"  {L.N} sites ({L.layout}), omega {L.omega[0]:.6f} .. {L.omega[-1]:.6f}; "
          f"insulated mode at {L.insulated_omega:.7f}")
    print(f"  bands: acoustic {edges['acoustic_bottom']:.6f} .. {edges['acoustic_top']:.6f}, "
          f"optical {edges['optical_bottom']:.6f} .. {edges['optical_top']:.6f}")
    z = L.zak_phases
    print(f"  Zak phases (acoustic): left cell {z['left', 'acoustic']:.4f}, right cell {z['right', 'acoustic']:.4f}")
    if "transition" in L.groups:
        T = L.transition
        print(f"  transition: {len(T.gamma)} gamma values {T.gamma[0]:g} .. {T.gamma[-1]:g}")


def show_simulate(run):
    s = run.simulate
    stored = f"u of {len(s.sites)} sites" if "u" in s else "no u"
    print(f"  {len(s.t)} samples to t = {s.t[-1]:g}, {stored}; E* {s.energy_star:g} "
          f"{'reached' if s.energy_reached else 'missed'}, cut-off at {s.t_off:g}, MCR {s.mcr:.4f}")


def show_sweep(run):
    w = run.sweep
    E, W = w.axes
    mcr = w.mcr
    i, j = np.unravel_index(np.nanargmax(mcr), mcr.shape)
    print(f"  {w.shape[0]} energies x {w.shape[1]} frequencies; maps {', '.join(sorted(w.maps))}")
    print(f"  largest MCR {mcr[i, j]:.4f} at E* {E[i]:g}, omega {W[j]:.4f}")


def show_zak(run):
    z = run.zak
    for E, t in zip(z.energy, z.theta_median):
        print(f"  E* {E:g}: theta (medians) {t:.4f}")


def show_perturb(run):
    for kind, g in run.perturb.items():
        print(f"  {kind}: delta {list(g.delta)}, mean MCR per delta {np.nanmean(g.mcr, axis=(1, 2)).round(4).tolist()}")


def show_stability(run):
    for c in run.stability.cases:
        print(f"  omega {c.omega:.4f} (E {c.orbit_energy:.3g}): max |mu| {c.max_modulus:.4f} "
              f"({'stable' if c.floquet_stable else 'unstable, ' + c.instability_name}); "
              f"{'persisted' if c.persisted else 'lost'} over {c.t[-1]:.0f} time units")


def show_floquet_scaling(run):
    top = run.floquet_scaling
    if "windows" not in top.groups:
        print(f"  {top.sizes_done} sizes done, no fit (interrupted)")
        return
    w = run.group(top.path + "/windows")
    for k in range(len(w.energy_lo)):
        verdict = w.codes("verdict")[int(w.verdict[k])]
        print(f"  E in [{w.energy_lo[k]:g}, {w.energy_hi[k]:g}): envelope ~ N^-p, p = {w.exponent[k]:.3f} "
              f"(R^2 {w.r2[k]:.2f}, {w.npoints[k]} sizes): {verdict.split(' (')[0]}")


def show_stabilitymap(run):
    m = run.stabilitymap
    for cells, s in m.sizes.items():
        share = {n: float(np.mean(s.region_name == n)) for n in ("stable", "B-E unstable", "E-E unstable")}
        print(f"  N = {s.attrs['N']}: {len(s.curves)} curves in {m.attrs['parameter']}; of the (p, E) raster "
              + ", ".join(f"{v:.0%} {k}" for k, v in share.items()))
    for ch in m.checks:
        a = np.asarray(ch.agree)
        print(f"  check at p = {ch.attrs['p']:g}: the map agrees with {int((a == 1).sum())} of {int((a >= 0).sum())} orbits")


def show_workprecision(run):
    w = run.workprecision
    for k, cfg in enumerate(w.configs):
        print(f"  {cfg:55s} {w.wall_seconds[k]:8.4f} s  MCR error {w.errors['mcr'][k]:.2e}")
    print(f"  predictability floor (MCR): {w.spread['mcr']:.1e}")
    if w.has_recommended:
        print(f"  recommended: {w.recommended}")


SHOW = {"continuation": show_continuation, "linear": show_linear, "simulate": show_simulate, "sweep": show_sweep,
        "zak": show_zak, "perturb": show_perturb, "stability": show_stability,
        "floquet_scaling": show_floquet_scaling, "stabilitymap": show_stabilitymap, "workprecision": show_workprecision}


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("files", nargs="+", help="nltopo HDF5 outputs")
    args = ap.parse_args()
    for path in args.files:
        with nltopo.open(path) as run:
            print(f"{path}: -study {run.study} (format {run.format_version}, nltopo {run.version}, "
                  f"{'complete' if run.complete else 'incomplete'}, {run.wall_seconds:.2f} s)")
            long = {k: v for k, v in run.options.items() if " " in v}
            print(f"  {len(run.options)} options given" + "".join(f"; -{k} \"{v}\"" for k, v in long.items()))
            SHOW[run.study](run)
    return 0


if __name__ == "__main__":
    sys.exit(main())
