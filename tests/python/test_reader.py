"""nltopo.open on real outputs of every study (conftest.py writes them): the
reader's values equal h5py's raw ones, codes decode as the writer means them,
options read back as given, and the physics the files state holds."""
import math
import os
import subprocess
import sys

import h5py
import numpy as np
import pytest

import nltopo
from nltopo import codes as ncodes
from nltopo import options as noptions

from conftest import REPO, RUNS, STUDY, WP_CONFIGS, given_options


def raw(ds):
    """A dataset as h5py gives it, strings decoded by hand."""
    a = ds[()]
    if ds.dtype.names:
        return {n: [x.decode() if isinstance(x, bytes) else x for x in np.asarray(a[n]).reshape(-1)] for n in ds.dtype.names}
    a = np.asarray(a)
    if a.dtype.kind in "SO":
        return [x.decode() if isinstance(x, bytes) else x for x in a.reshape(-1)]
    return a


TABLES = ("fields", "options_table")  # the table attributes of format 1 (docs/outputs.md)


def raw_attr(v):
    if isinstance(v, bytes):
        return v.decode()
    if isinstance(v, np.ndarray) and v.size == 1:
        return v.reshape(-1)[0].item()
    return v.item() if hasattr(v, "item") else v


def same(a, b):
    return np.array_equal(np.asarray(a), np.asarray(b), equal_nan=np.asarray(a).dtype.kind == "f")


# ---------------------------------------------------------------------------
# every output

@pytest.mark.parametrize("name", list(RUNS))
def test_root(runs, name):
    r = runs[name]
    assert r.study == STUDY[name]
    assert r.complete is True
    assert r.format_version == nltopo.FORMAT_VERSION  # the binary writes the current format: every field described (test_describe)
    assert r.version and r.wall_seconds > 0
    assert r.cost["wall_seconds"] == r.wall_seconds
    with h5py.File(r.path) as f:
        assert r.format_version == (int(f.attrs["format_version"]) if "format_version" in f.attrs else 0)
        assert set(r.cost) == set(f["cost"].attrs)


@pytest.mark.parametrize("name", list(RUNS))
def test_every_dataset_and_attribute_equals_h5py(runs, name):
    """Every group as a view: its datasets and attributes are h5py's, decoded."""
    r = runs[name]
    seen = 0
    with h5py.File(r.path) as f:
        groups = [("/", f)]
        f.visititems(lambda n, o: groups.append(("/" + n, o)) if isinstance(o, h5py.Group) else None)
        for path, g in groups:
            view = r.group(path)
            for k, obj in g.items():
                if isinstance(obj, h5py.Dataset):
                    got, want = view[k], raw(obj)
                    if isinstance(want, dict):
                        assert {n: list(got[n].reshape(-1)) for n in got.dtype.names} == want, f"{path}/{k}"
                    elif isinstance(want, list):
                        assert list(np.asarray(got).reshape(-1)) == want, f"{path}/{k}"
                    else:
                        assert got.shape == want.shape and same(got, want), f"{path}/{k}"
                    seen += 1
            for k, v in g.attrs.items():
                if k in TABLES:  # tables of strings, read through describe, codes, fields and options
                    continue
                want = raw_attr(v)
                got = view.attrs[k]
                assert (got == want) or (isinstance(want, float) and math.isnan(want) and math.isnan(got)), f"{path} @{k}"
    assert seen > 0


@pytest.mark.parametrize("name", list(RUNS))
def test_options_read_back_as_given(runs, outputs, name):
    """Every option given (options file and command line) reads back with its exact value."""
    r = runs[name]
    given = given_options(name, str(outputs[name]))
    for k, v in given.items():
        assert k in r.options, f"-{k} missing from {sorted(r.options)}"
        assert r.options[k] == v, f"-{k}: {r.options[k]!r}, given {v!r}"
    # the options text parsed back agrees with the structured table (format 1), or is it (format 0)
    assert noptions.parse_text(r.options_text) == r.options
    if r.format_version >= 1:
        with h5py.File(r.path) as f:
            assert "options_table" in f.attrs and f.attrs["options_table"].dtype.names == ("key", "value")


