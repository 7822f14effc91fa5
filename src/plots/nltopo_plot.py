"""Shared helpers of the figure scripts: the colours, the command line, and
open_run, through which every script reads its HDF5 files with the
repository's Python reader (python/nltopo, docs/python.md)."""
import argparse
import os
import sys
import numpy as np

# The reader of this checkout (<repo>/python, beside src/plots), whatever the
# working directory: the scripts and the reader follow the same output format.
_READER = os.path.join(os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))), "python")
if os.path.isdir(os.path.join(_READER, "nltopo")) and _READER not in sys.path:
    sys.path.insert(0, _READER)
import nltopo  # noqa: E402

# the paper's site colours (its Figs. 5 and 7): even sites orange, odd sites
# purple; sites are 1-based as in the model (site 2j-1, 2j: unit cell j)
EVEN, ODD = "tab:orange", "tab:purple"


def site_colour(n):
    """The colour of 1-based site n."""
    return EVEN if int(n) % 2 == 0 else ODD


# the colours of branches (and of other series that sit beside the instability
# classes' orange, purple and red)
BRANCH_COLOURS = ["tab:blue", "tab:green", "tab:brown", "tab:olive", "tab:cyan", "navy", "tab:gray", "tab:pink", "darkgoldenrod", "teal"]


def branch_colour(k):
    return BRANCH_COLOURS[k % len(BRANCH_COLOURS)]


# colours of the Floquet instability classes (the paper's Fig. 4b: orange B-B,
# purple B-E, red E-E), indexed by /continuation/<branch>/instability
INSTABILITY = {0: ("stable", "tab:blue"), 1: ("B-B", "tab:orange"), 2: ("B-E", "tab:purple"), 3: ("E-E", "tab:red")}


# the unstable stretches by class: (label, colour, width); -1: unstable, class not computed
STRETCH = {1: ("B-B unstable: effectively stable (bulk-bulk)", "tab:orange", 2.0), 2: ("B-E unstable (bulk-edge)", "tab:purple", 4.5),
           3: ("E-E unstable (edge-edge)", "tab:red", 4.5), -1: ("unstable (class not computed)", "tab:red", 2.0)}


def stretches(E, w, mask):
    """The polyline (in log E) covering the points where mask holds: each run
    of such points from half-way to its left neighbour to half-way to its
    right one, NaN between runs. Returns x, y and the indices of the orbits in them."""
    lE, n = np.log(E), len(E)
    x, y, at = [], [], []
    idx = np.flatnonzero(mask)
    for run in np.split(idx, np.flatnonzero(np.diff(idx) > 1) + 1):
        i0, i1 = run[0], run[-1]
        xs, ys = list(lE[i0:i1 + 1]), list(w[i0:i1 + 1])
        first = len(x) + (i0 > 0)
        at += list(range(first, first + i1 - i0 + 1))
        if i0 > 0:
            xs.insert(0, 0.5 * (lE[i0 - 1] + lE[i0]))
            ys.insert(0, 0.5 * (w[i0 - 1] + w[i0]))
        if i1 + 1 < n:
            xs.append(0.5 * (lE[i1] + lE[i1 + 1]))
            ys.append(0.5 * (w[i1] + w[i1 + 1]))
        x += xs + [np.nan]
        y += ys + [np.nan]
    return np.exp(np.array(x, float)), np.array(y, float), at


# the verdicts that are not an unstable class (stability_class): (label, colour, marker)
VERDICT_MARK = {-3: ("stable-to(delta): nothing beyond 1 + delta", "tab:green", "v"),
                -4: ("unresolved (verdict_reason says why)", "0.45", "d")}


def stability_class(g):
    """Per orbit: 0 stable, 1-3 the unstable class, -1 unstable without a class, -2 not decided or not computed,
    and from the verdicts (when written): -3 stable-to(delta), -4 unresolved."""
    if "stable" not in g:
        return np.full(len(g.energy), -2)
    st = np.asarray(g.stable).astype(int)
    cls = np.asarray(g.instability).astype(int) if "instability" in g else np.full(len(st), -1)
    old = np.where(st == 1, 0, np.where(st == 0, np.where(cls > 0, cls, -1), -2))
    if "verdict" not in g:
        return old
    v = np.asarray(g.verdict).astype(int)
    unstable = np.where(cls > 0, cls, -1)
    return np.select([v == 0, (v == 1) | (v == 2), v == 3, v == 4], [0, unstable, -3, -4], old)


