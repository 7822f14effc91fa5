#!/usr/bin/python3
"""Checks of the progress scene (tests/scenes/progress.sh); usage: progress.py STEP."""
import os
import re
import sys
sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
from scene_check import group, main, require


def lines():
    """Progress lines with an estimate of the time to go, the event count during location agreeing with the
    located events, and stdout in the order it was printed when piped."""
    out = open("piped.txt").read().splitlines()
    require(out[0].startswith("nltopo continuation:"), "the header comes first in a piped stdout", out[0])
    wrote = [i for i, l in enumerate(out) if l.strip() == "wrote p.h5"]
    require(len(wrote) == 1, "one write line")
    prog = [(i, re.search(r"progress: point (\d+), E ([0-9.e+-]+) of -cont_energy_max 20 \((\d+)% on a log scale\), "
                          r"[0-9.e+-]+ s so far, (about ([0-9.e+-]+) s to go|no estimate yet)", l)) for i, l in enumerate(out)]
    prog = [(i, m) for i, m in prog if m]
    require(len(prog) >= 10, "a progress line per point", len(prog))
    points = [int(m.group(1)) for _, m in prog]
    require(points == sorted(points), "progress lines in point order")
    pct = [int(m.group(3)) for _, m in prog]
    require(pct == sorted(pct) and pct[-1] >= 95, "the share done grows to the end", pct[-3:])
    require(sum(1 for _, m in prog if m.group(5)) >= len(prog) - 1, "every line but the first has an estimate")
    loc = [(i, re.search(r"locating: segment (\d+) of (\d+), (\d+) event\(s\) found", l)) for i, l in enumerate(out)]
    loc = [(i, m) for i, m in loc if m]
    require(len(loc) >= 10, "location progress lines", len(loc))
    seg = [int(m.group(1)) for _, m in loc]
    found = [int(m.group(3)) for _, m in loc]
    total = int(loc[0][1].group(2))
    require(seg == list(range(len(seg))) and len(seg) == total, "one line per segment, in order", seg[:5], total)
    require(found == sorted(found) and found[-1] > 0, "the event count grows during location", found[-3:])
    done = [l for l in out if re.search(r"\[insulated\] bifurcations: (\d+) event\(s\) located", l)]
    require(len(done) == 1, "one summary of the location")
    n_events = int(re.search(r"(\d+) event\(s\) located", done[0]).group(1))
    located = group("p.h5")["continuation/insulated/bifurcations/kind"].shape[0]
    require(n_events == located and found[-1] <= located, "the counts agree with the file", n_events, located, found[-1])
    # order: continuation progress, then location progress, then the summary
    require(prog[-1][0] < loc[0][0] < loc[-1][0] < out.index(done[0]) < wrote[0], "phases in the order they ran")


if __name__ == "__main__":
    main(globals())
