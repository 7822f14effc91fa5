#!/usr/bin/python3
"""Paper-style frequency-energy plot of -study continuation (the paper's Fig. 3):
(a) omega against energy of every branch over the linear bands (grey), the
    nonlinear optical band shaded between its edge NNMs (only with both the
    optical_bottom and the optical_top branch); the Floquet-unstable
    stretches of each branch as segments coloured by class (the paper's
    Fig. 4b): B-B, which the paper calls effectively stable, thin orange;
    B-E purple and E-E red, thick; modal interactions (x); lettered orbits of
    the insulated branch; orbits whose verdict is stable-to(delta) (green
    triangles) or unresolved (grey diamonds), from a long-lattice route;
    the located bifurcations (-cont_bifurcations)
    numbered 1, 2, ... as AUTO labels them, each a circle coloured by its type
    (LP fold, BP branch point, PD period doubling, HH+/HH- Hamiltonian-Hopf
    onset/end, KC a Krein collision that passes, R p/q an internal resonance)
    placed apart from the others with a leader line to where it lies;
    branches that leave the panel at the top are clipped there (their
    largest omega is written at the edge);
(T) the events table: number, branch:index (the -cont_switch name), type,
    class, omega, energy;
(b) the MCR of each orbit along the branches;
(c) the insulated NNM's shape u0 at the lettered points (normalised, offset);
(d) the band-edge NNMs' shapes at the lowest and the highest energy of their
    branches (only with acoustic_top, optical_bottom or optical_top);
(e) families born at branch points and period doublings (-cont_switch): how
    far each leaves its parent, |v0| / |u0| at the section, against E.
A family born at a period doubling has orbits of about twice its parent's
period: its omega (2 pi / period) is drawn times its period_multiple
attribute, on the parent's frequency scale, so that it meets its parent at
the located point.
usage: plot_fep.py fep.h5 [out.png]
figure(run) builds the figure without saving it (tests/scenes/fep_figure_check.py)."""
import matplotlib
matplotlib.use("Agg")
import matplotlib.lines
import matplotlib.pyplot as plt
import numpy as np
import nltopo_plot

# the event types: (legend name, face colour), keyed by the table's type
TYPES = {"LP": ("energy fold (LP)", "tab:brown"), "BP": ("branch point, +1 (BP)", "gold"), "PD": ("period doubling, -1 (PD)", "tab:pink"),
         "HH+": ("Hamiltonian-Hopf onset (HH+)", "#ff9896"), "HH-": ("Hamiltonian-Hopf end (HH-)", "#aec7e8"),
         "KC": ("Krein collision, passes (KC)", "white"), "R": ("internal resonance p/q (R)", "#98df8a")}
MARKER_PT = 13.0  # event circle diameter (points)
DPI = 120


def event_type(ev):
    """(key of TYPES, the table's type text) of an event."""
    if ev.kind == 1:
        return "LP", "LP"
    if ev.kind == 2:
        return "BP", "BP"
    if ev.kind == 3:
        return "PD", "PD"
    if ev.kind == 4:
        return "KC", "KC"
    if ev.kind == 5:
        return ("HH+", "HH+") if ev.direction > 0 else ("HH-", "HH-")
    return "R", f"R {ev.resonance[0]}/{ev.resonance[1]}"


def numbered_events(branches):
    """[(number, branch name, event)], numbered 1, 2, ... over the branches in order."""
    out = []
    for name, g in branches.items():
        for ev in nltopo_plot.events(g):
            out.append((len(out) + 1, name, ev))
    return out


def panel_top(branches, bands, ref):
    """The top of panel (a): the reference branch and the optical band with
    room; what lies above goes to the upper panel (a, above)."""
    w = np.asarray(branches[ref].omega) * int(branches[ref].get("period_multiple", 1))
    return max(float(w.max()), bands[1][1]) * 1.06