def test_wp_configs_read_back_exactly(runs):
    """A value that itself holds options, with its leading space and commas."""
    r = runs["workprecision"]
    assert r.options["wp_configs"] == WP_CONFIGS
    assert r.options["wp_reference"] == " -sim_ts_type rkn -sim_ts_rkn_scheme dep1210"
    assert r.workprecision.configs == [c.strip() for c in WP_CONFIGS.split(",")]


def test_options_text_parser():
    # PETSc lists the keys sorted: an option-like token that sorts before the key is part of its value
    text = ("-a_flag -alpha -1e-3 -gamma -1:1:5 -list 1,2 -neg_inf -inf -wp_configs  -sim_ts_type rk -sim_ts_rtol 1e-6, "
            "-sim_ts_type symsplit -wp_twins 1 -zeta a b  c -zz ")
    assert noptions.parse_text(text) == {"a_flag": "", "alpha": "-1e-3", "gamma": "-1:1:5", "list": "1,2", "neg_inf": "-inf",
                                         "wp_configs": " -sim_ts_type rk -sim_ts_rtol 1e-6, -sim_ts_type symsplit",
                                         "wp_twins": "1", "zeta": "a b  c", "zz": ""}
    assert noptions.parse_effective("-a 1\n-b\n-c  -x 1\n") == {"a": "1", "b": "", "c": " -x 1"}


# ---------------------------------------------------------------------------
# codes and self-description

def test_codes_tables(runs):
    r = runs["fep"]
    b = r.branches["insulated"]
    assert r.codes(b.path + "/stable") == {1: "stable", 0: "unstable", -1: "not decided"}
    kinds = {k: ncodes.short(m) for k, m in b.bifurcations.codes("kind").items()}
    assert kinds == {1: "energy fold", 2: "branch point", 3: "period doubling", 4: "Krein collision",
                     5: "Hamiltonian-Hopf", 6: "internal resonance"}
    inst = {k: ncodes.short(m) for k, m in b.codes("instability").items()}
    assert {k: inst[k] for k in (0, 1, 2, 3)} == {0: "none", 1: "B-B", 2: "B-E", 3: "E-E"}
    assert r.codes(b.path + "/energy") == {}
    assert r.codes("/complete")[1] == "yes"
    if r.format_version >= 1:
        with h5py.File(r.path) as f:
            text = f[b.path + "/bifurcations/kind"].attrs["codes"]
        assert nltopo.parse_codes(text.decode() if isinstance(text, bytes) else text) == b.bifurcations.codes("kind")


def test_codes_parser():
    assert nltopo.parse_codes("1 stable; 0 unstable; -1 not decided") == {1: "stable", 0: "unstable", -1: "not decided"}
    # a meaning holding ";" that is not followed by a code stays whole
    assert nltopo.parse_codes("0 none; 1 B-B (bulk; edge); 2 x") == {0: "none", 1: "B-B (bulk; edge)", 2: "x"}
    assert ncodes.short("B-B (critical eigenvector in the bulk)") == "B-B"


@pytest.mark.parametrize("name", list(RUNS))
def test_describe(runs, name):
    r = runs[name]
    with h5py.File(r.path) as f:
        datasets = []
        f.visititems(lambda n, o: datasets.append("/" + n) if isinstance(o, h5py.Dataset) else None)
        attr_paths = [("/" + n if n else "") + "/" + a for n, o in [("", f)] + list(_groups(f)) for a in o.attrs if a != "fields"]
    if r.format_version < 1:
        with pytest.raises(nltopo.NltopoError, match="format_version 0"):
            r.describe(datasets[0])
        return
    for p in datasets:
        desc, units = r.describe(p)
        assert desc and units, p
    for p in attr_paths:
        desc, units = r.describe(p)
        assert desc and units, p
    # every group's attributes are in its fields table
    with h5py.File(r.path) as f:
        group_paths = ["/"] + ["/" + n for n, _ in _groups(f)]
    for path in group_paths:
        g = r.group(path)
        assert set(g.fields) == set(g.attrs), path


