#!/usr/bin/python3
"""Paper-style frequency-energy plot of -study continuation (the paper's Fig. 3):
(a) omega vs energy of every branch over the linear bands (grey), the
    nonlinear optical band shaded between its edge NNMs (the optical_bottom and
    optical_top branches), Floquet-unstable orbits, flagged modal interactions,
    the located bifurcations (-cont_bifurcations: folds, branch points, period
    doublings, Hamiltonian-Hopf onsets and ends) and lettered points on the
    insulated branch;
(b) the MCR of each orbit along the branches;
(c) the insulated NNM's shape u0 at the lettered points (normalised, offset);
(d) the band-edge NNMs' shapes at the lowest and the highest energy of their
    branches (only with acoustic_top, optical_bottom or optical_top);
(e) families born at branch points and period doublings (-cont_switch): how
    far each leaves its parent, |v0| / |u0| at the section (0 on a family of
    orbits that start at rest, as the linear modes' families do), against E,
    from the located point.
A family born at a period doubling has orbits of about twice its parent's
period: its omega (2 pi / period) is drawn times its period_multiple
attribute, on the parent's frequency scale, so that it meets its parent at
the located point.
usage: plot_fep.py fep.h5 [out.png]"""
import sys
import h5py
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np
import nltopo_plot

f = h5py.File(sys.argv[1], "r")
out = sys.argv[2] if len(sys.argv) > 2 else sys.argv[1].replace(".h5", "") + "_fep.png"
C = f["continuation"]
bands = nltopo_plot.bands(C)
names = list(C.keys())
colour = {name: f"C{k}" for k, name in enumerate(names)}
edges = [n for n in ("acoustic_top", "optical_bottom", "optical_top") if n in C]
def parent_of(name):
    p = C[name].attrs.get("parent", b"")
    return p.decode() if isinstance(p, bytes) else str(p)
switched = [n for n in names if parent_of(n)]
def multiple(name):  # omega x this: the frequency scale of the linear modes' families
    return int(C[name].attrs.get("period_multiple", 1))
npan = 3 + bool(edges) + bool(switched)
fig, ax = plt.subplots(1, npan, figsize=(5.4 * npan, 6))
ax = list(ax)
Emax = max(float(C[n]["energy"][:].max()) for n in names)

# (a) the FEP
for k, (lo, hi) in enumerate(bands):
    ax[0].axhspan(lo, hi, color="0.88", label="linear bands (infinite lattice)" if k == 0 else "_nolegend_")
if "optical_bottom" in C and "optical_top" in C:  # the nonlinear optical band between its edge NNMs, on their common energies
    b, t = C["optical_bottom"], C["optical_top"]
    lo_e, hi_e = max(b["energy"][:].min(), t["energy"][:].min()), min(b["energy"][:].max(), t["energy"][:].max())
    if hi_e > lo_e:
        e = np.geomspace(lo_e, hi_e, 200)
        ax[0].fill_between(e, nltopo_plot.branch_omega(b, e), nltopo_plot.branch_omega(t, e), color="tab:cyan", alpha=0.25, lw=0,
                           label="nonlinear optical band (edge NNMs)")
unstable_label, inter_label = "Floquet-unstable orbit", "modal interaction"
for name in names:
    g = C[name]
    m = multiple(name)
    E, w = g["energy"][:], m * g["omega"][:]
    ax[0].plot(E, w, ".-", ms=3, color=colour[name], label=f"{name} ({g.attrs['points']} pts)" + (f", {m} x omega" if m > 1 else ""))
    ax[1].plot(E, g["mcr"][:], ".-", ms=3, color=colour[name], label=name)
    if "stable" in g:
        bad = g["stable"][:] == 0
        if bad.any():
            ax[0].plot(E[bad], w[bad], "o", mfc="none", mec="r", ms=5, label=unstable_label)
            unstable_label = "_" + unstable_label
    if "bifurcations" in g and g["bifurcations"]["kind"].shape[0]:
        ev = g["bifurcations"]
        kind, d, eE, ew = ev["kind"][:], ev["direction"][:], ev["energy"][:], m * ev["omega"][:]
        for sel, marker, size, what in (((kind == 1), "D", 7, "energy fold"), ((kind == 2), "*", 13, "branch point (+1)"),
                                          ((kind == 3), "P", 9, "period doubling (-1)"),
                                          ((kind == 5) & (d > 0), "^", 7, "Hamiltonian-Hopf onset"), ((kind == 5) & (d < 0), "v", 7, "Hamiltonian-Hopf end")):
            if sel.any():
                label = f"{what} (located)"
                seen = {t.get_label() for t in ax[0].get_lines()}
                ax[0].plot(eE[sel], ew[sel], marker, ms=size, mfc="gold", mec="k", mew=0.7, ls="none", label=label if label not in seen else "_" + label)
    inter = g["interactions"][:].astype(int) if "interactions" in g else []
    if len(inter):
        ax[0].plot(E[inter], w[inter], "x", color=colour[name], ms=8, label=inter_label)
        inter_label = "_" + inter_label