def clip_y(x, y, lo, hi):
    """The polyline (x on a log axis) inside lo <= y <= hi: the points outside
    NaN, the crossings of lo and hi added, so that a line ends on the edge."""
    x, y = np.asarray(x, float), np.asarray(y, float)
    ox, oy = [], []
    for k in range(len(x)):
        if k and np.isfinite(y[k - 1]) and np.isfinite(y[k]):
            for edge in (lo, hi):
                if (y[k - 1] - edge) * (y[k] - edge) < 0:
                    f = (edge - y[k - 1]) / (y[k] - y[k - 1])
                    ox.append(np.exp(np.log(x[k - 1]) + f * (np.log(x[k]) - np.log(x[k - 1]))))
                    oy.append(edge)
        inside = lo <= y[k] <= hi
        ox.append(x[k] if inside else np.nan)
        oy.append(y[k] if inside else np.nan)
    return np.array(ox), np.array(oy)


def draw_branches(ax, branches, colour, ylim):
    """The branch lines, unstable stretches and interactions within ylim."""
    lo, hi = ylim
    for name, g in branches.items():
        m = int(g.get("period_multiple", 1))
        E, w = g.energy, m * g.omega
        lab = f"{name} ({g.points} pts)" + (f", {m} x omega" if m > 1 else "")
        inside = (w >= lo) & (w <= hi)
        ax.plot(*clip_y(E, w, lo, hi), "-", lw=1.1, color=colour[name], label=lab if inside.any() else "_" + lab, zorder=3)
        ax.plot(E[inside], w[inside], ".", ms=2.5, color=colour[name], zorder=3, label="_points")
        cls = nltopo_plot.stability_class(g)
        for c, (label, col, lw) in nltopo_plot.STRETCH.items():
            if (cls == c).any():
                x, y, at = nltopo_plot.stretches(E, w, cls == c)
                keep = (y >= lo) & (y <= hi)
                if not keep.any():
                    continue
                seen = {l.get_label() for l in ax.get_lines()}
                thin = lw < 3  # B-B (and unclassed): thin, the orbits ringed
                at = [i for i in at if keep[i]]
                ax.plot(np.where(keep, x, np.nan), np.where(keep, y, np.nan), "-", color=col, lw=lw, alpha=0.85, solid_capstyle="butt",
                        zorder=2 if not thin else 4, marker="o" if thin else None, ms=5, mfc="none", mec=col, markevery=at if thin else None,
                        label=label if label not in seen else "_" + label, gid=f"stretch {c}")
        for c, (label, col, mk) in nltopo_plot.VERDICT_MARK.items():  # stable-to and unresolved orbits
            sel = (cls == c) & inside
            if sel.any():
                seen = {l.get_label() for l in ax.get_lines()}
                ax.plot(E[sel], w[sel], mk, ms=5, color=col, zorder=4, label=label if label not in seen else "_" + label, gid=f"verdict {c}")
        inter = np.asarray(g.interactions).astype(int) if "interactions" in g else np.zeros(0, int)
        inter = inter[(w[inter] >= lo) & (w[inter] <= hi)] if len(inter) else inter
        if len(inter):
            seen = {l.get_label() for l in ax.get_lines()}
            ax.plot(E[inter], w[inter], "x", color=colour[name], ms=7, zorder=4,
                    label="modal interaction" if "modal interaction" not in seen else "_modal interaction")


def lettered(ax, g, bands):
    """The lettered orbits of the reference branch: the first one, E ~ 1, the
    first inside the linear optical band, and the last. Returns (picks, letters)."""
    E, w = g.energy, g.omega
    picks = [0, int(np.argmin(np.abs(np.log(E / 1.0))))]
    inside = np.nonzero(w >= bands[1][0])[0]
    if len(inside):
        picks.append(int(inside[0]))
    picks.append(len(E) - 1)
    picks = sorted(set(picks))
    letters = [chr(ord("a") + k) for k in range(len(picks))]
    ax.plot(E[picks], w[picks], "ks", mfc="none", ms=8, zorder=5, label="lettered orbits (panel c)")
    for L, i in zip(letters, picks):
        ax.annotate(L, (E[i], w[i]), textcoords="offset points", xytext=(-10, 6), fontsize=9, weight="bold", gid="letter")
    return picks, letters