@pytest.mark.parametrize("name", list(RUNS))
def test_codes_in_file_equal_built_in_table(runs, name):
    """Format 1: the codes a file carries are the built-in table's (which decodes format 0), field for field."""
    r = runs[name]
    if r.format_version < 1:
        pytest.skip("format 0 carries no codes")
    with h5py.File(r.path) as f:
        groups = [("/", f)] + [("/" + n, o) for n, o in _groups(f)]
        for path, g in groups:
            names = [k for k, o in g.items() if isinstance(o, h5py.Dataset) and "codes" in o.attrs]
            names += [k for k, (_, _, c) in r.group(path).fields.items() if c]
            for k in names:
                built_in = ncodes.format0(path, k)
                assert built_in is not None, f"{path}/{k} carries codes the reader's table lacks"
                assert r.codes(f"{path.rstrip('/')}/{k}") == ncodes.parse(built_in), f"{path}/{k}"


def _groups(f):
    out = []
    f.visititems(lambda n, o: out.append((n, o)) if isinstance(o, h5py.Group) else None)
    return out


# ---------------------------------------------------------------------------
# continuation

def test_branch_floquet_and_stability_verdicts(runs):
    r = runs["fep"]
    b = r.branches["insulated"]
    assert list(r.branches) == ["insulated"]
    n = b.points
    for k in ("energy", "omega", "period", "mcr", "max_modulus", "stable", "instability"):
        assert len(b[k]) == n, k
    np.testing.assert_allclose(b.omega * b.period, 2 * np.pi, rtol=1e-12)
    mu = b.multipliers
    assert mu.shape == (n, b.z0.shape[1])  # 2N multipliers, dense route
    np.testing.assert_allclose(np.abs(mu).max(axis=1), b.max_modulus, rtol=1e-12)
    tol = float(r.options["floquet_tol"])
    assert np.array_equal(b.stable == 1, b.max_modulus <= 1 + tol)
    assert np.all(b.instability[b.stable == 1] == 0) and np.all(b.instability[b.stable == 0] > 0)
    assert set(b.stable_name) <= {"stable", "unstable"} and "unstable" in set(b.stable_name)
    assert list(b.instability_name) == [ncodes.short(b.codes("instability")[int(c)]) for c in b.instability]
    # the verdicts: the dense route says stable or unstable-* (confirmed), never stable-to; the bound,
    # e-folding time and class agree with the multipliers; every orbit has a reason
    v = list(b.verdict_name)
    assert set(v) <= {"stable", "unstable-localized", "unstable-extended", "unresolved"}
    assert [x == "stable" for x in v] == list(b.stable == 1)
    unstable = np.array([x.startswith("unstable") for x in v])
    np.testing.assert_allclose(b.verdict_bound[unstable], b.max_modulus[unstable] - 1, rtol=1e-9)
    np.testing.assert_allclose(b.verdict_efold[unstable], 1 / np.log(b.max_modulus[unstable]), rtol=1e-9)
    assert np.all(np.isinf(b.verdict_efold[~unstable])) and np.all(b.verdict_bound[b.stable == 1] == tol)
    assert [x == "unstable-localized" for x in v] == list(unstable & (b.instability >= 2))
    assert all(len(s) > 20 for s in b.verdict_reason)
    assert all("confirmed" in s for s, u in zip(b.verdict_reason, unstable) if u)


def test_krein_map(runs):
    b = runs["fep"].continuation.branches["insulated"]
    k = b.krein_map
    assert len(k.keys()) > 0 and k.path.endswith("/insulated/krein_map")
    with pytest.raises(nltopo.MissingError):
        runs["fep_plain"].continuation.branches[next(iter(runs["fep_plain"].continuation.branches))].krein_map


