"""Typed views of an output's groups (docs/python.md).

A view exposes its group's datasets as numpy arrays and its attributes as
Python values, both by their HDF5 names (`view.energy`, `view["energy"]`); a
name that is both (a stability case's `energy`) is the dataset, and
`view.attrs` holds every attribute. A name the file lacks raises MissingError
naming it, its group and the study (and options) that write it.
"""
from dataclasses import dataclass, field
from typing import Optional, Tuple

import numpy as np

from . import codes as _codes
from . import h5 as _h5


class NltopoError(Exception):
    """An output this reader cannot read (not an nltopo file, a newer format)."""


class MissingError(NltopoError, AttributeError):
    """A group, dataset or attribute the file does not hold. Its message names
    what is missing, the group, and which study (with which options) writes it."""


# What writes each group, most specific first (the group patterns of the schema, src/studies/*).
GROUP_WRITERS = [
    ("/linear/transition", "-study linear with -linear_gamma_list"),
    ("/linear/bloch", "-study linear"),
    ("/linear", "-study linear"),
    ("/simulate", "-study simulate"),
    ("/continuation/<branch>/codim2/<curve>", "-study continuation with -cont_codim2 (a located event followed in (E, p))"),
    ("/continuation/<branch>/codim2", "-study continuation with -cont_codim2 (a located event followed in (E, p))"),
    ("/continuation/<branch>/bifurcations", "-study continuation with -floquet (dense route) and -cont_bifurcations (on with -floquet)"),
    ("/continuation/<branch>", "-study continuation (-cont_branch names the branches)"),
    ("/continuation", "-study continuation"),
    ("/sweep", "-study sweep"),
    ("/zak", "-study zak"),
    ("/perturb/<kind>", "-study perturb (-perturb_kinds names the kinds)"),
    ("/perturb", "-study perturb"),
    ("/stability/case<k>", "-study stability (one case per -stability_omega)"),
    ("/stability", "-study stability"),
    ("/workprecision/recommended", "-study workprecision with -wp_target"),
    ("/workprecision", "-study workprecision"),
    ("/cost", "every study"),
    ("/", "every study"),
]

# Fields written only with some options: (group pattern, name) -> writer.
FIELD_WRITERS = {
    ("/continuation/<branch>", "multipliers_re"): "-study continuation with -floquet",
    ("/continuation/<branch>", "multipliers_im"): "-study continuation with -floquet",
    ("/continuation/<branch>", "krein"): "-study continuation with -floquet",
    ("/continuation/<branch>", "max_modulus"): "-study continuation with -floquet",
    ("/continuation/<branch>", "det_error"): "-study continuation with -floquet (dense route)",
    ("/continuation/<branch>", "stable"): "-study continuation with -floquet",
    ("/continuation/<branch>", "instability"): "-study continuation with -floquet",
    ("/continuation/<branch>", "floquet_route"): "-study continuation with -floquet_mf",
    ("/continuation/<branch>", "floquet_products"): "-study continuation with -floquet_mf",
    ("/simulate", "u"): "-study simulate with -sim_store_u 1 and -sim_sample_dt > 0",
    ("/linear", "modes"): "-study linear on its dense path (N <= -linear_dense_max)",
    ("/linear", "modes_selected"): "-study linear on its shift-invert path (N > -linear_dense_max)",
    ("/linear", "insulated_mode"): "-study linear on a lattice with an insulated mode",
    ("/sweep", "insulated_mode"): "-study sweep on a lattice with an insulated mode",
    ("/workprecision", "recommended"): "-study workprecision with -wp_target",
}


def writer_of(group, name=None):
    """Which study (and options) writes a group, or a field of it."""
    if name is not None:
        for (pattern, n), w in FIELD_WRITERS.items():
            if n == name and _codes.group_matches(pattern, group):
                return w
    for pattern, w in GROUP_WRITERS:
        if _codes.group_matches(pattern, group):
            return w
    return "no study nltopo knows"


def missing(run, group, name=None, kind="group"):
    where = group if name is None else f"{group.rstrip('/')}/{name}"
    return MissingError(f"{run.path}: no {kind} {where} in this -study {run.study} output; "
                        f"{writer_of(group, name)} writes it")