def place_legend(ax, handles, ncol):
    """The legend in the corner of the panel over the fewest points of its
    lines; returns (the corner, whether it still covers some)."""
    pts, _ = obstacles(ax)
    renderer = ax.figure.canvas.get_renderer()
    best = None
    for loc in ("upper left", "lower left", "upper right", "lower right"):
        b = ax.legend(handles=handles, fontsize=6.5, loc=loc, ncol=ncol, framealpha=0.85).get_window_extent(renderer)
        n = int(((pts[:, 0] > b.x0 - 3) & (pts[:, 0] < b.x1 + 3) & (pts[:, 1] > b.y0 - 3) & (pts[:, 1] < b.y1 + 3)).sum()) if len(pts) else 0
        if best is None or n < best[0]:
            best = (n, loc)
        if n == 0:
            break
    ax.legend(handles=handles, fontsize=6.5, loc=best[1], ncol=ncol, framealpha=0.85)
    return best[1], best[0] > 0


def legend_headroom(ax, lo, top):
    """The top of a panel whose upper-left legend clears the lines beneath it."""
    fig = ax.figure
    box = ax.get_legend().get_window_extent(fig.canvas.get_renderer()).transformed(ax.transAxes.inverted())  # in axes fractions
    x0, x1 = (ax.transAxes + ax.transData.inverted()).transform([[box.x0, 0], [box.x1, 0]])[:, 0]
    under = [np.asarray(l.get_ydata(), float)[(np.asarray(l.get_xdata(), float) >= x0) & (np.asarray(l.get_xdata(), float) <= x1)]
             for l in ax.get_lines() if l.get_transform() == ax.transData and len(np.atleast_1d(l.get_xdata())) > 1]
    under = np.concatenate(under) if under else np.zeros(0)
    under = under[np.isfinite(under)]
    if not len(under):
        return top
    frac = 1 - box.y0 + 0.03  # the legend's share of the height, and a margin
    need = lo + (under.max() - lo) / max(1 - frac, 0.2)
    return max(top, need)


def obstacles(ax):
    """Display points of panel (a)'s lines (densified) and boxes of its legend and texts."""
    pts = []
    for l in ax.get_lines():
        if l.get_gid() == "event_anchor" or l.get_transform() != ax.transData:
            continue
        xy = ax.transData.transform(np.column_stack([l.get_xdata(), l.get_ydata()]).astype(float))
        for a, b in zip(xy[:-1], xy[1:]):
            if np.isfinite(a).all() and np.isfinite(b).all():
                k = max(2, int(np.hypot(*(b - a)) / 3))
                pts.append(a + np.linspace(0, 1, k)[:, None] * (b - a))
            elif np.isfinite(a).all():
                pts.append(a[None])
    renderer = ax.figure.canvas.get_renderer()
    boxes = [t.get_window_extent(renderer) for t in ax.texts]
    if ax.get_legend() is not None:
        boxes.append(ax.get_legend().get_window_extent(renderer))
    return (np.concatenate(pts) if pts else np.zeros((0, 2))), boxes


def crossings(ax_, ay_, cx, cy, segs):
    """For each candidate centre (cx, cy), how many of the segments segs
    [(x0, y0, x1, y1)] its leader from (ax_, ay_) crosses."""
    n = np.zeros(len(cx))
    for x0, y0, x1, y1 in segs:
        d1 = (x1 - x0) * (ay_ - y0) - (y1 - y0) * (ax_ - x0)
        d2 = (x1 - x0) * (cy - y0) - (y1 - y0) * (cx - x0)
        d3 = (cx - ax_) * (y0 - ay_) - (cy - ay_) * (x0 - ax_)
        d4 = (cx - ax_) * (y1 - ay_) - (cy - ay_) * (x1 - ax_)
        n += (d1 * d2 < 0) & (d3 * d4 < 0)
    return n


