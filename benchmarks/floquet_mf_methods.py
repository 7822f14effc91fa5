#!/usr/bin/env python3
"""Tabulate the `bench:` lines of floquet_mf_methods against its dense reference.

Usage: floquet_mf_methods.py LOG [tol]
Per method: points, points with a verdict (finite modulus), points whose
leading modulus is within 1e-6 of the dense one, same stable/unstable call
(|mu| > 1 + tol, tol = -floquet_tol, 1e-4 by default), same kind (real +1,
real -1, complex), median products and seconds per point, and the largest
modulus error where finite. Also, per point, the dense leading modulus."""
import re
import statistics
import sys

log, tol = sys.argv[1], float(sys.argv[2]) if len(sys.argv) > 2 else 1e-4
pts, res, energy, window = {}, {}, {}, {}
for line in open(log):
    m = re.match(r"bench: point (\d+) E (\S+) omega (\S+)", line)
    if m:
        energy[int(m[1])] = (float(m[2]), float(m[3]))
        continue
    m = re.match(r"bench: point (\d+) method (\S+) modulus (\S+) re (\S+) im (\S+) kind (\S+) products (\d+) seconds (\S+)", line)
    if m:
        p = int(m[1])
        res.setdefault(m[2], {})[p] = dict(mod=float(m[3]), re=float(m[4]), im=float(m[5]), kind=int(m[6]), prod=int(m[7]), sec=float(m[8]))
        continue
    m = re.match(r"bench: point (\d+) window half_width (\S+) columns (\d+) rank (\d+) products (\d+) seconds (\S+) profile (\S+)", line)
    if m:
        window[int(m[1])] = dict(hw=int(m[2]), cols=int(m[3]), profile=m[7])
dense = res.get("dense", {})
print("| method | points | finite | modulus within 1e-6 of dense | same call | same kind | median products | median s | largest error |")
print("|---|---|---|---|---|---|---|---|---|")
for name, r in res.items():
    ps = sorted(r)
    fin = [p for p in ps if r[p]["mod"] == r[p]["mod"]]
    cmp = [p for p in fin if p in dense]
    err = [abs(r[p]["mod"] - dense[p]["mod"]) for p in cmp]
    within = sum(e <= 1e-6 for e in err)
    call = sum((r[p]["mod"] > 1 + tol) == (dense[p]["mod"] > 1 + tol) for p in cmp)
    kind = sum(r[p]["kind"] == dense[p]["kind"] or (dense[p]["mod"] <= 1 + tol and r[p]["mod"] <= 1 + tol) for p in cmp)
    print(f"| {name} | {len(ps)} | {len(fin)} | {within} | {call} | {kind} | {statistics.median(r[p]['prod'] for p in ps):.0f} | "
          f"{statistics.median(r[p]['sec'] for p in ps):.3f} | {max(err) if err else float('nan'):.1e} |")
print()
print("| point | E | omega | dense max |mu| | dense kind | " + " | ".join(n for n in res if n != "dense") + " |")
print("|---|---|---|---|---|" + "---|" * (len(res) - 1))
for p in sorted(energy):
    d = dense.get(p)
    row = [str(p), f"{energy[p][0]:.4g}", f"{energy[p][1]:.5f}", f"{d['mod']:.7f}" if d else "-", str(d["kind"]) if d else "-"]
    for n in res:
        if n == "dense":
            continue
        x = res[n].get(p)
        row.append("-" if not x else ("NaN" if x["mod"] != x["mod"] else f"{x['mod']:.7f}"))
    print("| " + " | ".join(row) + " |")
if window:
    print()
    print("| point | E | window half-width (sites) | columns | |E e_j| / |M| at distance 0, 2, 4, ... from the interface |")
    print("|---|---|---|---|---|")
    for p in sorted(window):
        w = window[p]
        prof = w["profile"].split(",")
        print(f"| {p} | {energy[p][0]:.4g} | {w['hw']} | {w['cols']} | {' '.join(prof[::2])} |")
