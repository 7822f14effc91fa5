#!/usr/bin/python3
"""Checks of the bifurcations scene (tests/scenes/bifurcations.sh); usage: bifurcations.py STEP [ARGUMENTS]."""
import os
import sys
sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
import numpy as np
from scene_check import attr_str, group, main, multipliers, rel, require


def event_rules(fn):
    """The events of the insulated branch in fn against its stored Floquet data, the Krein rule and the
    resonances: each located to tol between the two points it is reported after; one E-E branch point, where the
    stored points turn unstable. Returns (events, omega and index of the branch point)."""
    b = group(fn, "continuation/insulated")
    e = b["bifurcations"]
    tol = e.attrs["tol"]
    require(tol == 1e-7 and e.attrs["probes"] > 0)
    n = e["kind"].shape[0]
    N2 = b["z0"].shape[1]   # 2N
    for k in ("kind", "energy", "omega", "s", "multiplier_re", "multiplier_im", "direction", "point", "instability", "omega_bracket"):
        require(e[k].shape == (n,), k)
    require(e["krein"].shape == (n, 2) and e["resonance"].shape == (n, 2) and e["vector"].shape == (n, N2) and e["kind"].dtype.kind == "i")
    w, kind, d, pt = e["omega"][:], e["kind"][:], e["direction"][:], e["point"][:]
    require(np.all(e["omega_bracket"][:] <= tol))
    require(np.all(np.diff(e["s"][:]) >= 0))   # in the order of the branch
    omega = b["omega"][:]
    mu = multipliers(b)
    for i in range(n):
        # each event lies between the two points it is reported after
        lo, hi = sorted((omega[pt[i]], omega[pt[i] + 1]))
        require(lo - tol <= w[i] <= hi + tol, i, w[i], lo, hi)
        v = e["vector"][i]
        require(abs(np.linalg.norm(v) - 1) < 1e-10)
        if kind[i] == 5:  # Hamiltonian-Hopf: two pairs of opposite Krein signature collide
            require(e["krein"][i][0] * e["krein"][i][1] == -1, i, e["krein"][i])
            require(abs(abs(e["multiplier_re"][i] + 1j * e["multiplier_im"][i]) - 1) < 1e-3)
        if kind[i] == 4:  # Krein collision that passes: equal signatures, on the circle
            require(e["krein"][i][0] == e["krein"][i][1] != 0)
        if kind[i] == 6:  # internal resonance: an odd order (the NNM has the half-period symmetry), on the root
            p, q = e["resonance"][i]
            require(q >= 3 and q % 2 == 1 and 0 < 2 * p < q, p, q)
            th = 2 * np.pi * p / q
            require(abs(e["multiplier_re"][i] - np.cos(th)) < 1e-12 and abs(e["multiplier_im"][i] - np.sin(th)) < 1e-12)
            # the stored points on either side hold a circle multiplier near the root (the count below it
            # is no check: bulk multipliers cross it too, and only edge ones are located by default)
            for j in (pt[i], pt[i] + 1):
                m = mu[j][(np.abs(np.abs(mu[j]) - 1) < 1e-6) & (mu[j].imag > 0)]
                require(np.abs(np.angle(m) - th).min() < 0.1, i, j)
        else:
            require(tuple(e["resonance"][i]) == (0, 0))
    # the real E-E instability: one branch point, located to tol, where the stored points turn unstable
    bp = [i for i in range(n) if kind[i] == 2]
    require(len(bp) == 1, bp)
    i = bp[0]
    require(d[i] == 1 and e["instability"][i] == 3)
    require(abs(e["multiplier_re"][i] - 1) < 1e-3 and e["multiplier_im"][i] == 0)
    before, after = mu[pt[i]], mu[pt[i] + 1]
    require(np.abs(before).max() < 1 + 1e-6)                                  # stable before
    require(np.any((np.abs(after.imag) < 1e-12) & (after.real > 1.1)))        # a real pair beyond
    return e, w[i], i


def paper():
    """The events of the insulated branch of options/fep.opts (N = 102; the long test bifurcations_paper): the
    rules of event_rules, the weak B-E collisions of omega 1.7-1.9, the 1:3 resonance at omega 2.0275 and the E-E
    branch point at omega 2.418248."""
    e, wbp, _ = event_rules("paper.h5")
    n, w, kind = e["kind"].shape[0], e["omega"][:], e["kind"][:]
    # the weak B-E collisions of omega 1.7-1.9 (paper: B-E instabilities below the optical band)
    be = [(w[i], e["direction"][i]) for i in range(n) if kind[i] == 5 and e["instability"][i] == 2 and 1.7 < w[i] < 1.9]
    require(len(be) >= 4, be)
    # the 1:3 internal resonance of the edge pair below the branch point (omega 2.0275, E 34)
    res = [i for i in range(n) if kind[i] == 6 and abs(w[i] - 2.027498) < 1e-5]
    require(len(res) == 1 and tuple(e["resonance"][res[0]]) == (1, 3) and e["instability"][res[0]] == 3, res)
    require(abs(wbp - 2.418248) < 1e-5, wbp)
    print("bifurcations of the paper lattice OK:", n, "events, E-E branch point at omega", wbp)