class Group:
    """One HDF5 group: datasets (numpy arrays) and attributes by name."""

    def __init__(self, run, path):
        self._run = run
        self._path = path.rstrip("/") or "/"
        self._cache = {}
        if self._path not in run.file:
            raise missing(run, self._path)
        g = run.file[self._path]
        self._datasets = [k for k in g.keys() if not hasattr(g[k], "keys")]
        self._subgroups = [k for k in g.keys() if hasattr(g[k], "keys")]
        # the `fields` table describes the others (docs/outputs.md): it is not one of the group's values
        self.attrs = {k: _h5.value(v) for k, v in g.attrs.items() if k != "fields"}
        self._fields_table = np.asarray(g.attrs["fields"]) if "fields" in g.attrs else None

    # names -------------------------------------------------------------
    @property
    def path(self):
        return self._path

    @property
    def run(self):
        return self._run

    @property
    def datasets(self):
        """Names of the group's datasets."""
        return list(self._datasets)

    @property
    def groups(self):
        """Names of its subgroups."""
        return list(self._subgroups)

    def keys(self):
        return self.datasets + [a for a in self.attrs if a not in self._datasets]

    def __contains__(self, name):
        return name in self._datasets or name in self.attrs or name in self._subgroups

    def __dir__(self):
        return sorted(set(super().__dir__()) | set(self.keys()))

    def __repr__(self):
        return f"<nltopo {type(self).__name__} {self._path}: datasets {self._datasets}, attributes {sorted(self.attrs)}>"

    # values ------------------------------------------------------------
    def __getitem__(self, name):
        if name in self._datasets:
            if name not in self._cache:
                self._cache[name] = _h5.array(self._run.file[self._join(name)])
            return self._cache[name]
        if name in self.attrs:
            return self.attrs[name]
        if any(n == name and _codes.group_matches(p, self._path) for p, n in FIELD_WRITERS):
            raise missing(self._run, self._path, name, "dataset or attribute")
        raise MissingError(f"{self._run.path}: no dataset or attribute {name!r} in {self._path}, which holds "
                           f"datasets {', '.join(self._datasets) or '(none)'}; attributes {', '.join(sorted(self.attrs)) or '(none)'}"
                           + (f"; groups {', '.join(self._subgroups)}" if self._subgroups else ""))

    def __getattr__(self, name):
        if name.startswith("_"):
            raise AttributeError(name)
        prop = getattr(type(self), name, None)
        if isinstance(prop, property):  # a property that raised: its own error, not "no dataset <name>"
            return prop.fget(self)
        return self[name]

    def get(self, name, default=None):
        return self[name] if name in self._datasets or name in self.attrs else default

    def _join(self, name):
        return (self._path if self._path != "/" else "") + "/" + name

    # self-description ---------------------------------------------------
    def describe(self, name):
        """(description, units) of a dataset or attribute of this group."""
        return self._run.describe(self._join(name))

    def codes(self, name):
        """{int: meaning} of an integer-code dataset or attribute of this group."""
        return self._run.codes(self._join(name))

    def decode(self, name, full=False):
        """An integer-code field as names (numpy array of str, same shape):
        the short name ("B-B"), or with full=True the whole meaning."""
        table = self.codes(name)
        v = self[name]
        f = (lambda c: table.get(int(c), f"unknown code {int(c)}")) if full else \
            (lambda c: _codes.short(table[int(c)]) if int(c) in table else f"unknown code {int(c)}")
        if np.ndim(v) == 0:
            return f(v)
        a = np.asarray(v)
        return np.array([f(c) for c in a.reshape(-1)], dtype=object).reshape(a.shape).astype(str)

    @property
    def fields(self):
        """{attribute name: (units, description, codes)} from the group's
        `fields` table (format >= 1; {} in a format-0 file)."""
        if self._fields_table is None or self._run.format_version < 1:
            return {}
        return {r["name"]: (r.get("units", ""), r.get("description", ""), r.get("codes", ""))
                for r in _h5.table(self._fields_table)}


# ---------------------------------------------------------------------------
# continuation

@dataclass
class Event:
    """One located event of /continuation/<branch>/bifurcations, decoded."""
    branch: str
    index: int  # its row: -cont_switch <branch>:<index>
    kind: int
    kind_name: str  # short meaning of kind: "energy fold", "branch point", ...
    direction: int  # +1 an instability begins along the branch, -1 it ends
    omega: float
    energy: float
    s: float
    instability: int
    instability_name: str  # "none", "B-B", "B-E", "E-E"
    multiplier: complex
    krein: Tuple[int, int]
    point: int  # the continuation point the event follows
    resonance: Optional[Tuple[int, int]]  # (p, q) of exp(2 pi i p/q) for kind 6, else None
    omega_bracket: float
    vector: np.ndarray = field(repr=False)
    kind_meaning: str = ""  # the whole meaning of kind, from the file's codes (or the built-in table)

    @property
    def label(self):
        """"<branch>:<index>", as -cont_switch names an event."""
        return f"{self.branch}:{self.index}"


