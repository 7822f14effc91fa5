#!/usr/bin/python3
"""Floquet figure of a continuation branch (the paper's Fig. 4a-b; the
insulated branch by default), from -study continuation -floquet:
(a) the arguments of the Floquet multipliers against omega, coloured by their
    Krein signature (+1, -1, 0: real, or off the unit circle);
(b) every |mu| against omega, coloured by the orbit's verdict (stable;
    unstable-extended B-B; unstable-localized B-E or E-E: the eigenvector
    of its largest multiplier; stable-to(delta); unresolved);
(c) max |mu| - 1 along the branch (log), coloured by verdict, with the
    delta of each stable-to(delta) orbit;
(d) the branch's FEP coloured by class, with the orbits of a -study stability
    file (the 30,000-period runs, Fig. 4c) marked when one is given.
A -floquet_mf branch holds the leading pairs only: with its dense route
(floquet_route "dense") they are drawn like the full analysis; matrix-free
(no Krein signatures or classes) with (b) and (c) only, every orbit by its
verdict: unstable, or not decided (the matrix-free route cannot exclude a
Krein quadruplet).
The four panels of the full analysis stand in a 2 x 2 grid.
usage: plot_floquet.py fep.h5 [stability.h5] [branch] [out.png]
figure(run, stability, branch) builds the figure without saving it."""
import sys
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
import matplotlib.ticker
import numpy as np
import nltopo_plot


def load(fep_path, stability_path=None):
    """The continuation run and the -study stability cases [(energy, omega)] (or None)."""
    run = nltopo_plot.open_run(fep_path)
    cases = None
    if stability_path:
        cases = [(float(c.orbit_energy), float(c.attrs["omega"])) for c in nltopo_plot.open_run(stability_path).stability.cases]
    return run, cases


