#!/usr/bin/python3
"""Per-step cost of nltopo's rkn TS type against a plain C++ loop of the same
embedded pair and step-size controller (plain_rkn.cpp) on the paper-default
forced run (N = 102, options/simulate.opts, S fixed by nltopo's amplitude rule),
in one run, with the accuracy of each: the MCR against a converged reference
(rkn dep1210 at rtol = atol = 1e-13 with steps capped at 0.05: rkn takes the
window integrals on each step's quintic interpolant, whose error at the
uncapped steps of ~0.3 moves the MCR by 1e-8).

usage: benchmarks/rkn_vs_plain.py <build dir> [repeats] [pair:tol ...]
Medians over interleaved repeats (both see the same machine noise); the ratio is
of the time per accepted step, each with its own step count. The ratio of the
minima is printed next to it (a run preempted by another process loses whole
scheduler ticks, so the minima are the quieter estimate of the per-step cost)."""
import os, re, statistics, subprocess, sys, tempfile
import h5py

build = sys.argv[1] if len(sys.argv) > 1 else "build"
reps = int(sys.argv[2]) if len(sys.argv) > 2 else 7
configs = [c.split(":") for c in sys.argv[3:]] or [[p, t] for p in ("dep64", "dep86") for t in ("1e-6", "1e-8", "1e-10")]
root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
nltopo = os.path.join(build, "nltopo")
plain = os.path.join(build, "benchmarks", "plain_rkn")
tmp = tempfile.mkdtemp()

def run_nltopo(pair, tol, name="bench.h5", extra=()):
    out = os.path.join(tmp, name)
    subprocess.run([nltopo, "-options_file", os.path.join(root, "options", "simulate.opts"), "-sim_store_u", "0", "-sim_progress", "0",
                    "-sim_ts_type", "rkn", "-sim_ts_rkn_scheme", pair, "-sim_ts_rtol", tol, "-sim_ts_atol", tol, "-sim_ts_dt", "0.2", *extra,
                    "-output", out, "-output_overwrite"], check=True, capture_output=True)
    a = h5py.File(out, "r")["simulate"].attrs
    return (float(a["solve_seconds"]), int(a["steps"]), int(a["rejected_steps"]), float(a["mcr"]), float(a["amplitude"]),
            float(a["t_off"]))

_, _, _, mcr_ref, S, toff_ref = run_nltopo("dep1210", "1e-13", "ref.h5", ["-sim_ts_adapt_dt_max", "0.05"])

def run_plain(pair, tol):
    # the first step as nltopo's (-sim_ts_dt 0.2, given to both), E(t) sampled as nltopo's -sim_sample_dt
    txt = subprocess.run([plain, "--amplitude", repr(S), "--scheme", pair, "--rtol", tol, "--atol", tol, "--dt", "0.2", "--sample_dt", "1",
                          "--repeat", "1"], check=True, capture_output=True, text=True).stdout
    kv = dict(re.findall(r"(\w+)=(\S+)", txt))
    return float(kv["median_ms"]) / 1e3, int(kv["steps"]), int(kv["rejected"]), float(kv["mcr"]), float(kv["t_off"])

print(f"reference: rkn dep1210 rtol = atol = 1e-13, steps <= 0.05, MCR = {mcr_ref:.12f}, t_off = {toff_ref:.6f}, S = {S:.6g}; "
      f"medians of {reps} interleaved runs")
print("| pair | rtol = atol | steps (rejected) nltopo | steps (rejected) plain | nltopo solve (ms) | plain loop (ms) | nltopo us/step | "
      "plain us/step | ratio | ratio of minima | MCR rel. error nltopo | MCR rel. error plain |")
print("|---|---|---|---|---|---|---|---|---|---|---|---|")
for pair, tol in configs:
    tn, tp = [], []
    for _ in range(reps):
        t, steps, rej, mcr, _, toff = run_nltopo(pair, tol); tn.append(t)
        t, psteps, prej, pmcr, ptoff = run_plain(pair, tol); tp.append(t)
    mn, mp = statistics.median(tn), statistics.median(tp)
    print(f"| {pair} | {tol} | {steps} ({rej}) | {psteps} ({prej}) | {1e3 * mn:.2f} | {1e3 * mp:.2f} | {1e6 * mn / steps:.3f} | "
          f"{1e6 * mp / psteps:.3f} | {(mn / steps) / (mp / psteps):.2f} | {(min(tn) / steps) / (min(tp) / psteps):.2f} | "
          f"{abs(mcr - mcr_ref) / mcr_ref:.1e} | "
          f"{abs(pmcr - mcr_ref) / mcr_ref:.1e} |", flush=True)
    if abs(toff - toff_ref) > 1e-3 or abs(ptoff - toff_ref) > 1e-3:
        print(f"  ({pair} {tol}: t_off nltopo {toff:.6f}, plain {ptoff:.6f}, reference {toff_ref:.6f}: cut off on another energy peak)")