class Branch(Group):
    """/continuation/<branch>: one NNM family, a point per orbit.

    Arrays energy, omega, period, mcr, z0, ...; with -floquet multipliers
    (complex), krein, max_modulus, stable, instability, the verdicts (verdict,
    verdict_name, verdict_bound, verdict_efold, verdict_reason); `events` the located
    bifurcations, decoded."""

    def __init__(self, run, path):
        super().__init__(run, path)
        self.name = self._path.rsplit("/", 1)[-1]

    @property
    def floquet(self):
        """Whether the branch carries Floquet multipliers (-floquet)."""
        return "multipliers_re" in self._datasets

    @property
    def multipliers(self):
        """Floquet multipliers, complex, npts x 2N (dense) or npts x nev (-floquet_mf)."""
        if not self.floquet:
            raise missing(self._run, self._path, "multipliers_re", "dataset")
        return self["multipliers_re"] + 1j * self["multipliers_im"]

    @property
    def krein_map(self):
        """The Krein resonance map of the branch (/continuation/<branch>/krein_map, written with
        -floquet): per orbit where opposite-signature collisions can occur from the linear dispersion."""
        if "krein_map" not in self._subgroups:
            raise missing(self._run, self._path + "/krein_map")
        return Group(self._run, self._path + "/krein_map")

    @property
    def located(self):
        """Whether the branch's bifurcations were located (a bifurcations group)."""
        return "bifurcations" in self._subgroups

    @property
    def bifurcations(self):
        """The raw /continuation/<branch>/bifurcations group (tol, probes, seconds, arrays)."""
        if "_bif" not in self._cache:
            self._cache["_bif"] = Group(self._run, self._path + "/bifurcations")
        return self._cache["_bif"]

    @property
    def codim2(self):
        """The -cont_codim2 curves of its events: dict curve name (e.g. "fold5") -> Codim2Curve ({} without)."""
        if "codim2" not in self._subgroups:
            return {}
        g = self._run.file[self._path + "/codim2"]
        return {n: Codim2Curve(self._run, self._path + "/codim2/" + n) for n in g.keys()}

    @property
    def stable_name(self):
        """`stable` decoded: "stable", "unstable", "not decided" per point."""
        return self.decode("stable")

    @property
    def instability_name(self):
        """`instability` decoded: "none", "B-B", "B-E", "E-E" (or "not computed") per point."""
        return self.decode("instability")

    @property
    def verdict_name(self):
        """`verdict` decoded per point: "stable", "unstable-localized", "unstable-extended",
        "stable-to", "unresolved" (with verdict_bound, verdict_efold, verdict_reason)."""
        return self.decode("verdict")

    @property
    def events(self):
        """The located events as a list of Event (MissingError without location)."""
        if "_events" in self._cache:
            return self._cache["_events"]
        b = self.bifurcations
        n = len(b["kind"]) if "kind" in b else 0
        kinds = b.codes("kind") if n else {}
        inst = b.codes("instability") if n else {}
        out = []
        for i in range(n):
            k, ins = int(b["kind"][i]), int(b["instability"][i])
            res = tuple(int(x) for x in b["resonance"][i]) if "resonance" in b else (0, 0)
            out.append(Event(branch=self.name, index=i, kind=k,
                             kind_name=_codes.short(kinds.get(k, f"unknown kind {k}")),
                             direction=int(b["direction"][i]), omega=float(b["omega"][i]),
                             energy=float(b["energy"][i]), s=float(b["s"][i]), instability=ins,
                             instability_name=_codes.short(inst.get(ins, f"unknown class {ins}")),
                             multiplier=complex(b["multiplier_re"][i], b["multiplier_im"][i]),
                             krein=tuple(int(x) for x in b["krein"][i]), point=int(b["point"][i]),
                             resonance=res if any(res) else None, omega_bracket=float(b["omega_bracket"][i]),
                             vector=b["vector"][i], kind_meaning=kinds.get(k, "")))
        self._cache["_events"] = out
        return out