def parser(doc):
    """An argparse parser whose -h prints the script's docstring (without its
    own usage line: argparse writes one)."""
    text = "\n".join(l for l in doc.strip().splitlines() if not l.startswith("usage:"))
    return argparse.ArgumentParser(description=text, formatter_class=argparse.RawDescriptionHelpFormatter)


def main_one_file(doc, study, suffix, load, figure, argv=None, dpi=120):
    """The command line of a script drawing one file: h5 [out.png] (default
    <h5 without .h5>_<suffix>.png), -h printing doc; figure(load(h5)) saved."""
    p = parser(doc)
    p.add_argument("h5", help=f"a -study {study} output")
    p.add_argument("out", nargs="?", help=f"the PNG (default: <h5 without .h5>_{suffix}.png)")
    a = p.parse_args(argv)
    out = a.out or a.h5.replace(".h5", "") + f"_{suffix}.png"
    figure(load(a.h5)).savefig(out, dpi=dpi)
    print("wrote", out)


# ---- loading -------------------------------------------------------------------
def open_run(path):
    """The output file at path as an nltopo.Run of the repository's Python
    reader (python/nltopo, docs/python.md): the scripts' only access to HDF5.
    Its views give datasets and attributes by name (g.energy, g["mcr"],
    "stable" in g, g.get(name, default), g.attrs, g.groups), run.options,
    run.branches and each branch's decoded events."""
    return nltopo.open(path)


def events(branch):
    """The located events of a branch (nltopo Event records), [] when its
    bifurcations were not located (no -floquet, or -cont_bifurcations 0)."""
    return branch.events if branch.located else []


def space_time(fig, ax, t, u, sel=None, label="u (displacement)"):
    """The space-time map of u (time x site) over the samples sel, colours
    symmetric about 0 (clipped at the 99.5th percentile of |u|), with its
    colour bar; returns the colour limit."""
    sel = np.ones(len(t), bool) if sel is None else sel
    lim = float(np.percentile(np.abs(u[sel]), 99.5)) or 1.0
    N = u.shape[1]
    im = ax.imshow(u[sel].T, aspect="auto", origin="lower", extent=[t[sel][0], t[sel][-1], 0.5, N + 0.5], cmap="RdBu_r", vmin=-lim, vmax=lim,
                   interpolation="nearest")
    fig.colorbar(im, ax=ax, label=label, pad=0.01)
    return lim


def rms_by_parity(ax, rms, ms=3):
    """RMS amplitude per site on a log scale, even and odd sites in the paper's colours."""
    sites = np.arange(1, len(rms) + 1)
    ax.semilogy(sites[1::2], rms[1::2], "o", color=EVEN, ms=ms, label="even sites")
    ax.semilogy(sites[0::2], rms[0::2], "o", color=ODD, ms=ms, label="odd sites")


def bands(group):
    """The infinite lattice's bands [(acoustic bottom, top), (optical bottom, top)]
    in rad/s, from the *_inf attributes of a view (/linear/bloch, /continuation,
    /sweep)."""
    a = group
    return [(float(a["acoustic_bottom_inf"]), float(a["acoustic_top_inf"])), (float(a["optical_bottom_inf"]), float(a["optical_top_inf"]))]


def cell_edges(v, log=False):
    """Edges of the cells centred on the grid values v (ascending), for
    pcolormesh(..., shading="flat"): midpoints, geometric ones on a log axis.
    (shading="nearest" takes linear midpoints, whose first edge of a log grid
    such as E* = 1e-3 .. 1e3 is negative: a log axis then autoscales to one
    decade past the last edge and the map is empty.)"""
    v = np.asarray(v, float)
    if v.size == 1:
        return np.array([v[0] / 1.5, v[0] * 1.5]) if log else np.array([v[0] - 0.5, v[0] + 0.5])
    x = np.log10(v) if log else v
    mid = 0.5 * (x[1:] + x[:-1])
    e = np.concatenate([[x[0] - (mid[0] - x[0])], mid, [x[-1] + (x[-1] - mid[-1])]])
    return 10 ** e if log else e


