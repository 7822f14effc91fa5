#!/usr/bin/python3
"""How evenly -sweep_shard i/n shares a sweep's work (docs/studies/sweep.md,
"Shards and merge").

usage: benchmarks/sweep_shard_balance.py <whole sweep.h5> [shard files of a sweep ...]

Reads a finished whole-grid sweep's work per point (rhs_evals: every attempt
and the 0-1 test's continued record; seconds: wall time) and, for n shards,
the work each shard would hold under three splits: nltopo's (the cost model
c(E*) = max(1, (E*/E_q)^(1/4)) and the longest-processing-time rule,
studies/sweep_shard.cpp, re-implemented here), the points dealt round robin
(equal costs) and n blocks of whole energy rows (what a split by hand does).
Prints, per n, the largest shard's work over the mean (1 = perfect balance):
the whole job waits for the largest. Shard files given (-sweep_shard runs of
any sweep) are checked against this re-implementation: each file's
/sweep/shard_points must equal it."""
import heapq
import sys

import h5py
import numpy as np


def effective(f):
    """The root attribute effective_options as {name: value}."""
    t = f.attrs["effective_options"]
    t = t.decode() if isinstance(t, bytes) else str(t)
    return {l.split(" ", 1)[0]: (l.split(" ", 1)[1] if " " in l else "") for l in t.splitlines() if l}


def cost_energy(o):
    """E_q: -sim_dt_quartic_energy, else k1^2 / (2 |Gamma|) (0: uniform)."""
    q = float(o.get("-sim_dt_quartic_energy", 0))
    if q > 0:
        return q
    k1 = float(o["-lattice_k"]) * (1 + float(o["-lattice_gamma"]))
    g = float(o["-lattice_cubic"])
    return k1 * k1 / (2 * abs(g)) if g else 0.0


def point_cost(e, e_q):
    return int(np.round(1000 * ((e / e_q) ** 0.25 if e_q > 0 and e > e_q else 1.0)))


def split(energy, no, n, costs):
    """The longest-processing-time split of sweep_shard.cpp: shard of each grid index."""
    rows = sorted(range(len(energy)), key=lambda e: (-costs[e], -e))
    heap = [(0, k) for k in range(n)]
    shard = np.empty(len(energy) * no, dtype=int)
    for e in rows:
        for w in range(no - 1, -1, -1):
            load, k = heapq.heappop(heap)
            shard[e * no + w] = k
            heapq.heappush(heap, (load + costs[e], k))
    return shard


def main():
    path, shards = sys.argv[1], sys.argv[2:]
    for sp in shards:
        with h5py.File(sp, "r") as f:
            s, o = f["sweep"], effective(f)
            energy, no = s["energy"][:], len(s["omega"])
            i, n = int(s.attrs["shard_index"]), int(s.attrs["shard_count"])
            costs = [point_cost(e, cost_energy(o)) for e in energy]
            mine = np.flatnonzero(split(energy, no, n, costs) == i)
            ok = np.array_equal(mine, s["shard_points"][:])
            print(f"{sp}: shard {i}/{n}, {len(mine)} points: {'the same' if ok else 'NOT the same'} as this re-implementation")
            if not ok:
                return 1
    with h5py.File(path, "r") as f:
        s, o = f["sweep"], effective(f)
        energy, no = s["energy"][:], len(s["omega"])
        rhs = s["rhs_evals"][:].astype(float).ravel()
        sec = s["seconds"][:].ravel()
        e_q = cost_energy(o)
    ne = len(energy)
    costs = [point_cost(e, e_q) for e in energy]
    print(f"{path}: {ne} x {no} points, E_q = {e_q:g}; the largest shard's work over the mean (RHS evaluations / wall seconds)")
    print("| shards | cost model (nltopo) | round robin | blocks of rows |")
    print("|---|---|---|---|")
    for n in (2, 4, 8, 16, 64):
        if n > ne * no:
            continue
        splits = [split(energy, no, n, costs), split(energy, no, n, [1] * ne),
                  np.repeat(np.minimum(np.arange(ne) * n // ne, n - 1), no)]
        cells = []
        for sh in splits:
            r = np.bincount(sh, weights=rhs, minlength=n)
            t = np.bincount(sh, weights=sec, minlength=n)
            cells.append(f"{r.max() / r.mean():.3f} / {t.max() / t.mean():.3f}")
        print(f"| {n} | " + " | ".join(cells) + " |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
