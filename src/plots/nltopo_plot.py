"""Shared helpers of the figure scripts."""
import numpy as np

# colours of the Floquet instability classes (the paper's Fig. 4b: orange B-B,
# purple B-E, red E-E), indexed by /continuation/<branch>/instability
INSTABILITY = {0: ("stable", "tab:blue"), 1: ("B-B", "tab:orange"), 2: ("B-E", "tab:purple"), 3: ("E-E", "tab:red")}


def pop_option(argv, name, default, kind=float):
    """The value of "name value" in argv (removed from it), or default."""
    if name not in argv:
        return default
    k = argv.index(name)
    value = kind(argv[k + 1])
    del argv[k:k + 2]
    return value


def bands(group):
    """The infinite lattice's bands [(acoustic bottom, top), (optical bottom, top)]
    in rad/s, from the *_inf attributes of a group (/linear/bloch, /continuation,
    /sweep; outputs.md schema: src/io/schema.cpp)."""
    a = group.attrs
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


def run_options(h5file):
    """The options a study ran with (the root attribute `options`, outputs.md)
    as [(name, value)], value None for a flag. A value may be negative: a word
    after a name is its value unless it is itself an option name."""
    text = h5file.attrs.get("options", b"")
    words = (text.decode() if isinstance(text, bytes) else str(text)).split()
    out, k = [], 0
    while k < len(words):
        name, value = words[k], None
        if k + 1 < len(words):
            nxt = words[k + 1]
            try:
                float(nxt)
                is_value = True
            except ValueError:
                is_value = not nxt.startswith("-")
            if is_value:
                value, k = nxt, k + 1
        out.append((name, value))
        k += 1
    return out


def zak_reruns(zak_path, targets):
    """-study simulate runs that repeat runs of a -study zak file (the paper's
    Fig. 5a-b: the zak study keeps no time series): for the zak grid energies
    nearest (in log E) to each target, the mu = 0 and the mu = pi run, with the
    zak run's -lattice_*, -sim_*, -force_* and -linear_* options, its mode
    (mode0, modepi) at its frequency and its exact E*, and u(t) stored at the
    zak's samples per period (the same samples after the cut-off: zak_windows).
    Returns [(name, [options])]."""
    import h5py
    f = h5py.File(zak_path, "r")
    z = f["zak"]
    carried = []
    for name, value in run_options(f):
        if name.startswith(("-lattice_", "-sim_", "-force_", "-linear_")):
            carried += [name] + ([value] if value is not None else [])
    E = z["energy"][:]
    spp = int(z.attrs["samples_per_period"])
    picks = sorted({int(np.argmin(np.abs(np.log(E / t)))) for t in targets})
    runs = []
    for k in picks:
        for edge in ("0", "pi"):
            w = float(z.attrs["omega" + edge])
            runs.append((f"zak_run_{edge}_{k}", carried + ["-force_profile", "mode", "-force_mode_index", str(int(z.attrs["mode" + edge])),
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
