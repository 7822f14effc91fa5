#!/usr/bin/python3
"""Times one paper-default forced run (N = 102, 1000 s, rtol = atol = 1e-8) with
nltopo's PETSc TS (options/simulate.opts) against the plain C++ dopri5 baseline
(plain_dopri5.cpp) on the same model, amplitude and tolerance, in one run.

usage: benchmarks/simulate_vs_plain.py <build dir> [repeats] [extra nltopo options...]
Prints a markdown table row set; medians over interleaved repeats."""
import os, re, statistics, subprocess, sys, tempfile
import h5py

build = sys.argv[1] if len(sys.argv) > 1 else "build"
reps = int(sys.argv[2]) if len(sys.argv) > 2 else 11
extra = sys.argv[3:]
root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
nltopo = os.path.join(build, "nltopo")
plain = os.path.join(build, "benchmarks", "plain_dopri5")
tmp = tempfile.mkdtemp()
out = os.path.join(tmp, "bench.h5")
base = [nltopo, "-options_file", os.path.join(root, "options", "simulate.opts"), "-sim_store_u", "0", "-sim_ts_type", "rk", "-sim_ts_dt", "0.01",
        "-output", out] + extra

def run_nltopo():
    subprocess.run(base, check=True, capture_output=True)
    a = h5py.File(out, "r")["simulate"].attrs
    return float(a["solve_seconds"]), dict(a)

_, attrs = run_nltopo()
S = attrs["amplitude"]
plain_cmd = [plain, "--amplitude", repr(float(S)), "--repeat", "1"]

def run_plain():
    txt = subprocess.run(plain_cmd, check=True, capture_output=True, text=True).stdout
    kv = dict(re.findall(r"(\w+)=(\S+)", txt))
    return float(kv["median_ms"]) / 1e3, kv

tn, tp = [], []
for _ in range(reps):  # interleaved so both see the same machine noise
    t, attrs = run_nltopo(); tn.append(t)
    t, kv = run_plain(); tp.append(t)
mn, mp = statistics.median(tn), statistics.median(tp)
print(f"| solver | median solve (ms) | steps | RHS evaluations | MCR |")
print(f"|---|---|---|---|---|")
print(f"| nltopo TS (`{' '.join(['rk 5dp'] + extra) if extra else 'rk 5dp'}`) | {mn*1e3:.1f} | {attrs['steps']} | {attrs['rhs_evals']} | {attrs['mcr']:.10f} |")
print(f"| plain C++ dopri5 | {mp*1e3:.1f} | {kv['steps']} | {kv['rhs_evals']} | {float(kv['mcr']):.10f} |")
print(f"\nratio nltopo / plain = {mn/mp:.2f} (median of {reps} interleaved runs each; S = {S:.6g})")
