#!/usr/bin/python3
"""Where a finished sweep's time went, against the plain C++ dopri5 baseline.

usage: benchmarks/sweep_cost.py <build dir> <sweep.h5> [log_view.txt]
Reads /sweep (seconds and RHS evaluations per point, every attempt and the
0-1 test's free continuation included), times plain_dopri5 on the
paper-default run (median of 7) for its cost per RHS evaluation, and prints a
markdown table: wall time, runs per second, RHS evaluations, the per-run cost
of nltopo against what the baseline would need for the same RHS evaluations,
and the cost by energy decade. With a -log_view file, the share of the main
events."""
import re, signal, statistics, subprocess, sys
signal.signal(signal.SIGPIPE, signal.SIG_DFL)
import h5py
import numpy as np

build, path = sys.argv[1], sys.argv[2]
f = h5py.File(path, "r")
s = f["sweep"]
done = s["done"][:].astype(bool)
sec, rhs = s["seconds"][:][done], s["rhs_evals"][:][done].astype(float)
E = np.repeat(s["energy"][:][:, None], s["omega"].shape[0], axis=1)[done]
wall = float(f.attrs["wall_seconds"])
txt = subprocess.run([f"{build}/benchmarks/plain_dopri5", "--amplitude", "0.0389501", "--repeat", "7"], check=True, capture_output=True, text=True).stdout
kv = dict(re.findall(r"(\w+)=(\S+)", txt))
plain_per_rhs = float(kv["median_ms"]) / 1e3 / float(kv["rhs_evals"])
n = int(done.sum())
print(f"| quantity | value |\n|---|---|")
print(f"| points | {n} of {done.size} |")
print(f"| wall time (s) | {wall:.1f} |")
print(f"| runs per second | {n / wall:.2f} |")
print(f"| RHS evaluations (all attempts + 0-1 continuation) | {rhs.sum():.3e} |")
print(f"| nltopo seconds per run (median, mean) | {np.median(sec):.3f}, {sec.mean():.3f} |")
print(f"| nltopo us per RHS evaluation (sum seconds / sum RHS) | {1e6 * sec.sum() / rhs.sum():.2f} |")
print(f"| plain dopri5 us per RHS evaluation (paper-default run) | {1e6 * plain_per_rhs:.2f} |")
print(f"| per-run cost ratio nltopo / plain (same RHS count) | {sec.sum() / (plain_per_rhs * rhs.sum()):.2f} |")
print(f"| rescaled points (amplitude rule), never reached | {(s['rescalings'][:][done] > 0).sum()}, {(s['reached'][:][done] == 0).sum()} |")
print()
print("| E* decade | points | share of run time | mean s per run | mean RHS per run |\n|---|---|---|---|---|")
for lo in (1e-3, 1e-2, 1e-1, 1, 10, 100):
    m = (E >= lo * 0.999) & (E < lo * 10 * 0.999) if lo < 100 else (E >= lo * 0.999)
    if m.any():
        print(f"| [{lo:g}, {lo * 10:g}{']' if lo == 100 else ')'} | {m.sum()} | {sec[m].sum() / sec.sum():.0%} | {sec[m].mean():.3f} | {rhs[m].mean():.3g} |")
if len(sys.argv) > 3:
    log = open(sys.argv[3]).read()
    tot = float(re.search(r"^Time \(sec\):\s+(\S+)", log, re.M).group(1))
    print("\n| -log_view event (max over ranks) | seconds | share |\n|---|---|---|")
    for ev in ("TSStep", "RhsLinear", "RhsCubic", "RhsForcing", "Energy", "TSAdaptChoose", "Diagnostics", "OutputHDF5"):
        m = re.search(r"^%s\s+\d+\s+\S+\s+(\S+)" % ev, log, re.M)
        if m:
            print(f"| {ev} | {float(m.group(1)):.1f} | {float(m.group(1)) / tot:.0%} |")
