#!/usr/bin/python3
"""The FEP figure (src/plots/plot_fep.py) against its continuation file
(scene plots):

- events: each located event of the file is numbered once (1, 2, ... over
  the branches in order), its circle has the colour and legend entry of its
  type (passes, kind 4: KC; internal resonances, kind 6: R), a leader line
  runs from the circle to the event's (E, omega), no two circles' boxes
  overlap in display coordinates (plot_check.py rule 6), and the events
  table has its row: number, index on its branch, type, the class's short
  name from the file's codes ("B-B", not its whole meaning; none for a fold),
  omega, within the table's width;
- stability: the unstable stretches of each class the file holds are drawn
  (B-B, the paper's effectively stable, apart from B-E and E-E: its own
  colour, legend entry and rings on exactly the B-B orbits); none of a class
  the file does not hold;
- every rule of plot_check.py (data, limits, labels, legends, numbered
  markers apart);
- titles: panel (a)'s title names the branches drawn (or their number), and
  the nonlinear optical band only when it is shaded; panel (d)'s names only
  band-edge branches of the file.
Then it shows that it fails: the checked figures with a resonance's circle
removed, with a row giving a class's whole meaning, with two circles moved
onto each other, with a title naming a band that is not drawn, and with the
B-B stretch in the B-E colour, are each rejected.

usage: fep_figure_check.py <source dir> <fep.h5> [<fep.h5> ...]"""
import os
import sys
import matplotlib
matplotlib.use("Agg")
import matplotlib.colors
import matplotlib.pyplot as plt
import h5py
import numpy as np

src = sys.argv[1]
sys.path.insert(0, os.path.join(src, "src", "plots"))
sys.path.insert(0, os.path.join(src, "tests", "scenes"))
import nltopo_plot  # noqa: E402
import plot_check  # noqa: E402
import plot_fep  # noqa: E402


class Bad(AssertionError):
    pass


def require(cond, *what):
    if not cond:
        raise Bad(" ".join(str(w) for w in what))


# the type of each event kind (and direction) in the figure's legend, from the file's codes
KIND_TYPE = {1: "LP", 2: "BP", 3: "PD", 4: "KC", 6: "R"}


def class_names(ds):
    """{int: short name} of an instability dataset: its `codes` "v meaning; ..."
    (format >= 1), each meaning without its parenthesised remark."""
    text = ds.attrs["codes"]
    text = text.decode() if isinstance(text, bytes) else str(text)
    out = {}
    for part in text.split("; "):
        v, _, meaning = part.partition(" ")
        out[int(v)] = meaning.split(" (")[0]
    return out


def truth(path):
    """What the figure must show, read with h5py (not through the plots' loader):
    [(branch, {energy, omega (x period_multiple), cls per orbit, events})]."""
    out = []
    with h5py.File(path, "r") as f:
        for name, g in f["continuation"].items():
            m = int(g.attrs.get("period_multiple", 1))
            st = g["stable"][:] if "stable" in g else None
            ins = g["instability"][:] if "instability" in g else None
            cls = None if st is None else np.where(st == 1, 0, np.where(st == 0, np.where(ins > 0, ins, -1) if ins is not None else -1, -2))
            events = []
            if "bifurcations" in g:
                b = g["bifurcations"]
                names = class_names(b["instability"])
                for k in range(b["kind"].shape[0]):
                    kind, d = int(b["kind"][k]), int(b["direction"][k])
                    events.append(dict(index=k, kind=kind, energy=float(b["energy"][k]), omega=m * float(b["omega"][k]),
                                       type=KIND_TYPE.get(kind) or ("HH+" if d > 0 else "HH-"),
                                       cls="" if kind == 1 else names[int(b["instability"][k])]))
            out.append((name, dict(energy=g["energy"][:], omega=m * g["omega"][:], cls=cls, events=events)))
    return out


def markers(fig):
    """{number: (axes, display xy, type legend name)} of the event circles."""
    out = {}
    for ax in fig.axes:
        nums = {}
        for t in ax.texts:
            gid = t.get_gid() or ""
            if gid.startswith("event_number "):
                nums[tuple(np.round(t.get_position(), 12))] = int(gid.split()[1])
        for l in ax.get_lines():
            if l.get_gid() != "event_markers":
                continue
            for x, y in zip(l.get_xdata(), l.get_ydata()):
                n = nums.get(tuple(np.round((x, y), 12)))
                require(n is not None, "an event circle without its number at", (x, y))
                out[n] = (ax, (x, y), l.get_label())
    return out


