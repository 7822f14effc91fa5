#!/usr/bin/python3
"""The work-precision figure against its file (scenes workprecision and
workprecision_nnm): in every panel of the file's scene, one curve per method
holding exactly that method's (error, wall) pairs, limits that cover them,
and the predictability floor drawn as a band up to spread_<observable>.

usage: wp_figure_check.py <source dir> <workprecision.h5>"""
import importlib.util
import sys
import h5py
import numpy as np

spec = importlib.util.spec_from_file_location("pw", sys.argv[1] + "/src/plots/plot_workprecision.py")
pw = importlib.util.module_from_spec(spec)
spec.loader.exec_module(pw)
f = h5py.File(sys.argv[2], "r")
g = f["workprecision"]
method = [pw.text(m) for m in g["method"][:]]
wall = g["wall_seconds"][:]
fig = pw.figure(f)
for ax, (o, _) in zip(fig.axes, pw.panels(f)):
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
print(f"figure of {sys.argv[2]}: {len(set(method))} curves in each of {len(pw.panels(f))} panels hold the file's numbers")