def test_events_decoded(runs):
    b = runs["fep"].branches["insulated"]
    ev = b.events
    raw_b = b.bifurcations
    assert len(ev) == len(raw_b.kind) > 0
    kinds = b.bifurcations.codes("kind")
    seen = set()
    for i, e in enumerate(ev):
        assert e.index == i and e.label == f"insulated:{i}"
        assert e.kind == raw_b.kind[i] and e.kind_name == ncodes.short(kinds[e.kind])
        assert e.omega == raw_b.omega[i] and e.energy == raw_b.energy[i] and e.s == raw_b.s[i]
        assert e.multiplier == complex(raw_b.multiplier_re[i], raw_b.multiplier_im[i])
        # a Krein pass (kind 4) neither begins nor ends an instability: direction 0
        assert e.direction == 0 if e.kind == 4 else e.direction in (-1, 1)
        assert e.instability_name in ("none", "B-B", "B-E", "E-E")
        assert (e.resonance is not None) == (e.kind == 6)
        if e.resonance:
            p, q = e.resonance
            assert q >= 3 and 0 < p < q
        # an event lies between the point it follows and the next one (to its final bracket)
        lo, hi = sorted((b.omega[e.point], b.omega[e.point + 1]))
        assert lo - e.omega_bracket <= e.omega <= hi + e.omega_bracket, e
        seen.add(e.kind_name)
    # this branch of the 5-cell lattice to E 300 crosses these (tests/scenes/bifurcations.sh, the small lattice)
    assert {"Hamiltonian-Hopf", "Krein collision", "branch point", "internal resonance"} <= seen
    # a Hamiltonian-Hopf collision has opposite Krein signatures
    assert all(e.krein[0] == -e.krein[1] for e in ev if e.kind == 5)


def test_codim2_curve(runs):
    b = runs["codim2"].branches["mode0"]
    assert len(b.codim2) == 1 and b.groups.count("codim2") == 1
    c = next(iter(b.codim2.values()))
    ev = b.events[c.event]
    assert c.name == f"fold{c.event}" and c.kind == 1 and c.kind_name == "energy fold" and ev.kind == 1
    assert c.parameter == "-lattice_cubic"
    assert np.all(np.diff(c.p) > 0) and c.p[0] < 0.35 and c.p[-1] > 0.75 and c.p[c.event_point] == 0.5
    # the event itself, and E Gamma, omega constant along the curve (the exact degeneracy of -lattice_cubic)
    assert abs(c.omega[c.event_point] - ev.omega) <= ev.omega_bracket  # (the run's -cont_bif_tol)
    assert np.allclose(c.energy * c.p, c.energy[c.event_point] * 0.5, rtol=1e-10, atol=0)
    assert np.allclose(c.omega, c.omega[c.event_point], rtol=1e-10, atol=0)
    assert c.multipliers.shape == (len(c.p), 4) and np.all(np.abs(c.multipliers - 1) < 1e-2)
    # its codim-2 points: both ends, at the bounds of -lattice_cubic (no turn in p on E Gamma = const)
    pts = c.points
    assert [q["kind_name"] for q in pts] == ["end of the curve", "end of the curve"] and list(c.point_kind_name) == ["end of the curve"] * 2
    assert [q["arc"] for q in pts] == [0, len(c.p) - 1] and pts[0]["p"] == c.p[0] and pts[-1]["energy"] == c.energy[-1]
    assert "point_arc" in c and c.codes("point_kind")[1] == "turn in p (dp/ds = 0, the curve goes on)"
    assert runs["fep"].branches["insulated"].codim2 == {}


def test_branches_without_floquet(runs):
    r = runs["fep_plain"]
    linear = runs["linear"].linear  # the same lattice
    assert sorted(r.branches) == sorted(r.options["cont_branch"].split(","))
    edges = r.continuation.attrs  # the band edges of the infinite lattice
    assert edges["acoustic_bottom_inf"] < edges["acoustic_top_inf"] < edges["optical_bottom_inf"] < edges["optical_top_inf"]
    for name, b in r.branches.items():
        assert not b.floquet and not b.located
        # -cont_energy_max is a stop test: the last point is the first past it
        assert b.reached_energy_max == 1 and b.energy[-2] < 1e-2 <= b.energy[-1]
        # each branch starts (E 1e-5) at a frequency of the linear study's finite lattice
        assert np.min(np.abs(linear.omega - b.omega[0])) < 1e-6 * b.omega[0], name
    b = r.branches["insulated"]
    with pytest.raises(nltopo.MissingError, match=r"bifurcations.*-floquet"):
        b.events
    with pytest.raises(nltopo.MissingError, match=r"multipliers.*-floquet"):
        b.multipliers
    with pytest.raises(AttributeError, match="which holds datasets"):
        b.no_such_name
    with pytest.raises(KeyError):
        r.branches["no_such_branch"]