def grid_map(ax, x, y, c, xlog=False, ylog=False, **kw):
    """pcolormesh of c (len(y) x len(x)) on cells centred on the grid values,
    with the axis scales and the limits set to the cells: the map fills its
    panel whatever the grid size."""
    xe, ye = cell_edges(x, xlog), cell_edges(y, ylog)
    m = ax.pcolormesh(xe, ye, c, shading="flat", **kw)
    ax.set(xscale="log" if xlog else "linear", yscale="log" if ylog else "linear", xlim=(xe[0], xe[-1]), ylim=(ye[0], ye[-1]))
    return m


def clip_to(x, y, xlim, ylim):
    """x, y with the points outside the box set to NaN (an overlaid curve that
    stays inside the limits of a map)."""
    x, y = np.asarray(x, float).copy(), np.asarray(y, float).copy()
    out = (x < min(xlim)) | (x > max(xlim)) | (y < min(ylim)) | (y > max(ylim))
    x[out], y[out] = np.nan, np.nan
    return x, y


def branch_omega(group, energies):
    """omega of a continuation branch at the given energies, interpolated in
    log E (as -study perturb does with -perturb_fep)."""
    E, w = group["energy"][:], group["omega"][:]
    order = np.argsort(E)
    return np.interp(np.log(energies), np.log(E[order]), w[order])


def zak_reruns(zak_path, targets):
    """-study simulate runs that repeat runs of a -study zak file (the paper's
    Fig. 5a-b: the zak study keeps no time series): for the zak grid energies
    nearest (in log E) to each target, the mu = 0 and the mu = pi run, with the
    zak run's -lattice_*, -sim_*, -force_* and -linear_* options, its mode
    (mode0, modepi) at its frequency and its exact E*, and u(t) stored at the
    zak's samples per period (the same samples after the cut-off: zak_windows).
    Returns [(name, [options])]."""
    run = open_run(zak_path)
    z = run.zak
    carried = []
    for name, value in run.options.items():
        if name.startswith(("lattice_", "sim_", "force_", "linear_")):
            carried += ["-" + name] + ([value] if value != "" else [])
    E = z["energy"][:]
    spp = int(z.samples_per_period)
    picks = sorted({int(np.argmin(np.abs(np.log(E / t)))) for t in targets})
    runs = []
    for k in picks:
        for edge in ("0", "pi"):
            w = float(z["omega" + edge])
            runs.append((f"zak_run_{edge}_{k}", carried + ["-force_profile", "mode", "-force_mode_index", str(int(z["mode" + edge])),
                                                       "-force_omega", repr(w), "-force_energy", repr(float(E[k])),
                                                       "-sim_sample_dt", repr(2 * np.pi / w / spp), "-sim_store_u", "1",
                                                       "-sim_progress", "0"]))
    return runs


def zak_windows(t, t_off, samples_per_period, windows):
    """Indices into t of the -study zak windows of a run: whole periods of the
    samples after the cut-off, split into equal windows (zak_study.cpp)."""
    free = np.flatnonzero(t >= t_off)
    per = (len(free) // samples_per_period // windows) * samples_per_period
    return [free[k * per:(k + 1) * per] for k in range(windows)]


def dimer_phases(t, u, omega):
    """phi = phase(even) - phase(odd) of every unit cell (2j-1, 2j), 1-based,
    at omega over the samples given (Fourier coefficients), wrapped to
    model.md's [-pi/2, 3 pi/2) so that 0 and pi both lie inside."""
    c = (u * np.exp(-1j * omega * t)[:, None]).sum(axis=0)
    return (np.angle(c[1::2]) - np.angle(c[0::2]) + np.pi / 2) % (2 * np.pi) - np.pi / 2