def seg_dist(px, py, ax_, ay_, cx, cy):
    """Distance of the point (px, py) from each segment (ax_, ay_) - (cx, cy)."""
    vx, vy = cx - ax_, cy - ay_
    t = np.clip(((px - ax_) * vx + (py - ay_) * vy) / np.maximum(vx * vx + vy * vy, 1e-9), 0, 1)
    return np.hypot(ax_ + t * vx - px, ay_ + t * vy - py)


def near_lines(pts, r, frame):
    """A pixel grid over frame: True within r of a point of pts (display)."""
    x0, y0, x1, y1 = frame
    grid = np.zeros((int(y1 - y0) + 1, int(x1 - x0) + 1), bool)
    if not len(pts):
        return grid
    p = np.round(pts - (x0, y0)).astype(int)
    k = np.arange(-int(np.ceil(r)), int(np.ceil(r)) + 1)
    for dx in k:
        for dy in k[np.hypot(dx, k) <= r]:
            gx, gy = p[:, 0] + dx, p[:, 1] + dy
            ok = (gx >= 0) & (gx < grid.shape[1]) & (gy >= 0) & (gy < grid.shape[0])
            grid[gy[ok], gx[ok]] = True
    return grid


def place(anchors, d, frame, pts, boxes):
    """Centres (display) for circles of diameter d, one per anchor, in order:
    the cheapest free place on a grid around its anchor (half a step of
    d + gap), inside frame, its box clear of the placed circles' boxes, clear
    of every anchor, of pts (lines) and of boxes (legend, texts); the cost is
    the leader's length plus a penalty for each leader it crosses and each
    placed circle it passes through. Lines are given up for an event with no
    free place clear of them."""
    s = 1.25 * d
    R = np.arange(-36, 37)
    dx, dy = np.meshgrid(R * s * 0.5, R[np.abs(R) <= 20] * s * 0.5)
    dx, dy = dx.ravel(), dy.ravel()
    keep = np.maximum(np.abs(dx), np.abs(dy)) >= 0.9 * s
    dx, dy = dx[keep], dy[keep]
    base = np.hypot(dx, 1.2 * dy)
    x0, y0, x1, y1 = frame
    blocked = near_lines(pts, d / 2 + 1.5, frame)
    placed, segs = [], []
    for ax_, ay_ in anchors:
        cx, cy = ax_ + dx, ay_ + dy
        ok = (cx > x0 + d / 2 + 2) & (cx < x1 - d / 2 - 2) & (cy > y0 + d / 2 + 2) & (cy < y1 - d / 2 - 2)
        cost = base + 4 * s * crossings(ax_, ay_, cx, cy, segs)
        for px, py in placed:
            ok &= np.maximum(np.abs(cx - px), np.abs(cy - py)) >= s
            cost += 4 * s * (seg_dist(px, py, ax_, ay_, cx, cy) < d / 2)
        for qx, qy in anchors:
            ok &= np.hypot(cx - qx, cy - qy) >= d / 2 + 2
        for b in boxes:
            ok &= ~((cx > b.x0 - d / 2) & (cx < b.x1 + d / 2) & (cy > b.y0 - d / 2) & (cy < b.y1 + d / 2))
        ix, iy = np.round(cx - x0).astype(int), np.round(cy - y0).astype(int)
        clear = ~blocked[np.clip(iy, 0, blocked.shape[0] - 1), np.clip(ix, 0, blocked.shape[1] - 1)]
        best = np.flatnonzero(ok & clear)
        if not len(best):
            best = np.flatnonzero(ok)
        if not len(best):
            best = np.arange(len(cx))
        i = best[np.argmin(cost[best])]
        placed.append((cx[i], cy[i]))
        segs.append((ax_, ay_, cx[i], cy[i]))
    return np.array(placed)


