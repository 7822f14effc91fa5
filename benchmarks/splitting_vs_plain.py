#!/usr/bin/python3
"""Per-step cost of nltopo's symsplit TS type against a plain C++ loop of the
same scheme (plain_splitting.cpp) on the paper-default forced run (N = 102,
options/simulate.opts, S fixed by nltopo's amplitude rule), in one run, with the
accuracy of each: the MCR against a converged reference (bm6 at dt = 0.01).

usage: benchmarks/splitting_vs_plain.py <build dir> [repeats] [scheme:dt ...]
Medians over interleaved repeats (both see the same machine noise); the ratio of
the minima is printed next to the ratio of the medians (a run preempted by
another process loses whole scheduler ticks, so the minima are the quieter
estimate of the per-step cost)."""
import os, re, statistics, subprocess, sys, tempfile
import h5py

build = sys.argv[1] if len(sys.argv) > 1 else "build"
reps = int(sys.argv[2]) if len(sys.argv) > 2 else 7
configs = [c.split(":") for c in sys.argv[3:]] or [["verlet", "0.025"], ["yoshida4", "0.1"], ["bm4", "0.2"], ["yoshida6", "0.2"],
                                                  ["bm6", "0.2"], ["bm6", "0.4"], ["ss8", "0.4"]]
root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
nltopo = os.path.join(build, "nltopo")
plain = os.path.join(build, "benchmarks", "plain_splitting")
dopri = os.path.join(build, "benchmarks", "plain_dopri5")
tmp = tempfile.mkdtemp()

def run_nltopo(scheme, dt, name="bench.h5"):
    out = os.path.join(tmp, name)
    subprocess.run([nltopo, "-options_file", os.path.join(root, "options", "simulate.opts"), "-sim_store_u", "0", "-sim_progress", "0",
                    "-sim_ts_type", "symsplit", "-sim_ts_symsplit_scheme", scheme, "-sim_ts_dt", dt, "-output", out, "-output_overwrite"],
                   check=True, capture_output=True)
    a = h5py.File(out, "r")["simulate"].attrs
    return float(a["solve_seconds"]), int(a["steps"]), float(a["mcr"]), float(a["amplitude"])

_, _, mcr_ref, S = run_nltopo("bm6", "0.01", "ref.h5")

def run_plain(scheme, dt):
    txt = subprocess.run([plain, "--amplitude", repr(S), "--scheme", scheme, "--dt", dt, "--repeat", "1"], check=True, capture_output=True,
                         text=True).stdout
    kv = dict(re.findall(r"(\w+)=(\S+)", txt))
    return float(kv["median_ms"]) / 1e3, int(kv["steps"]), float(kv["mcr"])

def run_dopri():
    txt = subprocess.run([dopri, "--amplitude", repr(S), "--repeat", "1"], check=True, capture_output=True, text=True).stdout
    kv = dict(re.findall(r"(\w+)=(\S+)", txt))
    return float(kv["median_ms"]) / 1e3, float(kv["mcr"])

print(f"reference: bm6 dt = 0.01, MCR = {mcr_ref:.12f}, S = {S:.6g}; medians of {reps} interleaved runs")
print("| scheme | dt | steps | nltopo solve (ms) | plain loop (ms) | nltopo us/step | plain us/step | ratio | ratio of minima | MCR rel. error (nltopo) |")
print("|---|---|---|---|---|---|---|---|---|---|")
td = []
for scheme, dt in configs:
    tn, tp = [], []
    for _ in range(reps):
        t, steps, mcr, _ = run_nltopo(scheme, dt); tn.append(t)
        t, psteps, _ = run_plain(scheme, dt); tp.append(t)
        t, mcr_dopri = run_dopri(); td.append(t)
    mn, mp = statistics.median(tn), statistics.median(tp)
    print(f"| {scheme} | {dt} | {steps} | {1e3 * mn:.2f} | {1e3 * mp:.2f} | {1e6 * mn / steps:.3f} | {1e6 * mp / psteps:.3f} | "
          f"{(mn / steps) / (mp / psteps):.2f} | {(min(tn) / steps) / (min(tp) / psteps):.2f} | {abs(mcr - mcr_ref) / mcr_ref:.1e} |")
print(f"\nplain C++ dopri5, rtol = atol = 1e-8 (interleaved with every row above): median {1e3 * statistics.median(td):.2f} ms, "
      f"MCR rel. error {abs(mcr_dopri - mcr_ref) / mcr_ref:.1e}")