def test_matrix_free_floquet(runs):
    r = runs["fep_mf"]
    b = r.branches["insulated"]
    nev = int(r.effective_options["floquet_mf_nev"])
    assert b.floquet and not b.located and b.floquet_route == "matrix-free"
    assert b.multipliers.shape == (b.points, nev)
    ok = np.isfinite(b.max_modulus)  # NaN: not converged
    np.testing.assert_allclose(np.abs(b.multipliers[ok]).max(axis=1), b.max_modulus[ok], rtol=1e-12)
    # matrix-free never decides "stable": -1 "not decided" (or 0 unstable); the class is not computed
    assert set(b.stable) <= {-1, 0} and set(b.stable_name) <= {"not decided", "unstable"}
    assert set(b.instability_name) == {"not computed"}
    assert b.floquet_undecided == np.count_nonzero(b.stable == -1)
    # the critical route bounds nothing on its own: unresolved with an infinite bound, or unstable-* confirmed
    v = b.verdict_name
    assert set(v) <= {"unresolved", "unstable-localized", "unstable-extended"}
    assert np.all(np.isinf(b.verdict_bound[v == "unresolved"]))
    assert all("quadruplet" in s or "converged" in s for s, x in zip(b.verdict_reason, v) if x == "unresolved")


# ---------------------------------------------------------------------------
# linear

def analytic_edges(k, gamma, gamma0):
    """Band edges of the infinite dimer lattice: omega^2 = gamma0 + 2k -+ k |(1 - g) + (1 + g) e^{iq}| at q = 0, pi."""
    return {"acoustic_bottom": math.sqrt(gamma0), "acoustic_top": math.sqrt(gamma0 + 2 * k - 2 * k * abs(gamma)),
            "optical_bottom": math.sqrt(gamma0 + 2 * k + 2 * k * abs(gamma)), "optical_top": math.sqrt(gamma0 + 4 * k)}


def test_linear(runs):
    r = runs["linear"]
    L = r.linear
    k, g, g0 = (float(r.options[n]) for n in ("lattice_k", "lattice_gamma", "lattice_gamma0"))
    edges = analytic_edges(k, g, g0)
    for n, v in edges.items():
        assert L.band_edges[n] == pytest.approx(v, rel=1e-12), n
    assert np.all(np.diff(L.omega) > 0) and len(L.omega) == L.N == L.mode_matrix.shape[0] == L.mode_matrix.shape[1]
    # the Bloch bands span their edges (q runs over [-pi, pi], 0 and pi included)
    B = L.bands
    assert len(B.q) == int(r.options["linear_nq"])
    assert B.omega_acoustic.min() == pytest.approx(edges["acoustic_bottom"], rel=1e-9)
    assert B.omega_acoustic.max() == pytest.approx(edges["acoustic_top"], rel=1e-9)
    assert B.omega_optical.min() == pytest.approx(edges["optical_bottom"], rel=1e-9)
    assert B.omega_optical.max() == pytest.approx(edges["optical_top"], rel=1e-9)
    # the insulated mode at sqrt(gamma0 + 2k) in the gap; every other mode in a band or an edge/interface mode
    assert L.insulated_omega == pytest.approx(math.sqrt(g0 + 2 * k), rel=1e-9)
    assert edges["acoustic_top"] < L.insulated_omega < edges["optical_bottom"]
    in_band = ((L.omega >= edges["acoustic_bottom"] - 1e-9) & (L.omega <= edges["acoustic_top"] + 1e-9)) | \
              ((L.omega >= edges["optical_bottom"] - 1e-9) & (L.omega <= edges["optical_top"] + 1e-9))
    assert 1 <= np.count_nonzero(~in_band) <= 4
    # the finite lattice's modes of the insulated cluster are in the gap, next to it
    cluster = L.omega[np.argsort(np.abs(L.omega - L.insulated_omega))[:L.insulated_cluster]]
    assert np.all((cluster > edges["acoustic_top"]) & (cluster < edges["optical_bottom"]))
    assert np.all(np.abs(cluster - L.insulated_omega) < 0.01)
    assert L.omega[L.optical_top_index] == L.optical_top
    # gamma = 0.4 > 0: the left cell is the topological one (Zak phase pi), the right one trivial
    z = L.zak_phases
    assert z[("left", "acoustic")] == pytest.approx(math.pi) and z[("right", "acoustic")] == pytest.approx(0, abs=1e-9)