class Codim2Curve(Group):
    """/continuation/<branch>/codim2/<curve>: a located event followed in (E, p) (-cont_codim2).

    Arrays p (along the curve: the side where p first decreases, reversed, then the other), energy, omega, period, test (the kind's test function, 0 on the
    curve), max_modulus; `multipliers` (complex, npts x 4, nearest the kind's critical point);
    attributes parameter (the option, e.g. "-lattice_gamma"), kind (`kind_name` decoded), event
    (its row in the branch's bifurcations), event_point (the curve's row at the event), stop_reason.
    Its codim-2 points (row-aligned arrays point_kind, point_p, point_energy, point_omega, point_arc):
    `points`, with `point_kind_name` decoded ("end of the curve", "turn in p", ...)."""

    def __init__(self, run, path):
        super().__init__(run, path)
        self.name = self._path.rsplit("/", 1)[-1]

    @property
    def multipliers(self):
        return self["multipliers_re"] + 1j * self["multipliers_im"]

    @property
    def kind_name(self):
        return self.decode("kind")

    @property
    def point_kind_name(self):
        """point_kind decoded per codim-2 point (numpy array of str; empty in a file written before them)."""
        return self.decode("point_kind") if "point_kind" in self else np.array([], dtype=str)

    @property
    def points(self):
        """The codim-2 points in order along the curve: list of dicts kind, kind_name, p, energy, omega,
        arc (fractional row of p, energy, ...); [] in a file written before them."""
        if "point_kind" not in self:
            return []
        names = self.point_kind_name
        return [dict(kind=int(k), kind_name=str(n), p=float(p), energy=float(e), omega=float(w), arc=float(a))
                for k, n, p, e, w, a in zip(self["point_kind"], names, self["point_p"], self["point_energy"],
                                            self["point_omega"], self["point_arc"])]


class StabilityMapSize(Group):
    """/stabilitymap/cells<c>: one lattice size of the map. Arrays region (np x ne, codes of the
    instability class: `region_name` decodes), branch_* (the branch at p_base), event_* (its located
    events; event_curve the curve each lies on), curve_* (one row per curve); attributes N, cells,
    inconsistent_columns. `curves`: dict curve name -> Codim2Curve, in the order of the curve_* rows."""

    @property
    def curves(self):
        if "_curves" not in self._cache:
            names = [n for n in str(self.attrs.get("curves", "")).split(",") if n]
            self._cache["_curves"] = {n: Codim2Curve(self._run, self._path + "/curves/" + n) for n in names}
        return self._cache["_curves"]

    @property
    def region_name(self):
        return self.decode("region")


class StabilityMap(Group):
    """/stabilitymap of -study stabilitymap: the raster's axes p and energy, the band edges and
    decay_cells against p; `sizes` (dict cells -> StabilityMapSize, ascending) and `checks` (the
    brute-force branches, list of groups in order, each with attribute p)."""

    @property
    def sizes(self):
        if "_sizes" not in self._cache:
            cells = sorted(int(n[5:]) for n in self._subgroups if n.startswith("cells"))
            self._cache["_sizes"] = {c: StabilityMapSize(self._run, f"{self._path}/cells{c}") for c in cells}
        return self._cache["_sizes"]

    @property
    def checks(self):
        if "checks" not in self._subgroups:
            return []
        g = Group(self._run, self._path + "/checks")
        return [Group(self._run, f"{self._path}/checks/check{k}") for k in range(len(g.groups))]


class Continuation(Group):
    """/continuation: the band-edge attributes (*_inf) and `branches`."""

    @property
    def branches(self):
        if "_branches" not in self._cache:
            self._cache["_branches"] = {n: Branch(self._run, self._path + "/" + n) for n in self._subgroups}
        return self._cache["_branches"]


# ---------------------------------------------------------------------------
# forced runs and maps