def event_omega(numbered, branches):
    """omega of each numbered event on its branch's drawn scale (period_multiple x omega)."""
    return np.array([int(branches[b].get("period_multiple", 1)) * ev.omega for _, b, ev in numbered])


def type_proxies(numbered, branches, ylim):
    """Legend handles of the event types within ylim, as draw_events draws them (not drawn)."""
    W = event_omega(numbered, branches)
    keys = {event_type(ev)[0] for (_, _, ev), w in zip(numbered, W) if ylim[0] <= w <= ylim[1]}
    return [matplotlib.lines.Line2D([], [], marker="o", ms=MARKER_PT, mfc=TYPES[k][1], mec="k", mew=0.7, ls="none", label=TYPES[k][0])
            for k in TYPES if k in keys]


def draw_events(ax, numbered, branches, ylim):
    """The numbered circles of the events within ylim, placed apart, with leader lines."""
    W = event_omega(numbered, branches)
    inside = (W >= ylim[0]) & (W <= ylim[1])
    numbered = [x for x, i in zip(numbered, inside) if i]
    if not numbered:
        return
    Wc = W[inside]
    fig = ax.figure
    pts, boxes = obstacles(ax)  # the layout is fixed (no tight_layout): the transforms hold without a draw
    E = np.array([ev.energy for _, _, ev in numbered])
    anchors = ax.transData.transform(np.column_stack([E, Wc]))
    order = np.lexsort((anchors[:, 1], anchors[:, 0]))
    d = MARKER_PT * fig.dpi / 72
    bb = ax.get_window_extent()
    centres = np.zeros_like(anchors)
    centres[order] = place(anchors[order], d, (bb.x0, bb.y0, bb.x1, bb.y1), pts, boxes)
    data = ax.transData.inverted().transform(centres)
    ax.plot(E, Wc, ".", color="k", ms=2.5, zorder=6, gid="event_anchor", label="_event positions")
    for (n, b, ev), (x, y), e, w in zip(numbered, data, E, Wc):
        ax.plot([e, x], [w, y], "-", color="0.35", lw=0.6, zorder=6, gid="event_leader", label="_leader")
        ax.text(x, y, str(n), ha="center", va="center", fontsize=6.5 if n < 100 else 5.2, zorder=8, gid=f"event_number {n}")
    keys = [event_type(ev)[0] for _, _, ev in numbered]
    for key in TYPES:
        sel = [i for i, k in enumerate(keys) if k == key]
        if sel:
            name, face = TYPES[key]
            ax.plot(data[sel, 0], data[sel, 1], "o", ms=MARKER_PT, mfc=face, mec="k", mew=0.7, ls="none", zorder=7, label=name, gid="event_markers")


TABLE_HEAD = "  #  idx type    class     omega         E"
TABLE_CHARS = 44  # the longest row: 3 + 1 + 4 + 1 + 7 + 1 + 5 + 1 + 9 + 1 + 9 characters, and room


