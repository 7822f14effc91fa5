"""nltopo.open(path) -> Run: one nltopo output (docs/python.md)."""
import os

import h5py
import numpy as np

from . import codes as _codes
from . import h5 as _h5
from . import options as _options
from . import views as _views
from .views import MissingError, NltopoError

# The newest format_version this reader knows (docs/outputs.md); 0: a file without one.
FORMAT_VERSION = 1


class Run:
    """One nltopo output file, opened read-only.

    Root: study, version, options (dict), effective_options (dict), complete,
    format_version, wall_seconds, cost (dict of /cost). Groups: linear,
    simulate, continuation, branches, sweep, zak, perturb, stability,
    floquet_scaling, stabilitymap, workprecision (each raises MissingError if the file lacks it)."""

    def __init__(self, path):
        self.path = os.fspath(path)
        if not os.path.exists(self.path):
            raise FileNotFoundError(f"{self.path}: no such file")
        try:
            self.file = h5py.File(self.path, "r")
        except OSError as e:
            raise NltopoError(f"{self.path}: not an HDF5 file ({e})") from None
        try:
            self._read_root()
        except Exception:
            self.file.close()
            raise
        self._views = {}

    def _read_root(self):
        a = self.file.attrs
        if "study" not in a:
            raise NltopoError(f"{self.path}: not an nltopo output (no root attribute study)")
        self.format_version = int(_h5.value(a["format_version"])) if "format_version" in a else 0
        if self.format_version > FORMAT_VERSION:
            raise NltopoError(f"{self.path}: format_version {self.format_version} is newer than this reader knows "
                              f"({FORMAT_VERSION}); read it with the python/nltopo of the nltopo that wrote it")
        self.study = _h5.text(a["study"])
        self.version = _h5.text(a["version"]) if "version" in a else ""
        self.wall_seconds = float(_h5.value(a["wall_seconds"])) if "wall_seconds" in a else float("nan")
        self.complete = bool(_h5.value(a["complete"])) if "complete" in a else False
        self.options_text = _h5.text(a["options"]) if "options" in a else ""
        self.effective_options = _options.parse_effective(_h5.text(a["effective_options"])) \
            if "effective_options" in a else {}
        if self.format_version >= 1 and "options_table" in a:
            self.options = {r["key"]: r["value"] for r in _h5.table(np.asarray(a["options_table"]))}
        else:
            self.options = _options.parse_text(self.options_text)
        self.cost = {k: _h5.value(v) for k, v in self.file["cost"].attrs.items()} if "cost" in self.file else {}

    # context manager -----------------------------------------------------
    def close(self):
        self.file.close()

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()

    def __repr__(self):
        state = "complete" if self.complete else "incomplete"
        return f"<nltopo Run {self.path}: -study {self.study}, format {self.format_version}, {state}, groups {self.groups}>"

    @property
    def groups(self):
        """The top-level groups (linear, simulate, ..., cost)."""
        return [k for k in self.file.keys() if isinstance(self.file[k], h5py.Group)]

    @property
    def command_line(self):
        """The given options as one command line (values with spaces quoted)."""
        return _options.to_command_line(self.options)

    # self-description --------------------------------------------------
    def _split(self, path):
        path = "/" + path.strip("/")
        group, _, name = path.rpartition("/")
        return group or "/", name

    def _locate(self, path):
        """("dataset", h5py object) or ("attribute", group path, name) of a path."""
        path = "/" + path.strip("/")
        obj = self.file.get(path)
        if isinstance(obj, h5py.Dataset):
            return "dataset", obj
        group, name = self._split(path)
        g = self.file.get(group)
        if isinstance(g, h5py.Group) and name in g.attrs:
            return "attribute", group, name
        if isinstance(obj, h5py.Group):
            raise NltopoError(f"{self.path}: {path} is a group; describe a dataset or an attribute")
        raise _views.missing(self, group, name, "dataset or attribute")

    def _fields_row(self, group, name):
        g = self.file[group]
        if "fields" in g.attrs:
            for r in _h5.table(np.asarray(g.attrs["fields"])):
                if r.get("name") == name:
                    return r
        return None

    def describe(self, path):
        """(description, units) of a dataset, or of a group's attribute (from
        its group's `fields` table). Format 1 and newer; a format-0 file carries
        none and raises NltopoError."""
        loc = self._locate(path)
        if self.format_version < 1:
            raise NltopoError(f"{self.path}: format_version 0 carries no descriptions or units "
                              f"(docs/outputs.md describes {path})")
        if loc[0] == "dataset":
            at = loc[1].attrs
            if "description" not in at:
                raise MissingError(f"{self.path}: dataset {path} has no description attribute")
            return _h5.text(at["description"]), _h5.text(at.get("units", ""))
        row = self._fields_row(loc[1], loc[2])
        if row is None:
            raise MissingError(f"{self.path}: attribute {path} is not in the fields table of {loc[1]}")
        return row.get("description", ""), row.get("units", "")

    def codes(self, path):
        """{int: meaning} of an integer-code dataset or attribute: from its
        `codes` (format >= 1) or the built-in table of today's meanings (format 0).
        {} for a field that is not a code."""
        loc = self._locate(path)
        group = loc[1].parent.name if loc[0] == "dataset" else loc[1]
        name = loc[1].name.rsplit("/", 1)[-1] if loc[0] == "dataset" else loc[2]
        if self.format_version >= 1:
            if loc[0] == "dataset":
                text = _h5.text(loc[1].attrs["codes"]) if "codes" in loc[1].attrs else ""
            else:
                row = self._fields_row(group, name)
                text = row.get("codes", "") if row else ""
            if text:
                return _codes.parse(text)
            return {}
        text = _codes.format0(group, name)
        return _codes.parse(text) if text else {}

    # typed views -------------------------------------------------------
    def _view(self, key, cls, path, **kw):
        if key not in self._views:
            self._views[key] = cls(self, path, **kw)
        return self._views[key]

    def group(self, path):
        """Any group as a generic view."""
        return _views.Group(self, path)

    @property
    def linear(self):
        return self._view("linear", _views.Linear, "/linear")

    @property
    def simulate(self):
        return self._view("simulate", _views.Simulate, "/simulate")

    @property
    def continuation(self):
        return self._view("continuation", _views.Continuation, "/continuation")

    @property
    def branches(self):
        """{name: Branch} of /continuation/<branch>."""
        return self.continuation.branches

    @property
    def sweep(self):
        return self._view("sweep", _views.Sweep, "/sweep")

    @property
    def zak(self):
        return self._view("zak", _views.Zak, "/zak")

    @property
    def perturb(self):
        return self._view("perturb", _views.Perturb, "/perturb")

    @property
    def stability(self):
        return self._view("stability", _views.Stability, "/stability")

    @property
    def stabilitymap(self):
        """/stabilitymap of -study stabilitymap: its sizes (cells<c>: regions, curves, events) and checks (brute-force branches)."""
        return self._view("stabilitymap", _views.StabilityMap, "/stabilitymap")

    @property
    def floquet_scaling(self):
        """/floquet_scaling of -study floquet_scaling: its cells<c> groups (one branch per size) and windows (the fits)."""
        return self._view("floquet_scaling", _views.Group, "/floquet_scaling")

    @property
    def workprecision(self):
        return self._view("workprecision", _views.Workprecision, "/workprecision")


def open(path):  # noqa: A001 (nltopo.open, like h5py.File or builtins.open)
    """Opens an nltopo output; a Run (also a context manager)."""
    return Run(path)
