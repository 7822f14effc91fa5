#!/usr/bin/python3
"""Figure of -study stabilitymap (docs/studies/stabilitymap.md).
(a) the main size's map in (p, E): the regions the event curves bound
(stable, B-E, E-E; colour bar), the curves coloured by the class they bound,
their codim-2 points, the events of the one-parameter check branches
(crosses) on their columns, and the finite-size region (hatched: the
insulated mode's decay length above a quarter of the cells per side).
(b) where the sizes differ: the raster points whose label differs between
the main size and the next one (shaded), the curves of both sizes (solid:
main; dashed: the other).
(c) the curves in (p, omega) with the linear band edges against p (grey:
the bands) and the finite-size region.
usage: plot_stabilitymap.py stabilitymap.h5 [out.png]"""
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
from matplotlib.colors import ListedColormap, BoundaryNorm
import numpy as np
import nltopo_plot

# region codes (the instability class): 0 stable, 1 B-B, 2 B-E, 3 E-E
REGION = [(0, "stable", "#dbe9f6"), (1, "B-B", "#fde0c5"), (2, "B-E", "#e3d3ef"), (3, "E-E", "#f7c9c9")]
CURVE = {1: "tab:orange", 2: "tab:purple", 3: "tab:red"}
# codim-2 points (codes of point_kind): 0 an end (a bound or step collapse: stop_reason), 1 a turn in p, 2 and 3 a
# Hamiltonian-Hopf end at b = +1 / -1, 4 the linear limit
POINT_MARK = {0: ("end of a curve (a bound or step collapse)", "o"), 1: ("turn in p", "D"), 2: ("end at b = +1", "s"), 3: ("end at b = -1", "^"),
              4: ("linear limit", "v")}


def load(path):
    """The /stabilitymap view of a -study stabilitymap file (nltopo.StabilityMap)."""
    return nltopo_plot.open_run(path).stabilitymap


def finite_size(ax, m, cells, **kw):
    """Hatches the p where the insulated mode's decay length exceeds cells / 4 (cells per side)."""
    p, fs = m.p, m.decay_cells > cells / 4.0
    if fs.any():
        ax.fill_between(p, 0, 1, where=fs, transform=ax.get_xaxis_transform(), facecolor="none", hatch="//", edgecolor="grey", lw=0,
                        label=f"finite size (decay length > {cells / 4:g} cells)", **kw)


def draw_curves(ax, size, box, y="energy", ls="-"):
    """The curves of one size inside box ((p0, p1), (y0, y1)), coloured by the class of the instability
    they bound; their codim-2 points."""
    seen = set()
    for row, (name, c) in enumerate(size.curves.items()):
        cls = int(size.curve_class[row])
        lab = f"N = {size.attrs['N']}: {nltopo_plot.INSTABILITY.get(cls, ('?',))[0]} boundary"
        x, yy = nltopo_plot.clip_to(c.p, c[y], *box)
        if not np.isfinite(yy).any():
            continue
        ax.plot(x, yy, ls, color=CURVE.get(cls, "k"), lw=1.0, label=lab if lab not in seen else None)
        seen.add(lab)
        if "point_kind" not in c:
            continue
        for k, pk in enumerate(c.point_kind):
            what, mk = POINT_MARK.get(int(pk), ("codim-2 point", "*"))
            px, py = nltopo_plot.clip_to([c.point_p[k]], [c.point_energy[k] if y == "energy" else c.point_omega[k]], *box)
            if np.isfinite(py).all():
                ax.plot(px, py, mk, mfc="none", mec="k", ms=6, label=what if what not in seen else None)
                seen.add(what)