def test_linear_transition(runs):
    r = runs["linear"]
    T = r.linear.transition
    k, g0 = float(r.options["lattice_k"]), float(r.options["lattice_gamma0"])
    np.testing.assert_allclose(T.gamma, np.linspace(-1, 1, 5), atol=1e-15)
    assert T.omega.shape == (5, r.linear.N) and np.all(np.diff(T.omega, axis=1) >= 0)
    for i, g in enumerate(T.gamma):
        e = analytic_edges(k, g, g0)
        np.testing.assert_allclose(T.bands_inf[i], [e["acoustic_bottom"], e["acoustic_top"], e["optical_bottom"], e["optical_top"]],
                                   rtol=1e-9)


def test_linear_missing_transition(runs, tmp_path):
    with h5py.File(runs["linear"].path) as f, h5py.File(tmp_path / "lin.h5", "w") as g:
        for k, v in f.attrs.items():
            g.attrs[k] = v
        f.copy(f["linear"], g, "linear")
        del g["linear/transition"]
    with nltopo.open(tmp_path / "lin.h5") as r:
        with pytest.raises(nltopo.MissingError, match=r"/linear/transition.*-study linear with -linear_gamma_list"):
            r.linear.transition
        with pytest.raises(nltopo.MissingError, match=r"no group /sweep.*-study sweep"):
            r.sweep


# ---------------------------------------------------------------------------
# forced runs

def test_simulate(runs):
    s = runs["simulate"].simulate
    assert np.all(np.diff(s.t) > 0) and s.u.shape == (len(s.t), s.N) and len(s.energy) == len(s.t)
    assert s.energy_reached == 1 and s.energy_final == pytest.approx(s.energy[-1], rel=1e-6)
    assert s.energy_star == float(runs["simulate"].options["force_energy"])
    assert 0 < s.t_off < s.t[-1] and 0 < s.mcr < 1
    assert np.array_equal(s.u_site(4), s.u[:, 4])
    assert s.even.shape[1] + s.odd.shape[1] == s.N
    strided = runs["simulate_stride"].simulate
    assert list(strided.sites) == list(range(0, strided.N, 3)) and strided.u.shape[1] == len(strided.sites)
    # the same run sub-sampled: its stored columns are the full run's sites 0, 3, 6, ...
    np.testing.assert_array_equal(strided.u_site(6), s.u[:, 6])
    with pytest.raises(nltopo.MissingError, match="u_stride 3"):
        strided.u_site(4)


def test_sweep(runs):
    r = runs["sweep"]
    w = r.sweep
    o = r.options
    E, W = w.axes
    np.testing.assert_allclose(E, np.geomspace(float(o["sweep_energy_min"]), float(o["sweep_energy_max"]), int(o["sweep_energy_n"])),
                               rtol=1e-12)
    np.testing.assert_allclose(W, np.linspace(float(o["sweep_omega_min"]), float(o["sweep_omega_max"]), int(o["sweep_omega_n"])),
                               rtol=1e-12)
    assert w.shape == (2, 3) and {"mcr", "kcorr", "t_off", "reached", "done"} <= set(w.maps)
    assert all(m.shape == w.shape for m in w.maps.values())
    assert np.all(w.done == 1) and w.points_done == 6
    assert set(np.unique(w.decode("reached"))) <= {"yes", "no"}
    # -sweep_lyapunov: the exponent at every point reached, the regime decoded from the file's codes
    assert np.all(np.isfinite(w.lyapunov[w.reached == 1])) and w.lyapunov_computed == 1
    names = set(ncodes.short(m) for m in w.codes("regime").values())
    assert set(np.unique(w.regime_name)) <= names and "regular" in names


