#!/usr/bin/python3
"""Work-precision of nltopo's integrators on the paper-default forced run
(options/simulate.opts: N = 102, tone burst at sqrt(3), 1000 s), one table per
energy, and a log-log plot of solve time against error.

E* = 1 (regular): rk 5dp and rkn dep86 at rtol = atol = 1e-6 .. 1e-10, symsplit
bm4 at dt = 0.4, 0.2, 0.1, 0.05 and bm6 at dt = 0.4, 0.2, 0.1, with S fixed at
the amplitude rule's value. Errors against rkn dep1210 at rtol = atol = 1e-13
with steps capped at 0.05 (the window integrals of rkn are taken on each step's
quintic interpolant, whose error at the uncapped steps of ~0.3 moves the MCR by
1e-8): the MCR, the final displacement u(t_final) (the last row of
/simulate/u; the final velocity is not written) and E_final.

E* = 100 at omega_ext = 2 (chaotic after the cut-off): the same integrators
with S fixed at twice the amplitude rule's value (the rule's own next attempt:
at the rule's first S the peak energy barely reaches E*, so integrators differ
in whether they cut off at all). Energy is conserved once the forcing stops:
the error is |E_final - E*| / E* (every cut-off here is located to a relative
1e-10 in E; E_final is the state at the last step's end). The largest
|E(t) - E*| / E* over the 1 s samples of /simulate/energy after t_off is
printed next to it: those are taken on each step's quintic interpolant, so
they measure the samples a user reads, whose error is mostly the
interpolant's. The MCR is reported as a spread across integrators: a chaotic
run has no digits to compare.

usage: benchmarks/work_precision.py <build dir> [repeats] [png path]
Solve times are medians over repeats, the configurations interleaved within
each repeat (all see the same machine noise)."""
import math, os, statistics, subprocess, sys, tempfile
import h5py
import numpy as np

build = sys.argv[1] if len(sys.argv) > 1 else "build"
reps = int(sys.argv[2]) if len(sys.argv) > 2 else 5
root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
png = sys.argv[3] if len(sys.argv) > 3 else os.path.join(root, "benchmarks", "work_precision.png")
nltopo = os.path.join(build, "nltopo")
tmp = tempfile.mkdtemp()
tols = ["1e-6", "1e-7", "1e-8", "1e-9", "1e-10"]
configs = ([("rk 5dp", tol, ["-sim_ts_type", "rk", "-sim_ts_rk_type", "5dp", "-sim_ts_dt", "0.01", "-sim_ts_rtol", tol, "-sim_ts_atol", tol])
            for tol in tols]
           + [("rkn dep86", tol, ["-sim_ts_type", "rkn", "-sim_ts_rkn_scheme", "dep86", "-sim_ts_rtol", tol, "-sim_ts_atol", tol]) for tol in tols]
           + [("symsplit bm4", dt, ["-sim_ts_type", "symsplit", "-sim_ts_symsplit_scheme", "bm4", "-sim_ts_dt", dt]) for dt in ("0.4", "0.2", "0.1", "0.05")]
           + [("symsplit bm6", dt, ["-sim_ts_type", "symsplit", "-sim_ts_symsplit_scheme", "bm6", "-sim_ts_dt", dt]) for dt in ("0.4", "0.2", "0.1")])
reference = ["-sim_ts_type", "rkn", "-sim_ts_rkn_scheme", "dep1210", "-sim_ts_rtol", "1e-13", "-sim_ts_atol", "1e-13", "-sim_ts_adapt_dt_max", "0.05"]

def run(args, energy_args, name="run.h5"):
    """One nltopo run; None if the integration failed."""
    out = os.path.join(tmp, name)
    p = subprocess.run([nltopo, "-options_file", os.path.join(root, "options", "simulate.opts"), "-sim_progress", "0", "-sim_store_u", "1"]
                       + energy_args + args + ["-output", out, "-output_overwrite"], capture_output=True, text=True)
    if p.returncode != 0:
        return {"failed": (p.stdout + p.stderr).strip().splitlines()[-1]}
    g = h5py.File(out, "r")["simulate"]
    a = g.attrs
    r = {k: float(a[k]) for k in ("solve_seconds", "mcr", "t_off", "energy_final", "amplitude", "nl_ratio")}
    r.update(steps=int(a["steps"]), reached=int(a["energy_reached"]), rhs=int(a["rhs_evals"]), t=g["t"][:], energy=g["energy"][:],
             u_final=g["u"][-1, :], rms=g["rms"][:])
    return r

def measure(energy_args):
    """Every configuration reps times, interleaved; the last run's outputs and the median solve time."""
    runs = {i: [] for i in range(len(configs))}
    for _ in range(reps):
        for i, (_, _, args) in enumerate(configs):
            runs[i].append(run(args, energy_args))
    res = []
    for i in range(len(configs)):
        r = runs[i][-1]
        if "failed" not in r:
            r["time"] = statistics.median(x["solve_seconds"] for x in runs[i])
        res.append(r)
    return res

def fmt(x):
    return "-" if x is None or not math.isfinite(x) else f"{x:.1e}"

# --- E* = 1 -----------------------------------------------------------------
rule = run(reference, [], "rule.h5")
S1 = rule["amplitude"]
e1 = ["-force_amplitude", repr(S1)]
ref1 = run(reference, e1, "ref1.h5")
res1 = measure(e1)
print(f"## E* = 1 (S = {S1:.6g}, the amplitude rule's), reference rkn dep1210 1e-13 (steps <= 0.05): MCR = {ref1['mcr']:.12f}, "
      f"t_off = {ref1['t_off']:.6f}, E_final = {ref1['energy_final']:.12f}, {ref1['steps']} steps; solve time: median of {reps}")