def check_events(fig, file):
    numbered = [(b, ev) for b, g in file for ev in g["events"]]
    m = markers(fig)
    require(sorted(m) == list(range(1, len(numbered) + 1)), "event numbers", sorted(m)[:10], "for", len(numbered), "events")
    rows = {int(t.get_gid().split()[1]): t.get_text() for ax in fig.axes for t in ax.texts if (t.get_gid() or "").startswith("event_row ")}
    require(sorted(rows) == sorted(m), "table rows", sorted(rows)[:10])
    kinds = {4: 0, 6: 0}
    for n, (b, ev) in enumerate(numbered, 1):
        ax, (x, y), label = m[n]
        require(label == plot_fep.TYPES[ev["type"]][0], f"event {n} ({b}:{ev['index']}, kind {ev['kind']}) drawn as '{label}'")
        e, w = ev["energy"], ev["omega"]
        leaders = [l for l in ax.get_lines() if l.get_gid() == "event_leader" and np.allclose(l.get_xydata()[1], (x, y), rtol=1e-12)]
        require(len(leaders) == 1 and np.allclose(leaders[0].get_xydata()[0], (e, w), rtol=1e-12), f"event {n}: leader", leaders)
        lo, hi = ax.get_ylim()
        require(lo <= w <= hi and ax.get_xlim()[0] <= e <= ax.get_xlim()[1], f"event {n} at ({e}, {w}) outside its panel")
        words = rows[n].split()
        require(words[0] == str(n) and words[1] == str(ev["index"]) and words[2] == ev["type"] and f"{w:.6f}" in words, f"row {n}: '{rows[n]}'", ev)
        # the class column (after number, index and type: 3 + 1 + 4 + 1 + 7 + 1 characters), and the row within the table's width
        require(rows[n][17:].split(f"{w:.6f}")[0].strip() == ev["cls"] and len(rows[n]) <= plot_fep.TABLE_CHARS,
                f"row {n}: '{rows[n]}': class '{ev['cls']}' in {plot_fep.TABLE_CHARS} characters")
        if ev["kind"] in kinds:
            kinds[ev["kind"]] += 1
    drawn = {k: sum(1 for v in m.values() if v[2] == plot_fep.TYPES[t][0]) for k, t in ((4, "KC"), (6, "R"))}
    require(drawn == kinds, "passes and resonances drawn", drawn, "in the file", kinds)
    plot_check.check_numbered_markers(fig)  # rule 6: numbered, apart, each in the table
    return len(numbered), kinds


def check_stability(fig, file):
    lines = {}
    for a in fig.axes:
        for l in a.get_lines():
            gid = l.get_gid() or ""
            if gid.startswith("stretch "):
                lines.setdefault(int(gid.split()[1]), []).append(l)
    held = set()
    bb = []
    for name, g in file:
        if g["cls"] is None:
            continue
        held |= {int(c) for c in set(g["cls"].tolist()) if c in (1, 2, 3, -1)}
        bb += [(e, w) for e, w in zip(g["energy"][g["cls"] == 1], g["omega"][g["cls"] == 1])]
    require(set(lines) == held, "stretches drawn for classes", sorted(lines), "the file holds", sorted(held))
    colour = {c: {matplotlib.colors.to_hex(l.get_color()) for l in ls} for c, ls in lines.items()}
    if 1 in lines:
        for c in (2, 3):
            require(not (colour[1] & colour.get(c, set())), "B-B drawn in the colour of class", c, colour)
        require(all("B-B" in l.get_label() or l.get_label().startswith("_") for l in lines[1]), "B-B labels", [l.get_label() for l in lines[1]])
        entries = {t.get_text() for a in fig.axes if a.get_legend() for t in a.get_legend().get_texts()}
        require(any("B-B" in e for e in entries), "no B-B legend entry", entries)
        rings = []
        for l in lines[1]:
            xy = l.get_xydata()
            rings += [tuple(xy[i]) for i in (l.get_markevery() or [])]
        rings, bb = np.array(sorted(rings), float).reshape(-1, 2), np.array(sorted(bb), float).reshape(-1, 2)
        require(rings.shape == bb.shape and np.allclose(rings, bb, rtol=1e-12, atol=0), "B-B rings", rings, "B-B orbits", bb)
    return sorted(held), len(bb)


def check_titles(fig, file):
    names = [b for b, _ in file]
    title = next(a.get_title() for a in fig.axes if a.get_title().startswith("(a)"))
    listed = title.split(":", 1)[1].split(";")[0].split("(")[0].strip()
    if len(names) <= 3:
        require([n.strip() for n in listed.split(",")] == names, "title (a) lists", listed, "the file has", names)
    else:
        require(listed == f"{len(names)} NNM branches", "title (a):", listed)
    shaded = any(c.get_label() == "nonlinear optical band (edge NNMs)" for a in fig.axes for c in a.collections)
    require(("nonlinear optical band" in title) == shaded, "title (a) and the shaded band:", title, shaded)
    for a in fig.axes:
        if a.get_title().startswith("(d)"):
            named = a.get_title()[4:].split(":")[0].split(", ")
            require(all(n in names and n in ("acoustic_top", "optical_bottom", "optical_top") for n in named), "title (d) names", named)