def events():
    """The events of the insulated branch of the N = 22 lattice (s1.h5) by the rules of event_rules (the branch
    point at omega 2.418267); 1 = 2 ranks; passes and resonances found apart from the changes of stability.
    Writes the branch point's index to bp_index.txt. (The paper's N = 102 branch: paper(), the long test.)"""
    e, wbp, ibp = event_rules("s1.h5")
    require(abs(wbp - 2.418267) < 1e-5, wbp)
    tol = e.attrs["tol"]
    def load(fn):
        b = group(fn, "continuation/insulated")
        return b, b["bifurcations"]
    # 1 and 2 ranks: the same events on the small lattice
    (_, e1), (_, e2) = load("s1.h5"), load("s2.h5")
    k1, k2 = e1["kind"][:], e2["kind"][:]
    require(len(k1) > 0 and np.array_equal(k1, k2), k1, k2)
    require(np.abs(e1["omega"][:] - e2["omega"][:]).max() < 2 * tol)
    require(np.array_equal(e1["direction"][:], e2["direction"][:]))
    # Passes and resonances (kinds 4, 6) are found apart from the changes of stability: without them the
    # other events are the same ones, at the same omega
    (_, e0) = load("s0.h5")
    k0, keep = e0["kind"][:], ~np.isin(k1, (4, 6))
    require(not np.isin(k0, (4, 6)).any() and np.array_equal(k0, k1[keep]), k0, k1)
    require(np.abs(e0["omega"][:] - e1["omega"][:][keep]).max() < 2 * tol)
    require(np.isin(k1, (4,)).sum() >= 1 and np.isin(k1, (6,)).sum() >= 1)   # N = 22: E-E passes and 1:3 resonances
    # each resonance of the small lattice (every multiplier counts there): the stored spectra on either
    # side of its segment differ in how many lie in the half radian below the root, by at least as many as
    # are located there. (Not the count of all below it: a pair that leaves or joins the circle elsewhere in
    # the segment, e.g. at +1, changes that count too.)
    b1 = group("s1.h5", "continuation/insulated")
    mu1 = multipliers(b1)
    for r in np.flatnonzero(k1 == 6):
        p, q = e1["resonance"][r]
        th, j = 2 * np.pi * p / q, e1["point"][r]
        below = [((np.abs(np.abs(m) - 1) < 1e-6) & (m.imag > 0) & (np.angle(m) < th) & (np.angle(m) > th - 0.5)).sum()
                 for m in (mu1[j], mu1[j + 1])]
        same = [k for k in np.flatnonzero(k1 == 6) if e1["point"][k] == j and tuple(e1["resonance"][k]) == (p, q)]
        require(abs(below[1] - below[0]) >= len(same), r, below, same)   # (crossings no harmonic drives count too)
    print("bifurcations scene OK:", len(k1), "events on N = 22, E-E branch point at omega", wbp)
    open("bp_index.txt", "w").write(str(int(ibp)))


def switching(bp, fn):
    """-cont_switch at the branch point bp of the small lattice (in fn): the two families born there start at the
    located point, carry the parent and are time-reversal images of each other."""
    bp = int(bp)
    C = group(fn, "continuation")
    P, e = C["insulated"], C["insulated/bifurcations"]
    N = P["z0"].shape[1] // 2
    for side in ("plus", "minus"):
        b = C[f"insulated_bp{bp}_{side}"]
        require(attr_str(b, "parent") == f"insulated:{bp}")
        require(b.attrs["reached_energy_max"] == 1 and b["energy"].shape[0] > 5)
        # it starts at the located point: the parent's orbit there, at rest (v = 0 on the parent family)
        require(abs(b["omega"][0] - e["omega"][bp]) < 1e-6 and rel(b["energy"][0], e["energy"][bp]) < 1e-6)
        require(np.abs(b["z0"][0, N:]).max() < 1e-6 * np.abs(b["z0"][0, :N]).max())
        # and leaves the parent family: its orbits are not at rest at the section (the parent's all are)
        require(np.all(np.abs(b["z0"][1:, N:]).max(axis=1) > 1e-3 * np.abs(b["z0"][1:, :N]).max(axis=1)))
        require("bifurcations" in b and "multipliers_re" in b)
    pl, mi = C[f"insulated_bp{bp}_plus"], C[f"insulated_bp{bp}_minus"]
    n = min(pl["energy"].shape[0], mi["energy"].shape[0])
    # the two sides are time-reversal images: same u0, opposite v0, same frequency-energy curve
    require(np.abs(pl["z0"][:n, :N] - mi["z0"][:n, :N]).max() < 1e-6 * np.abs(pl["z0"][:n, :N]).max())
    require(np.abs(pl["z0"][:n, N:] + mi["z0"][:n, N:]).max() < 1e-6 * np.abs(pl["z0"][:n, :N]).max())
    # The same frequency-energy curve: two continuations whose step lengths differ by rounding, amplified by
    # the step control, sit at points slid along the curve (with OpenBLAS: dE/E 2.7e-7 by point 13, so
    # d omega 1.8e-7 at equal index): compare omega at equal energy, the slide removed to first order.
    Ep, Em, Wp, Wm = pl["energy"][:n], mi["energy"][:n], pl["omega"][:n], mi["omega"][:n]
    require(np.abs(Em / Ep - 1).max() < 1e-5, np.abs(Em / Ep - 1).max())   # the same points to within a slide
    slide = np.abs((Wm - Wp) - np.gradient(Wp, Ep) * (Em - Ep)).max()
    require(slide < 1e-7, slide)
    print("branch switching OK:", pl["energy"].shape[0], "points on each side from omega", pl["omega"][0])