def test_zak(runs):
    r = runs["zak"]
    z = r.zak
    np.testing.assert_allclose(z.energy, [0.01, 0.1])
    np.testing.assert_allclose(z.theta_mean, z.phipi_mean - z.phi0_mean, atol=1e-12)
    assert z.phi0_window_median.shape == (2, int(r.options["zak_windows"])) and z.done.shape == (2, 2)


def test_perturb(runs):
    r = runs["perturb"]
    p = r.perturb
    assert sorted(p.kinds) == sorted(r.options["perturb_kinds"].split(","))
    for kind, g in p.items():
        assert list(g.delta) == [0, 0.05] and list(g.energy) == [0.1]
        assert g.mcr.shape == (2, 1, 2) and g.insulated_omega.shape == (2, 2)
        assert np.all(g.done == 1)
        # delta = 0: every realisation is the unperturbed lattice
        assert g.insulated_omega[0, 0] == g.insulated_omega[0, 1]
    assert p["chiral"] is p.chiral


def test_stability(runs):
    r = runs["stability"]
    cases = r.stability.cases
    targets = [float(x) for x in r.options["stability_omega"].split(",")]
    assert len(cases) == len(targets) == r.stability.cases_done
    for c, w in zip(cases, targets):
        assert c.omega_target == w and len(c.multipliers) == len(c.multipliers_re)
        assert np.abs(c.multipliers).max() == pytest.approx(c.max_modulus, rel=1e-12)
        assert c.orbit_energy == c.attrs["energy"] and len(c.energy) == len(c.t)
    # the linear limit is stable; omega 2.5 (E ~ 90) past the E-E instability (tests/scenes/stability.sh)
    assert cases[0].floquet_stable == 1 and cases[0].instability_name == "none"
    assert cases[1].floquet_stable == 0 and cases[1].instability_name == "E-E"
    # the verdicts: stable at -floquet_tol; past it unstable-localized (E-E), confirmed, e-folding 1/ln|mu|
    assert cases[0].decode("verdict") == "stable" and cases[0].verdict_bound == float(r.effective_options["floquet_tol"])
    assert cases[1].decode("verdict") == "unstable-localized" and "confirmed" in cases[1].verdict_reason
    assert cases[1].verdict_bound == pytest.approx(cases[1].max_modulus - 1, rel=1e-9)
    assert cases[1].verdict_efold == pytest.approx(1 / np.log(cases[1].max_modulus), rel=1e-9)


def test_floquet_scaling(runs):
    r = runs["floquet_scaling"]
    top = r.floquet_scaling
    assert sorted(top.groups) == ["cells3", "cells5", "windows"] and top.sizes_done == 2
    w = r.group("/floquet_scaling/windows")
    assert list(w.N) == [14, 22] and w.envelope.shape == (1, 2)
    for k, c in enumerate((3, 5)):
        g = r.group(f"/floquet_scaling/cells{c}")
        assert w.envelope[0, k] == pytest.approx(np.max(g.max_modulus[g.energy < 1]) - 1, abs=1e-15)
        assert np.all((g.leading_participation >= 1) & (g.leading_participation <= g.N))
    assert ncodes.short(w.codes("verdict")[int(w.verdict[0])]) in ("stable", "persists", "finite-size", "undetermined")


