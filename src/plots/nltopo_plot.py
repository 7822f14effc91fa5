"""Shared helpers of the figure scripts."""
import numpy as np

# colours of the Floquet instability classes (the paper's Fig. 4b: orange B-B,
# purple B-E, red E-E), indexed by /continuation/<branch>/instability
INSTABILITY = {0: ("stable", "tab:blue"), 1: ("B-B", "tab:orange"), 2: ("B-E", "tab:purple"), 3: ("E-E", "tab:red")}


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