def figure(run, cases=None, branch="insulated"):
    g = run.branches.get(branch)
    if g is None or "multipliers_re" not in g:
        sys.exit(f"plot_floquet.py: /continuation/{branch} has no Floquet multipliers (run with -floquet)")
    E, w = g.energy, g.omega
    mu = g.multipliers_re + 1j * g.multipliers_im
    mm = g.max_modulus
    route = g.get("floquet_route", "")
    # -floquet_mf written matrix-free (or before its verdicts, without a route): no classes or
    # signatures; stable 0 unstable, -1 not decided (a Krein quadruplet is not excluded)
    mf = "floquet_products" in g and route != "dense"
    verdicts = "verdict" in g and np.all(np.asarray(g.verdict) >= 0)
    if verdicts:  # the verdict of each orbit, unstable ones by class (nltopo_plot.stability_class)
        cls = nltopo_plot.stability_class(g)
    elif mf:
        cls = np.select([g.stable == 0], [-1], -2)
    else:
        cls = np.asarray(g.instability).astype(int)
        cls[cls < 0] = -1   # the dense leading pairs: a class without an eigenvector
    classes = dict(nltopo_plot.INSTABILITY)
    classes[-1] = ("unstable (kind not computed)", "tab:red")
    classes[-2] = ("not decided (matrix-free: a Krein quadruplet is not excluded)", "0.55")
    if verdicts:
        classes.update({1: ("unstable-extended B-B", "tab:orange"), 2: ("unstable-localized B-E", "tab:purple"), 3: ("unstable-localized E-E", "tab:red"),
                        -3: (nltopo_plot.VERDICT_MARK[-3][0], nltopo_plot.VERDICT_MARK[-3][1]),
                        -4: (nltopo_plot.VERDICT_MARK[-4][0], nltopo_plot.VERDICT_MARK[-4][1])})
    has_krein = "krein" in g and not mf
    if has_krein:
        fig, axes = plt.subplots(2, 2, figsize=(12.5, 9.5))
        ax = list(axes.flat)
    else:
        fig, axes = plt.subplots(1, 2, figsize=(12.5, 4.8))
        ax = list(axes)
    W = np.broadcast_to(w[:, None], mu.shape)
    ok = np.isfinite(mu)

    if has_krein:  # (a) arguments by Krein signature
        K = g.krein
        for k, lab, c in ((1, r"$\mathcal{K}$ = +1", "tab:blue"), (-1, r"$\mathcal{K}$ = -1", "tab:orange"), (0, r"$\mathcal{K}$ = 0 (real, or off the circle)", "k")):
            sel = ok & (K == k)
            if sel.any():
                ax[0].scatter(W[sel], np.angle(mu[sel]) / np.pi, s=3 if k else 8, color=c, label=lab, zorder=3 if k == 0 else 2)
        ax[0].set(xlabel=r"$\omega$ (rad/time)", ylabel=r"arg $\mu$ / $\pi$")
        ax[0].set_title(f"(a) Krein signatures, {branch} branch", pad=22)
        ax[0].legend(fontsize=7, loc="lower center", bbox_to_anchor=(0.5, 1.0), ncol=3, markerscale=2, frameon=False)  # above: the data fill the panel
        a_mod, a_max = ax[1], ax[2]
    else:
        a_mod, a_max = ax[0], ax[1]

    # (b) |mu| by the orbit's class; (c) |max |mu| - 1| (numerical floor ~1e-13 .. 1e-8 on the circle)
    excess = np.maximum(np.abs(mm - 1), 1e-16)
    a_max.plot(w, excess, "-", color="0.7", lw=0.8, zorder=0)
    for c in sorted(set(cls.tolist())):
        lab, col = classes[c]
        rows = cls == c
        sel = ok & rows[:, None]
        a_mod.scatter(W[sel], np.abs(mu[sel]), s=3, color=col, label=f"{lab} ({rows.sum()} orbits)")
        a_max.plot(w[rows], excess[rows], "o", ms=4, color=col, label=lab)
    a_mod.set_yscale("log")
    a_mod.yaxis.set_major_formatter(matplotlib.ticker.FormatStrFormatter("%g"))
    a_mod.yaxis.set_minor_formatter(matplotlib.ticker.FormatStrFormatter("%g"))
    a_mod.set(xlabel=r"$\omega$ (rad/time)", ylabel=r"|$\mu$|", title="(b) |Floquet multipliers| by instability class" if has_krein else "(a) |Floquet multipliers|")
    a_mod.legend(fontsize=7, loc="best", markerscale=2)
    if verdicts and (cls == -3).any():  # what the long-lattice route resolved: nothing beyond 1 + delta
        a_max.plot(w[cls == -3], np.asarray(g.verdict_bound)[cls == -3], "v", ms=5, mfc="none", color="tab:green", label="delta of stable-to(delta)")
    tol = float(run.options.get("floquet_tol", 1e-6))
    a_max.axhline(tol, color="k", ls=":", lw=0.8, label=f"-floquet_tol {tol:g}")
    a_max.set(yscale="log", xlabel=r"$\omega$ (rad/time)", ylabel=r"|max |$\mu$| - 1|", title=("(c)" if has_krein else "(b)") + " largest multiplier: distance from the circle")
    a_max.legend(fontsize=7, loc="best")

    if has_krein:  # (d) the FEP by class, with the long runs
        ax[3].plot(E, w, "-", color="0.6", lw=0.8, zorder=0)
        for c in sorted(set(cls.tolist())):
            lab, col = classes[c]
            rows = cls == c
            ax[3].plot(E[rows], w[rows], "o", ms=4, color=col, label=lab)
        if cases:
            ax[3].plot([c[0] for c in cases], [c[1] for c in cases], "k*", ms=11, mfc="none", label="long runs (Fig. 4c)")
        ax[3].axhline(nltopo_plot.bands(run.continuation)[1][0], color="0.6", ls=":", lw=0.8)
        ax[3].set(xscale="log", xlabel="energy E", ylabel=r"$\omega$ (rad/time)", title=f"(d) {branch} branch by stability")
        ax[3].legend(fontsize=7, loc="upper left")
    fig.tight_layout()
    summary = "orbits by class: " + ", ".join(f"{classes[c][0]} {(cls == c).sum()}" for c in sorted(set(cls.tolist())))
    return fig, summary


def main(argv=None):
    p = nltopo_plot.parser(__doc__)
    p.add_argument("args", nargs="+", metavar="fep.h5 [stability.h5] [branch] [out.png]",
                   help="the continuation output (with -floquet), optionally a -study stability output, the branch (default insulated) and the PNG")
    a = p.parse_args(argv)
    h5 = [x for x in a.args if x.endswith(".h5")]
    png = [x for x in a.args if x.endswith(".png")]
    rest = [x for x in a.args if not x.endswith(".h5") and not x.endswith(".png")]
    if not h5:
        p.error("no .h5 file given")
    out = png[0] if png else h5[0].replace(".h5", "") + "_floquet.png"
    run, cases = load(h5[0], h5[1] if len(h5) > 1 else None)
    fig, summary = figure(run, cases, rest[0] if rest else "insulated")
    fig.savefig(out, dpi=120)
    print("wrote", out)
    print(summary)


if __name__ == "__main__":
    main()