def test_stabilitymap(runs):
    m = runs["stabilitymap"].stabilitymap
    assert list(m.sizes) == [5] and len(m.checks) == 1 and m.attrs["parameter"] == "-lattice_gamma"
    s = m.sizes[5]
    assert s.attrs["N"] == 22 and s.region.shape == (len(m.p), len(m.energy))
    names = set(np.unique(s.region_name))
    assert names <= {"stable", "B-E unstable", "E-E unstable"}, names
    assert len(s.curves) >= 1 and list(s.curves) == str(s.attrs["curves"]).split(",")
    c = next(iter(s.curves.values()))
    assert c.kind_name.startswith("Hamiltonian-Hopf") and np.all(np.abs(c.test) < 1e-10)
    k = int(c.attrs["event_point"])
    assert c.p[k] == pytest.approx(m.attrs["p_base"], abs=0)
    assert str(c.attrs["stop_reason"]).count("reached -cont_codim2_") == 2, c.attrs["stop_reason"]  # both sides left the window (p or E)
    ch = m.checks[0]
    assert ch.attrs["p"] == pytest.approx(0.405) and set(np.unique(ch.agree)) <= {-1, 0, 1}
    assert np.all(m.decay_cells > 0) and np.all(m.optical_bottom > m.acoustic_top)


def test_workprecision(runs):
    w = runs["workprecision"].workprecision
    nc = len(w.configs)
    assert nc == 2 and list(w.method) == ["rk", "symsplit"]
    assert set(w.errors) == set(w.observables) >= {"mcr", "t_off", "state"}
    assert all(len(e) == nc for e in w.errors.values())
    assert set(w.spread) == set(w.observables) and set(w.reference_change) == set(w.observables)
    assert w.reference_values["mcr"] == w.reference_mcr
    if w.has_recommended:
        assert w.recommended
    else:
        with pytest.raises(nltopo.MissingError, match="-wp_target"):
            w.recommended


# ---------------------------------------------------------------------------
# format versions

def test_newer_format_refused_in_one_line(runs, tmp_path):
    p = tmp_path / "future.h5"
    p.write_bytes(open(runs["simulate"].path, "rb").read())
    with h5py.File(p, "a") as f:
        f.attrs["format_version"] = np.int32(nltopo.FORMAT_VERSION + 1)
    with pytest.raises(nltopo.NltopoError) as e:
        nltopo.open(p)
    msg = str(e.value)
    assert "\n" not in msg and f"format_version {nltopo.FORMAT_VERSION + 1}" in msg


def test_not_an_output(tmp_path):
    p = tmp_path / "other.h5"
    with h5py.File(p, "w") as f:
        f["x"] = [1]
    with pytest.raises(nltopo.NltopoError, match="not an nltopo output"):
        nltopo.open(p)
    with pytest.raises(FileNotFoundError):
        nltopo.open(tmp_path / "absent.h5")


def test_example_script(outputs):
    """docs/python.md's example runs on real outputs."""
    files = [str(outputs[n]) for n in RUNS]
    p = subprocess.run([sys.executable, str(REPO / "python" / "examples" / "read_outputs.py")] + files,
                       capture_output=True, text=True, env=dict(os.environ, PYTHONPATH=str(REPO / "python")))
    assert p.returncode == 0, p.stderr
    for study in set(STUDY.values()):
        assert f"-study {study}" in p.stdout
    assert "branch point" in p.stdout and "wp_configs" in p.stdout


def test_docs_first_example(outputs, tmp_path, capsys):
    """docs/python.md's first example, as printed there, runs on a real fep.h5 and prints its events."""
    text = (REPO / "docs" / "python.md").read_text()
    code = text.split("```python\n", 1)[1].split("```", 1)[0]
    os.symlink(outputs["fep"], tmp_path / "fep.h5")
    cwd = os.getcwd()
    os.chdir(tmp_path)
    try:
        exec(compile(code, "docs/python.md", "exec"), {})
    finally:
        os.chdir(cwd)
    out = capsys.readouterr().out.splitlines()
    with nltopo.open(outputs["fep"]) as r:
        n_events = len(r.branches["insulated"].events)
    assert out[0].startswith("continuation 300 True") and n_events > 0 and len(out) == 2 + n_events, out[:3]
