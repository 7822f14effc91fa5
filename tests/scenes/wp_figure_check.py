#!/usr/bin/python3
"""The work-precision figure against its file (scenes workprecision and
workprecision_nnm): in every panel of the file's scene, one curve per method
holding exactly that method's (error, wall) pairs, limits that cover them,
the predictability floor drawn as a band up to spread_<observable>, and each
point labelled by its configuration's step or tolerance (the file's
/workprecision/accuracy, which names the setting of /workprecision/config).

usage: wp_figure_check.py <source dir> <workprecision.h5>"""
import importlib.util
import re
import sys
import h5py
import numpy as np

sys.path.insert(0, sys.argv[1] + "/src/plots")
spec = importlib.util.spec_from_file_location("pw", sys.argv[1] + "/src/plots/plot_workprecision.py")
pw = importlib.util.module_from_spec(spec)
spec.loader.exec_module(pw)
f = h5py.File(sys.argv[2], "r")
g = f["workprecision"]
method = [pw.text(m) for m in g["method"][:]]
config = [pw.text(c) for c in g["config"][:]]
accuracy = [pw.text(a) for a in g["accuracy"][:]]
wall = g["wall_seconds"][:]
G = pw.load(sys.argv[2])
# the labels name the setting the configuration's options give
for c, a in zip(config, accuracy):
    value = a.split()[1] if a.startswith(("dt ", "tol ")) else a.split()[0]
    assert re.search(r"(_dt|_rtol|_steps_per_period) " + re.escape(value) + r"( |$)", c), (c, a)
assert pw.accuracy_labels(G) == accuracy, pw.accuracy_labels(G)
fig = pw.figure(G)
labelled = 0
for ax, (o, _) in zip(fig.axes, pw.panels(G)):
    err = np.maximum(g["error_" + o][:], 1e-17)
    lines = [l for l in ax.get_lines() if l.get_label() in set(method)]
    assert sorted(l.get_label() for l in lines) == sorted(set(method)), (o, [l.get_label() for l in lines])
    for l in lines:
        idx = [k for k, m in enumerate(method) if m == l.get_label()]
        assert sorted(zip(l.get_xdata(), l.get_ydata())) == sorted(zip(err[idx], wall[idx])), (o, l.get_label())
    x0, x1 = ax.get_xlim()
    y0, y1 = ax.get_ylim()
    assert x0 <= err.min() and x1 >= err.max() and y0 <= wall.min() and y1 >= wall.max(), (o, ax.get_xlim(), ax.get_ylim())
    floor = g.attrs["spread_" + o]
    if floor > 0:
        band = [p for p in ax.patches if p.get_label() == "predictability floor"]
        assert len(band) == 1 and abs(band[0].get_xy()[:, 0].max() - floor) <= 1e-12 * floor, (o, floor)
        assert x0 <= floor, (o, x0, floor)
    # every configuration's point carries its accuracy label, in its method's colour
    labels = [t for t in ax.texts if t.get_gid() == "point_label"]
    assert len(labels) == len(method), (o, len(labels), len(method))
    colour = {l.get_label(): l.get_color() for l in lines}
    for k in range(len(method)):
        at = [t for t in labels if t.xy[0] == err[k] and t.xy[1] == wall[k]]
        assert len(at) >= 1 and accuracy[k] in [t.get_text() for t in at], (o, k, accuracy[k], [t.get_text() for t in at])
        assert any(t.get_color() == colour[method[k]] for t in at if t.get_text() == accuracy[k]), (o, k)
        labelled += 1
print(f"figure of {sys.argv[2]}: {len(set(method))} curves in each of {len(pw.panels(G))} panels hold the file's numbers; "
      f"{labelled} points labelled by their setting ({', '.join(dict.fromkeys(accuracy))})")