def panel_map(ax, fig, m, size):
    cmap = ListedColormap([c for _, _, c in REGION])
    norm = BoundaryNorm(np.arange(-0.5, 4.5), cmap.N)
    mesh = ax.pcolormesh(m.p, m.energy, np.asarray(size.region).T, cmap=cmap, norm=norm, shading="nearest")
    cb = fig.colorbar(mesh, ax=ax, ticks=[0, 1, 2, 3])
    cb.ax.set_yticklabels([n for _, n, _ in REGION])
    cb.set_label("region (from the curves)")
    box = ((m.p[0], m.p[-1]), (m.energy[0], m.energy[-1]))
    draw_curves(ax, size, box)
    marked = False
    for ch in m.checks:  # the events of the kinds and classes the map follows (event_curve != -1)
        E = np.asarray(ch.event_energy)
        sel = (E >= m.energy[0]) & (E <= m.energy[-1]) & (np.asarray(ch.event_curve) != -1)
        if sel.any():
            ax.plot(np.full(sel.sum(), ch.attrs["p"]), E[sel], "x", color="k", ms=5, label=None if marked else "events of the check branches (kinds and classes followed)")
            marked = True
    finite_size(ax, m, size.attrs["cells"])
    ax.set(yscale="log", xlim=(m.p[0], m.p[-1]), ylim=(m.energy[0], m.energy[-1]), xlabel=m.attrs["parameter"].lstrip("-"), ylabel="E (energy)",
           title=f"(a) N = {size.attrs['N']}: regions, curves, check events")
    ax.legend(fontsize=6, loc="upper left")


def panel_difference(ax, fig, m, sizes):
    a, b = sizes[0], sizes[1]
    diff = (np.asarray(a.region) != np.asarray(b.region)).astype(float)
    mesh = ax.pcolormesh(m.p, m.energy, np.where(diff > 0, 1.0, np.nan).T, cmap=ListedColormap(["#c8c8c8"]), shading="nearest")
    cb = fig.colorbar(mesh, ax=ax, ticks=[1])
    cb.ax.set_yticklabels(["labels differ"])
    box = ((m.p[0], m.p[-1]), (m.energy[0], m.energy[-1]))
    draw_curves(ax, a, box)
    draw_curves(ax, b, box, ls="--")
    finite_size(ax, m, b.attrs["cells"])
    ax.set(yscale="log", xlim=(m.p[0], m.p[-1]), ylim=(m.energy[0], m.energy[-1]), xlabel=m.attrs["parameter"].lstrip("-"), ylabel="E (energy)",
           title=f"(b) N = {a.attrs['N']} (solid) against N = {b.attrs['N']} (dashed)")
    ax.legend(fontsize=6, loc="upper left")


def panel_omega(ax, m, sizes):
    p = m.p
    om = np.concatenate([np.asarray(c.omega) for s in sizes for c in s.curves.values()] or [np.array([1.7, 1.9])])
    ylim = (min(np.nanmin(om), np.min(m.acoustic_top)) - 0.05, max(np.nanmax(om), np.max(m.optical_bottom)) + 0.05)
    for lo, hi, lab in ((m.acoustic_bottom, m.acoustic_top, "linear bands (infinite lattice)"), (m.optical_bottom, m.optical_top, None)):
        ax.fill_between(p, np.clip(lo, *ylim), np.clip(hi, *ylim), color="0.85", lw=0, label=lab)
    for k, s in enumerate(sizes):
        draw_curves(ax, s, ((p[0], p[-1]), ylim), y="omega", ls="-" if k == 0 else "--")
    finite_size(ax, m, sizes[0].attrs["cells"])
    ax.set(xlim=(p[0], p[-1]), ylim=ylim,
           xlabel=m.attrs["parameter"].lstrip("-"), ylabel="omega (rad/time)", title="(c) the curves in omega, the band edges")
    ax.legend(fontsize=6, loc="upper left")


def figure(m):
    sizes = list(m.sizes.values())
    n = 3 if len(sizes) > 1 else 2
    fig, ax = plt.subplots(1, n, figsize=(6.2 * n, 5.2))
    panel_map(ax[0], fig, m, sizes[0])
    if len(sizes) > 1:
        panel_difference(ax[1], fig, m, sizes)
    panel_omega(ax[-1], m, sizes)
    fig.tight_layout()
    return fig


if __name__ == "__main__":
    nltopo_plot.main_one_file(__doc__, "stabilitymap", "stabilitymap", load, figure, dpi=120)