print("| integrator | rtol = atol or dt | steps | solve (ms) | MCR rel. error | u(t_final) rel. error | E_final rel. error | t_off |")
print("|---|---|---|---|---|---|---|---|")
pts1 = []
for (name, par, _), r in zip(configs, res1):
    if "failed" in r:
        print(f"| {name} | {par} | - | - | failed: {r['failed']} | | | |")
        continue
    em = abs(r["mcr"] - ref1["mcr"]) / ref1["mcr"]
    eu = float(np.linalg.norm(r["u_final"] - ref1["u_final"]) / np.linalg.norm(ref1["u_final"]))
    ee = abs(r["energy_final"] - ref1["energy_final"]) / ref1["energy_final"]
    pts1.append((name, r["time"], em, eu))
    print(f"| {name} | {par} | {r['steps']} | {1e3 * r['time']:.1f} | {fmt(em)} | {fmt(eu)} | {fmt(ee)} | {r['t_off']:.4f} |")

# --- E* = 100, omega_ext = 2 ------------------------------------------------
base100 = ["-force_energy", "100", "-force_omega", "2"]
rule100 = run(reference, base100, "rule100.h5")
S100 = 2 * rule100["amplitude"]
e100 = base100 + ["-force_amplitude", repr(S100)]
ref100 = run(reference, e100, "ref100.h5")
res100 = measure(e100)
print(f"\n## E* = 100, omega_ext = 2 (S = {S100:.6g} = 2 x the rule's {rule100['amplitude']:.6g}); reference rkn dep1210 1e-13 (steps <= 0.05): "
      f"MCR = {ref100['mcr']:.6f}, t_off = {ref100['t_off']:.6f}")
print("| integrator | rtol = atol or dt | steps | solve (ms) | t_off | \\|E_final - E*\\| / E* | max \\|E(t) - E*\\| / E* of the interpolated 1 s samples, t > t_off | MCR | nl_ratio |")
print("|---|---|---|---|---|---|---|---|---|")
pts100, mcrs = [], []
for (name, par, _), r in zip(configs, res100):
    if "failed" in r:
        print(f"| {name} | {par} | - | - | - | failed: {r['failed']} | | | |")
        continue
    if not r["reached"]:
        print(f"| {name} | {par} | {r['steps']} | {1e3 * r['time']:.1f} | E* not reached | - | - | {r['mcr']:.4f} | {r['nl_ratio']:.3f} |")
        continue
    ef = abs(r["energy_final"] - 100) / 100
    after = r["t"] > r["t_off"]
    emax = float(np.max(np.abs(r["energy"][after] - 100)) / 100)
    pts100.append((name, r["time"], ef))
    mcrs.append(r["mcr"])
    print(f"| {name} | {par} | {r['steps']} | {1e3 * r['time']:.1f} | {r['t_off']:.3f} | {fmt(ef)} | {fmt(emax)} | {r['mcr']:.4f} | {r['nl_ratio']:.3f} |")
if mcrs:
    q = np.percentile(mcrs, [25, 50, 75])
    print(f"\nMCR across the {len(mcrs)} runs that cut off: min {min(mcrs):.4f}, quartiles {q[0]:.4f} / {q[1]:.4f} / {q[2]:.4f}, "
          f"max {max(mcrs):.4f}, mean {statistics.mean(mcrs):.4f} +- {statistics.stdev(mcrs):.4f} (reference {ref100['mcr']:.4f})")

# --- the plot ------------------------------------------------------------------
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
style = {"rk 5dp": "o-", "rkn dep86": "s-", "symsplit bm4": "^-", "symsplit bm6": "v-"}
fig, ax = plt.subplots(1, 3, figsize=(15, 4.6))
panels = [(ax[0], [(n, t, e) for n, t, e, _ in pts1], "MCR rel. error", "E* = 1: MCR"),
          (ax[1], [(n, t, e) for n, t, _, e in pts1], "u(t_final) rel. error", "E* = 1: final displacement"),
          (ax[2], pts100, "|E_final - E*| / E*", "E* = 100, omega_ext = 2: energy after the cut-off")]
for a, pts, ylabel, title in panels:
    for name, st in style.items():
        xs = [1e3 * t for n, t, e in pts if n == name and e > 0]
        ys = [e for n, t, e in pts if n == name and e > 0]
        if xs:
            a.loglog(xs, ys, st, label=name)
    a.set_xlabel("solve time (ms)")
    a.set_ylabel(ylabel)
    a.set_title(title, fontsize=10)
    a.grid(True, which="both", alpha=0.3)
    a.legend(fontsize=8)
fig.suptitle("nltopo work-precision, paper-default forced run (N = 102, 1000 s), 2-core VM", fontsize=11)
fig.tight_layout()
fig.savefig(png, dpi=90)
# the figure must hold data: every panel a line with finite points, and the image not blank
for a, pts, _, title in panels:
    n = sum(len(l.get_xdata()) for l in a.get_lines())
    assert n > 0 and all(np.all(np.isfinite(l.get_ydata())) for l in a.get_lines()), f"empty panel: {title}"
img = plt.imread(png)
assert img.std() > 0.01, "blank figure"
print(f"\nwrote {png} ({sum(len(l.get_xdata()) for a, *_ in panels for l in a.get_lines())} points in 3 panels)")