def first_period_doubling(bp, fn):
    """Print the index of the first period doubling (onset) on the _plus family switched onto at bp (in fn)."""
    e = group(fn, f"continuation/insulated_bp{bp}_plus/bifurcations")
    k = [i for i in range(e["kind"].shape[0]) if e["kind"][i] == 3 and e["direction"][i] == 1]
    require(k, "no period doubling on the switched family")
    print(k[0])


def period_doubling(bp, pd):
    """-cont_switch at the period doubling pd of the family switched onto at bp: one doubled-period family,
    a closed loop, starting at the located point at half its frequency, with period_multiple 2."""
    pd = int(pd)
    C = group("pd.h5", "continuation")
    P = C[f"insulated_bp{bp}_plus"]
    e = P["bifurcations"]
    require(e["kind"][pd] == 3 and e["multiplier_re"][pd] < -1)
    D = C[f"insulated_bp{bp}_plus_pd{pd}"]
    require(f"insulated_bp{bp}_plus_pd{pd}_plus" not in C and f"insulated_bp{bp}_plus_pd{pd}_minus" not in C)  # one family
    require(attr_str(D, "parent") == f"insulated_bp{bp}_plus:{pd}")
    require(D.attrs["period_multiple"] == 2 and P.attrs["period_multiple"] == 1 and C["insulated"].attrs["period_multiple"] == 1)
    n = D["energy"].shape[0]
    # this family is a closed loop (it rises to a fold, falls to another and retraces itself): it stops where it began
    require(n > 5 and D.attrs["stop_reason"] == b"the family closed: it returned to its first orbit", D.attrs["stop_reason"])
    # point 0 is the parent's orbit at the located point, traversed twice: half its frequency
    require(abs(2 * D["omega"][0] - e["omega"][pd]) < 1e-7 and rel(D["energy"][0], e["energy"][pd]) < 1e-6)
    T0 = D["period"][0]
    require(np.all(rel(D["period"][:], T0) < 0.05))  # orbits of about twice the parent's period
    # ... whose multipliers are the parent's squared: the pair at -1 joins the trivial pair at +1
    mu = multipliers(D)[0]
    require(np.sum(np.abs(mu - 1) < 1e-2) >= 4, np.sort(np.abs(mu - 1))[:6])
    # the first step leaves along the critical eigenvector
    dz = D["z0"][1] - D["z0"][0]
    v = e["vector"][pd]
    require(abs(dz @ v) / np.linalg.norm(dz) > 0.9)
    print("period doubling switching OK:", n, "points from omega", e["omega"][pd], "(", D.attrs["stop_reason"].decode(), ")")


def resumed_families(full, resumed, stopped):
    """The switched families stopped part-way (stopped) and resumed (resumed) equal the run without a stop (full)
    bit for bit, every family resumed, not recomputed whole (the doubled one too, stopped inside its loop)."""
    A, B, H = (group(f, "continuation") for f in (full, resumed, stopped))
    require(sorted(A.keys()) == sorted(B.keys()) and len(A.keys()) == 4, list(A.keys()), list(B.keys()))
    for n in A.keys():
        a, b = A[n], B[n]
        require(n in H and 1 < H[n]["energy"].shape[0] < a["energy"].shape[0], n)   # resumed, not recomputed whole
        for k in ("energy", "omega", "z0", "multipliers_re", "multipliers_im", "bifurcations/omega", "bifurcations/kind"):
            require(np.array_equal(a[k][:], b[k][:]), n, k)
        for k in ("parent", "period_multiple", "stop_reason"):
            require(a.attrs[k] == b.attrs[k], n, k)
    print("resume of the switched families OK:", {n: B[n]["energy"].shape[0] for n in B.keys()})


if __name__ == "__main__":
    main(globals())