def check(path):
    """Checks the FEP figure of the file at path (drawn as plot_fep.py draws
    it); returns (figure, truth, events, passes and resonances, classes, B-B orbits)."""
    file = truth(path)
    fig = plot_fep.figure(nltopo_plot.open_run(path))
    for line in plot_check.check_figure(fig, "plot_fep.py"):  # the rules of every figure (data, limits, labels, legends, ...)
        print("  " + line)
    n, kinds = check_events(fig, file)
    held, bb = check_stability(fig, file)
    check_titles(fig, file)
    return fig, file, n, kinds, held, bb


def must_fail(what, fig, file, spoil, step):
    """The check step of the (checked) figure spoiled by spoil(fig) raises."""
    spoil(fig)
    try:
        step(fig, file)
    except (Bad, plot_check.PlotCheckError) as e:
        print(f"  spoiled ({what}): rejected: {str(e)[:110]}")
        return
    raise SystemExit(f"fep_figure_check: a figure with {what} passes")


RESTORE = []  # (text artist, its text) of a spoiled row


def long_class(fig):
    """The first row with a class: that class's whole meaning, as the file's codes give it."""
    meaning = {"B-B": "B-B (critical eigenvector in the bulk)", "B-E": "B-E (between bulk and edge)", "E-E": "E-E (at the interface edge)"}
    for a in fig.axes:
        for t in a.texts:
            text = t.get_text()
            for short, whole in meaning.items():
                if (t.get_gid() or "").startswith("event_row ") and f" {short}  " in text:
                    RESTORE.append((t, text))
                    t.set_text(text.replace(f" {short}  ", f" {whole}", 1))
                    return


def recolour_bb(fig):
    be = [l for a in fig.axes for l in a.get_lines() if l.get_gid() in ("stretch 2", "stretch 3")]
    for a in fig.axes:
        for l in a.get_lines():
            if l.get_gid() == "stretch 1":
                l.set_color(be[0].get_color())


def drop_resonance(fig):
    for a in fig.axes:
        for l in a.get_lines():
            if l.get_gid() == "event_markers" and l.get_label() == plot_fep.TYPES["R"][0]:
                x, y = l.get_xdata(), l.get_ydata()
                l.set_data(x[1:], y[1:])
                return


def stack_two(fig):
    for a in fig.axes:
        for l in a.get_lines():
            if l.get_gid() == "event_markers" and len(l.get_xdata()) >= 2:
                x, y = np.array(l.get_xdata(), float), np.array(l.get_ydata(), float)
                # the second circle (and its number) 0.3 of a diameter beside the first, in display coordinates
                p = a.transData.transform([(x[0], y[0])])[0] + (0.3 * l.get_markersize() * fig.dpi / 72, 0)
                q = a.transData.inverted().transform([p])[0]
                for t in a.texts:
                    if tuple(np.round(t.get_position(), 12)) == tuple(np.round((x[1], y[1]), 12)):
                        t.set_position(q)
                x[1], y[1] = q
                l.set_data(x, y)
                return


def title_band(fig):
    for a in fig.axes:
        if a.get_title().startswith("(a)") and "nonlinear optical band" not in a.get_title():
            a.set_title(a.get_title() + "; nonlinear optical band shaded")


def main():
    checked = []
    for path in sys.argv[2:]:
        fig, file, n, kinds, held, bb = check(path)
        checked.append((fig, file, n, bb))
        print(f"FEP figure of {path}: {n} events numbered apart, each with its leader and table row "
              f"({kinds[4]} passes, {kinds[6]} resonances); unstable classes drawn {held}, {bb} B-B orbits ringed; titles match")
    # the checks fail: the checked figures spoiled, one rule after another
    fig, file = next((f, t) for f, t, n, _ in checked if n >= 2)
    must_fail("a class's whole meaning in the table", fig, file, long_class, check_events)
    for t, text in RESTORE:  # the row as drawn again, for the next spoil
        t.set_text(text)
    must_fail("a resonance not drawn", fig, file, drop_resonance, check_events)
    must_fail("two event circles on each other", fig, file, stack_two, lambda f, r: plot_check.check_numbered_markers(f))
    must_fail("a title naming a band that is not drawn", fig, file, title_band, check_titles)
    bb = [(f, r) for f, r, _, b in checked if b]
    if bb:
        must_fail("B-B drawn like B-E", bb[0][0], bb[0][1], recolour_bb, check_stability)
    print("fep_figure_check OK")


if __name__ == "__main__":
    main()