class Simulate(Group):
    """/simulate: t, energy, u (nt x sites stored), rms per site; mcr, t_off, ... attributes."""

    @property
    def N(self):
        """Sites of the lattice."""
        return len(self["rms"])

    @property
    def sites(self):
        """The sites whose u is stored: 0, u_stride, 2 u_stride, ... (columns of u)."""
        return np.arange(0, self.N, int(self.attrs.get("u_stride", 1)))

    def u_site(self, site):
        """u(t) of one site (a stored one: its index divisible by u_stride)."""
        stride = int(self.attrs.get("u_stride", 1))
        if site % stride or not 0 <= site < self.N:
            raise MissingError(f"{self._run.path}: site {site} is not stored in /simulate/u "
                               f"(u_stride {stride}, N {self.N}); -sim_store_u_stride 1 stores every site")
        return self["u"][:, site // stride]

    @property
    def even(self):
        """u of the stored even sites (columns), as the paper colours them."""
        return self["u"][:, self.sites % 2 == 0]

    @property
    def odd(self):
        return self["u"][:, self.sites % 2 == 1]


class Sweep(Group):
    """/sweep: maps (ne x no) over the axes energy (E*, rows) and omega (columns). A merged map
    (-study merge) reads like any sweep; a shard file (-sweep_shard i/n) holds only its points,
    1-D in the order of `shard_points` (their grid indices), and `maps` places them on the grid."""

    _NOT_MAPS = ("energy", "omega", "shard_points", "force_eta", "insulated_mode")

    @property
    def regime_name(self):
        """`regime` decoded per point (-sweep_lyapunov): "regular", "chaotic, the MCR statistically
        predictable", "unpredictable" or "not computed"."""
        return self.decode("regime")

    @property
    def axes(self):
        """(energy, omega): the rows' and the columns' values."""
        return self["energy"], self["omega"]

    @property
    def shape(self):
        return (len(self["energy"]), len(self["omega"]))

    @property
    def shard(self):
        """(i, n) of a shard file (-sweep_shard i/n); None for a whole map (a sweep or a merge)."""
        if "shard_points" not in self._datasets:
            return None
        return int(self.attrs["shard_index"]), int(self.attrs["shard_count"])

    @property
    def maps(self):
        """{name: ne x no array} of every per-point map; of a shard, masked arrays (numpy.ma)
        with the points of the other shards masked."""
        if self.shard is None:
            return {n: self[n] for n in self._datasets
                    if n not in self._NOT_MAPS and np.shape(self[n]) == self.shape}
        pts = np.asarray(self["shard_points"])
        out = {}
        for n in self._datasets:
            v = np.asarray(self[n])
            if n in self._NOT_MAPS or v.shape != pts.shape:
                continue
            m = np.ma.masked_all(self.shape[0] * self.shape[1], dtype=v.dtype)
            m[pts] = v
            out[n] = m.reshape(self.shape)
        return out

    @property
    def refined(self):
        """/sweep/refined of an adaptive refinement level (-sweep_refine_from): every point so far as
        scattered samples, 1-D arrays omega, energy, level (quadtree depth at which the point was
        added), omega_index, energy_index (fine lattice), done and every per-point score (mcr, kcorr,
        nl_ratio, predictable, ...); None for a grid. The base grid's points are also in `maps`."""
        if "_refined" not in self._cache:
            has = "refined" in self._subgroups
            self._cache["_refined"] = Group(self._run, self._path + "/refined") if has else None
        return self._cache["_refined"]

    def triangulation(self, log_energy=True):
        """A matplotlib.tri.Triangulation of the refined samples in (omega, log10 E*) (E* itself with
        log_energy False), or None for a grid."""
        r = self.refined
        if r is None:
            return None
        import matplotlib.tri as mtri
        e = np.asarray(r["energy"])
        return mtri.Triangulation(np.asarray(r["omega"]), np.log10(e) if log_energy else e)


class Linear(Group):
    """/linear: omega (ascending), modes (row j: mode j), insulated mode;
    `bands` /linear/bloch, `zak_phases`, `transition` /linear/transition."""

    @property
    def mode_matrix(self):
        """The stored modes, rows: `modes` (dense path) or `modes_selected` (shift-invert)."""
        return self["modes"] if "modes" in self._datasets else self["modes_selected"]

    @property
    def bands(self):
        """/linear/bloch: q, omega_acoustic, omega_optical and the *_inf band edges."""
        if "_bloch" not in self._cache:
            self._cache["_bloch"] = Group(self._run, self._path + "/bloch")
        return self._cache["_bloch"]

    bloch = bands

    @property
    def band_edges(self):
        """The infinite lattice's band edges {acoustic_bottom, acoustic_top, optical_bottom, optical_top}."""
        a = self.bands.attrs
        return {k: a[k + "_inf"] for k in ("acoustic_bottom", "acoustic_top", "optical_bottom", "optical_top")}

    @property
    def zak_phases(self):
        """{(cell, band): Zak phase}: cell "left"/"right", band "acoustic"/"optical"."""
        a = self.bands.attrs
        return {(c, b): a[f"zak_{c}_{b}"] for c in ("left", "right") for b in ("acoustic", "optical")}

    @property
    def transition(self):
        """/linear/transition (with -linear_gamma_list): gamma, omega (ng x N), zak_left, zak_right, bands_inf."""
        if "_tr" not in self._cache:
            self._cache["_tr"] = Group(self._run, self._path + "/transition")
        return self._cache["_tr"]


class Zak(Group):
    """/zak: phi_0, phi_pi and theta over the energies E*; the threshold attributes."""


class Kinds(Group):
    """A group of named subgroups (/perturb: chiral, achiral) by name and attribute."""

    def __init__(self, run, path, cls=Group):
        super().__init__(run, path)
        self._cls = cls

    @property
    def kinds(self):
        return list(self._subgroups)

    def __getitem__(self, name):
        if name in self._subgroups:
            key = "_g" + name
            if key not in self._cache:
                self._cache[key] = self._cls(self._run, self._path + "/" + name)
            return self._cache[key]
        return super().__getitem__(name)

    def items(self):
        return [(k, self[k]) for k in self._subgroups]

    def __iter__(self):
        return iter(self._subgroups)

    def __len__(self):
        return len(self._subgroups)


class Perturb(Kinds):
    """/perturb: one group per kind ("chiral", "achiral"): delta, energy, omega_ext,
    mcr (nd x ne x nens), insulated_omega (nd x nens), done."""


class StabilityCase(Group):
    """/stability/case<k>: t, corr, mcr, energy (per sample); multipliers (complex);
    omega, orbit_energy, period, max_modulus, floquet_stable, instability, persisted,
    omega_replaced (1: the branch's first orbit stands for omega_target)."""

    @property
    def multipliers(self):
        return self["multipliers_re"] + 1j * self["multipliers_im"]

    @property
    def orbit_energy(self):
        """The orbit's energy (the attribute `energy`; the dataset `energy` is E(t))."""
        return self.attrs["energy"]

    @property
    def instability_name(self):
        return self.decode("instability")


class Stability(Group):
    """/stability: `cases`, case0, case1, ... in order."""

    @property
    def cases(self):
        if "_cases" not in self._cache:
            names = sorted((n for n in self._subgroups if n.startswith("case") and n[4:].isdigit()), key=lambda n: int(n[4:]))
            self._cache["_cases"] = [StabilityCase(self._run, self._path + "/" + n) for n in names]
        return self._cache["_cases"]


class Workprecision(Group):
    """/workprecision: one entry per configuration (config, method, accuracy,
    wall_seconds, rhs_evals, steps, error_<observable>); floors and the reference."""

    @property
    def observables(self):
        return [n[len("error_"):] for n in self._datasets if n.startswith("error_")]

    @property
    def configs(self):
        """The configurations as option strings (list of str)."""
        return [str(c) for c in self["config"]]

    def _by_observable(self, prefix, attrs):
        src = self.attrs if attrs else {n: self[n] for n in self._datasets}
        return {n[len(prefix):]: v for n, v in src.items() if n.startswith(prefix)}

    @property
    def errors(self):
        """{observable: relative error per configuration}."""
        return self._by_observable("error_", False)

    @property
    def spread(self):
        """{observable: predictability floor}."""
        return self._by_observable("spread_", True)

    @property
    def reference_values(self):
        """{observable: the reference's value}."""
        return {k: v for k, v in self._by_observable("reference_", True).items()
                if not k.startswith("change_") and k not in ("converged", "wall_seconds")}

    @property
    def reference_change(self):
        return self._by_observable("reference_change_", True)

    @property
    def has_recommended(self):
        return "recommended" in self._datasets or "recommended" in self._subgroups

    @property
    def recommended(self):
        """/workprecision/recommended (with -wp_target): the cheapest configuration
        meeting the target per observable, as a list of dicts (a table) or a Group."""
        if "recommended" in self._subgroups:
            return Group(self._run, self._path + "/recommended")
        if "recommended" not in self._datasets:
            raise missing(self._run, self._path, "recommended", "dataset")
        ds = self._run.file[self._join("recommended")]
        return _h5.table(ds) if ds.dtype.names else self["recommended"]
