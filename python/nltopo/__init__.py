"""nltopo: read nltopo's HDF5 outputs (docs/python.md).

    import nltopo
    with nltopo.open("fep.h5") as run:
        for name, b in run.branches.items():
            print(name, b.energy.max(), [e.kind_name for e in b.events])

Debian's python3 with h5py and numpy; importable with PYTHONPATH=<repo>/python.
Reads format_version 0 (files without the attribute) and 1; refuses a newer one.
"""
from .codes import parse as parse_codes
from .run import FORMAT_VERSION, Run, open
from .views import (Branch, Codim2Curve, Continuation, Event, Group, Linear, MissingError, NltopoError, Perturb, Simulate, Stability,
                    StabilityCase, Sweep, Workprecision, Zak)

__all__ = ["open", "Run", "FORMAT_VERSION", "NltopoError", "MissingError", "Group", "Branch", "Codim2Curve", "Event", "Continuation",
           "Linear", "Simulate", "Sweep", "Zak", "Perturb", "Stability", "StabilityCase", "Workprecision", "parse_codes"]