def table_layout(n_rows):
    """(rows per block, blocks, font size, inches per block) of the events table."""
    fs = 8.0 if n_rows <= 34 else 6.5
    per = 34 if fs == 8.0 else 44
    blocks = max(1, -(-n_rows // per))
    return per, blocks, fs, TABLE_CHARS * 0.62 * fs / 72


def table_lines(numbered, branches, colour):
    """The table's rows: (text, colour, event number or None for a branch's header)."""
    lines = []
    for name in branches:
        rows = [(n, ev) for n, b, ev in numbered if b == name]
        if not rows:
            continue
        lines.append((name + ":", colour[name], None))
        m = int(branches[name].get("period_multiple", 1))
        for n, ev in rows:
            cls = ev.instability_name if ev.kind != 1 else ""
            lines.append((f"{n:>3} {ev.index:>4} {event_type(ev)[1]:<7} {cls:<5} {m * ev.omega:9.6f} {ev.energy:9.4g}", "k", n))
    return lines


def draw_table(ax, numbered, branches, colour):
    """The events table: blocks of rows side by side, a header row per branch."""
    ax.set_axis_off()
    lines = table_lines(numbered, branches, colour)
    per, nblocks, fs, block_in = table_layout(len(lines))
    width_in = ax.get_position().width * ax.figure.get_figwidth()
    if block_in * nblocks > width_in:  # a narrower slot than planned: a smaller font
        fs *= width_in / (block_in * nblocks)
        block_in = width_in / nblocks
    for j in range(nblocks):
        x = j * block_in / width_in
        ax.text(x, 1.0, TABLE_HEAD, transform=ax.transAxes, family="monospace", fontsize=fs, weight="bold", va="top", gid="event_table_head")
        for r, (text, col, n) in enumerate(lines[j * per:(j + 1) * per]):
            ax.text(x, 1.0 - (r + 1.4) / (per + 1.5), text, transform=ax.transAxes, family="monospace", fontsize=fs, va="top", color=col,
                    weight="bold" if n is None else "normal", gid=f"event_row {n}" if n is not None else "event_table_branch")
    ax.set_title("(T) located events\n(idx: -cont_switch <branch>:<idx>)", fontsize=9, loc="left")


def layout(branches, numbered, colour, top, wmax):
    """The figure and its panels: (a) (with the part above a broken axis,
    "a_up", when branches rise far above top), the events table "T" beside
    it (or (b) when there are no events), (b)-(e) below."""
    edges = [n for n in ("acoustic_top", "optical_bottom", "optical_top") if n in branches]
    lower = ["b", "c"] + (["d"] if edges else []) + (["e"] if any(g.get("parent", "") for g in branches.values()) else [])
    _, nblocks, _, block_in = table_layout(len(table_lines(numbered, branches, colour)))
    side = max(3.2, block_in * nblocks + 0.2) if numbered else 5.4
    fig = plt.figure(figsize=(12 + 1.1 * side, 11.5), dpi=DPI)
    gs = fig.add_gridspec(2, 1, height_ratios=[6.3, 4.4], hspace=0.28)
    top_gs = gs[0].subgridspec(1, 2, width_ratios=[11, side], wspace=0.12 if numbered else 0.22)
    panels = {}
    if wmax > 1.8 * top:  # branches far above the reference one: a compressed panel above, the axis broken
        a_gs = top_gs[0].subgridspec(2, 1, height_ratios=[2.1, 4.6], hspace=0.05)
        panels["a_up"] = fig.add_subplot(a_gs[0], gid="broken_axis_upper")
        panels["a"] = fig.add_subplot(a_gs[1], sharex=panels["a_up"])
    else:
        panels["a"] = fig.add_subplot(top_gs[0])
    if not numbered:
        lower.remove("b")
    panels["T" if numbered else "b"] = fig.add_subplot(top_gs[1])
    low_gs = gs[1].subgridspec(1, len(lower), wspace=0.28)
    for k, name in enumerate(lower):
        panels[name] = fig.add_subplot(low_gs[k])
    fig.subplots_adjust(left=0.05, right=0.985, top=0.965, bottom=0.1)
    return fig, panels, edges


def optical_band(ax, branches, lo, hi):
    """The nonlinear optical band between its edge NNMs, within lo..hi; True if drawn."""
    if "optical_bottom" not in branches or "optical_top" not in branches:
        return False
    b, t = branches["optical_bottom"], branches["optical_top"]
    lo_e, hi_e = max(b.energy.min(), t.energy.min()), min(b.energy.max(), t.energy.max())
    if hi_e <= lo_e:
        return False
    e = np.geomspace(lo_e, hi_e, 300)
    y1, y2 = np.clip(nltopo_plot.branch_omega(b, e), lo, hi), np.clip(nltopo_plot.branch_omega(t, e), lo, hi)
    if not (y2 > y1).any():
        return False
    ax.fill_between(e, y1, y2, where=y2 > y1, color="paleturquoise", alpha=0.6, lw=0, label="nonlinear optical band (edge NNMs)", zorder=1)
    return True


def draw_a(panels, branches, bands, colour, numbered, ref, top, wmax):
    """Panel (a): the FEP, in two parts when branches rise far above the
    reference one; returns the lettered orbits (picks, letters)."""
    ax_a, ax_u = panels["a"], panels.get("a_up")
    names = list(branches)
    low = min(bands[0][0], min(float(g.omega.min()) for g in branches.values())) * 0.95
    parts = [(ax_a, (low, top))] + ([(ax_u, (top, wmax * 1.04))] if ax_u is not None else [])
    band_drawn = False
    for ax, (lo, hi) in parts:
        for k, (blo, bhi) in enumerate(bands):
            if blo < hi and bhi > lo:
                ax.axhspan(max(blo, lo), min(bhi, hi), color="0.9", label="linear bands (infinite lattice)" if k == 0 or ax is ax_u else "_nolegend_", zorder=0)
        band_drawn |= optical_band(ax, branches, lo, hi)
        draw_branches(ax, branches, colour, (lo, hi))
        ax.set(xscale="log", ylim=(lo, hi), ylabel=r"$\omega$ (rad/time)")
    picks, letters = lettered(ax_a, branches[ref], bands)
    Emax = max(float(g.energy.max()) for g in branches.values())
    Emin = min(float(g.energy.min()) for g in branches.values())
    for a in [ax for ax, _ in parts] + [panels["b"]]:
        if Emin < 12 < Emax:
            a.axvline(12, color="k", ls="--", lw=0.8, label="E = 12 (paper)" if a is not ax_u else "_E = 12")
    ax_a.set(xlabel="energy E")
    title = "(a) frequency-energy plot: " + (", ".join(names) if len(names) <= 3 else f"{len(names)} NNM branches")
    if band_drawn:
        title += "; nonlinear optical band shaded"
    if ax_u is not None:
        ax_u.set_ylabel(r"$\omega$ (above)")
        ax_u.tick_params(labelbottom=False)
        ax_u.spines["bottom"].set_linestyle((0, (4, 3)))
        ax_a.spines["top"].set_linestyle((0, (4, 3)))
        title += " (the axis broken at the dashed line)"
    (ax_u or ax_a).set_title(title, fontsize=10)
    locs = {}
    for ax, ylim in parts:  # the legends as they will be, with the event types (their place is kept clear)
        handles = ax.get_legend_handles_labels()[0] + type_proxies(numbered, branches, ylim)
        locs[ax], covered = place_legend(ax, handles, ncol=2 if ax is ax_a else 4)
        if covered and ax is ax_a and ax_u is None:  # no free corner, nothing above: room above the lines
            locs[ax] = "upper left"
            ax.legend(handles=handles, fontsize=6.5, loc="upper left", ncol=2, framealpha=0.85)
            top = legend_headroom(ax_a, low, top)
            parts = [(ax_a, (low, top))]
            ax_a.set_ylim(low, top)
    for ax, ylim in parts:
        draw_events(ax, numbered, branches, ylim)
    if numbered:
        for ax, _ in parts:  # again: with the event types
            ax.legend(fontsize=6.5, loc=locs[ax], ncol=2 if ax is ax_a else 4, framealpha=0.85)
    return picks, letters


def draw_shapes(pc, g, ref, picks, letters):
    """Panel (c): the reference branch's shapes at the lettered orbits."""
    E, w = g.energy, g.omega
    N = g.z0.shape[1] // 2
    sites = np.arange(1, N + 1)
    for k, (L, i) in enumerate(zip(letters, picks)):
        u = g.z0[i, :N]
        u = u / np.abs(u).max()
        pc.plot(sites, u - 2.2 * k, ".-", ms=2.5, lw=0.8, color=nltopo_plot.branch_colour(k + 5), label=rf"{L}: E = {E[i]:.3g}, $\omega$ = {w[i]:.4f}")
    pc.set(xlabel="site", ylabel=r"$u_0 / \max|u_0|$ (offset by 2.2)", title=f"(c) {ref} NNM shapes at the lettered orbits")
    pc.legend(fontsize=7, loc="upper center", bbox_to_anchor=(0.5, -0.13), ncol=2)


def draw_edges(pd, branches, edges, colour):
    """Panel (d): the band-edge NNMs at the two ends of their branches."""
    for k, name in enumerate(edges):
        ge = branches[name]
        N = ge.z0.shape[1] // 2
        for j, style in ((0, "--"), (len(ge.energy) - 1, "-")):
            u = ge.z0[j, :N]
            u = u / np.abs(u).max()
            pd.plot(np.arange(1, N + 1), u - 2.5 * k, style, lw=0.8, color=colour[name], label=f"{name}, E = {ge.energy[j]:.3g}")
    pd.set(xlabel="site", ylabel=r"$u_0 / \max|u_0|$ (offset by 2.5)", title="(d) " + ", ".join(edges) + ": lowest (dashed), highest E")
    pd.title.set_fontsize(9)
    pd.legend(fontsize=7, loc="upper center", bbox_to_anchor=(0.5, -0.13), ncol=2)


def draw_switched(pe, branches, colour):
    """Panel (e): the switched families, the order parameter of the broken symmetry."""
    switched = [n for n in branches if branches[n].get("parent", "")]
    for name in switched:
        g = branches[name]
        z = g.z0
        n2 = z.shape[1] // 2
        r = np.linalg.norm(z[:, n2:], axis=1) / np.linalg.norm(z[:, :n2], axis=1)
        pe.plot(g.energy[1:], r[1:], ".-", ms=4, color=colour[name], label=f"{name} (from {g.parent})")
        # point 0 is the parent's orbit at the located event: at rest (|v0| = 0, drawn below the
        # family) on a linear mode's family, not on a switched one
        r0 = r[0] if r[0] > 1e-9 else max(r[1:].min() * 0.1, 1e-12)
        pe.plot(g.energy[0], r0, "*", ms=13, mfc="gold", mec="k", ls="none",
                label="_located event" if name != switched[0] else "located event (the parent's orbit; |v0| = 0 drawn below)")
    pe.set(xscale="log", yscale="log", xlabel="energy E", ylabel=r"$|v_0| / |u_0|$ at the section", title="(e) families born at branch points and period doublings")
    pe.title.set_fontsize(9)
    pe.legend(fontsize=7)


def figure(run, branches=None, bands=None):
    """The FEP figure of an open continuation run."""
    if branches is None:
        branches, bands = run.branches, nltopo_plot.bands(run.continuation)
    colour = {name: nltopo_plot.branch_colour(k) for k, name in enumerate(branches)}
    numbered = numbered_events(branches)
    ref = "insulated" if "insulated" in branches else list(branches)[0]
    top = panel_top(branches, bands, ref)
    wmax = max(float((int(g.get("period_multiple", 1)) * g.omega).max()) for g in branches.values())
    fig, panels, edges = layout(branches, numbered, colour, top, wmax)
    if "a_up" not in panels:
        top = max(top, wmax * 1.04)
    picks, letters = draw_a(panels, branches, bands, colour, numbered, ref, top, wmax)
    if numbered:
        draw_table(panels["T"], numbered, branches, colour)
    pb = panels["b"]
    for name, g in branches.items():
        pb.plot(g.energy, g.mcr, ".-", ms=3, color=colour[name], label=name)
    pb.set(xscale="log", xlabel="energy E", ylabel="MCR of u0", title="(b) localisation along the branches")
    pb.legend(fontsize=7)
    draw_shapes(panels["c"], branches[ref], ref, picks, letters)
    if edges:
        draw_edges(panels["d"], branches, edges, colour)
    if "e" in panels:
        draw_switched(panels["e"], branches, colour)
    return fig


if __name__ == "__main__":
    nltopo_plot.main_one_file(__doc__, "continuation", "fep", nltopo_plot.open_run, figure, dpi=DPI)