# the lettered orbits of the insulated branch (or of the first branch): the
# first one, E ~ 1, the first inside the linear optical band, and the last
ref = "insulated" if "insulated" in C else names[0]
g = C[ref]
E, w = g["energy"][:], g["omega"][:]
picks = [0, int(np.argmin(np.abs(np.log(E / 1.0))))]
inside = np.nonzero(w >= bands[1][0])[0]
if len(inside):
    picks.append(int(inside[0]))
picks.append(len(E) - 1)
picks = sorted(set(picks))
letters = [chr(ord("a") + k) for k in range(len(picks))]
ax[0].plot(E[picks], w[picks], "ks", mfc="none", ms=8, label=f"lettered {ref} orbits (panel c)")
for L, i in zip(letters, picks):
    ax[0].annotate(L, (E[i], w[i]), textcoords="offset points", xytext=(-10, 6), fontsize=9, weight="bold")
if E.min() < 12 < Emax:
    ax[0].axvline(12, color="k", ls="--", lw=0.8, label="E = 12 (paper)")
    ax[1].axvline(12, color="k", ls="--", lw=0.8, label="E = 12 (paper)")
ax[0].set(xscale="log", xlabel="energy E", ylabel=r"$\omega$ (rad/s)", title="(a) NNM branches and the nonlinear optical band")
ax[0].legend(fontsize=7, loc="upper left")
ax[1].set(xscale="log", xlabel="energy E", ylabel="MCR of u0", title="(b) localisation along the branches")
ax[1].legend(fontsize=7)

# (c) the shapes at the lettered orbits
N = g["z0"].shape[1] // 2
sites = np.arange(1, N + 1)
for k, (L, i) in enumerate(zip(letters, picks)):
    u = g["z0"][i, :N]
    u = u / np.abs(u).max()
    ax[2].plot(sites, u - 2.2 * k, ".-", ms=2.5, lw=0.8, label=rf"{L}: E = {E[i]:.3g}, $\omega$ = {w[i]:.4f}")
ax[2].set(xlabel="site", ylabel=r"$u_0 / \max|u_0|$ (offset by 2.2)", title=f"(c) {ref} NNM shapes")
ax[2].legend(fontsize=7, loc="upper center", bbox_to_anchor=(0.5, -0.13), ncol=2)

# (d) the band-edge NNMs at the two ends of their branches
if edges:
    for k, name in enumerate(edges):
        ge = C[name]
        Ee = ge["energy"][:]
        for j, style in ((0, "--"), (len(Ee) - 1, "-")):
            u = ge["z0"][j, :N]
            u = u / np.abs(u).max()
            ax[3].plot(sites, u - 2.5 * k, style, lw=0.8, color=colour[name], label=f"{name}, E = {Ee[j]:.3g}")
    ax[3].set(xlabel="site", ylabel=r"$u_0 / \max|u_0|$ (offset by 2.5)", title="(d) band-edge NNMs: lowest (dashed), highest E")
    ax[3].legend(fontsize=7, loc="upper center", bbox_to_anchor=(0.5, -0.13), ncol=2)
# (e) the switched families: the order parameter of the broken symmetry
if switched:
    pe = ax[-1]
    for name in switched:
        g = C[name]
        z = g["z0"][:]
        n2 = z.shape[1] // 2
        r = np.linalg.norm(z[:, n2:], axis=1) / np.linalg.norm(z[:, :n2], axis=1)
        pe.plot(g["energy"][1:], r[1:], ".-", ms=4, color=colour[name], label=f"{name} (from {parent_of(name)})")
        # point 0 is the parent's orbit at the located event: at rest (|v0| = 0, drawn below the
        # family) on a linear mode's family, not on a switched one
        r0 = r[0] if r[0] > 1e-9 else max(r[1:].min() * 0.1, 1e-12)
        pe.plot(g["energy"][0], r0, "*", ms=13, mfc="gold", mec="k", ls="none",
                label="_located event" if name != switched[0] else "located event (the parent's orbit; |v0| = 0 drawn below)")
    pe.set(xscale="log", yscale="log", xlabel="energy E", ylabel=r"$|v_0| / |u_0|$ at the section",
           title="(e) families born at branch points and period doublings")
    pe.legend(fontsize=7)
fig.tight_layout()
fig.savefig(out, dpi=120)
print("wrote", out)
