"""What the scene checks share (tests/scenes/checks/<scene>.py).

A scene script, tests/scenes/<scene>.sh, runs nltopo and then, in its work
directory, calls one check step of its scene's file:

    $PY "$CHECKS/<scene>.py" <step> [arguments...]

Each step is a function of that file named after what it checks; it reads the
HDF5 outputs in the current directory, require()s what the scene promises and
prints one line saying what it found. A step that fails exits 1 with one
message naming the file, line and source of the failed require and its
context values. Rerun a step by hand from the scene's work directory, e.g.

    cd build/tests/scene_simulate && /usr/bin/python3 ../../../tests/scenes/checks/simulate.py paper

Debian's python3 (/usr/bin/python3, $PY in common.bash) with h5py and numpy.
"""
import ast
import linecache
import os
import sys
import textwrap

import h5py
import numpy as np


class CheckFailed(Exception):
    """A require() that does not hold."""


def _statement(filename, lineno):
    """The source of the statement that starts at filename:lineno (up to 20 lines)."""
    text = ""
    for k in range(lineno, lineno + 20):
        line = linecache.getline(filename, k)
        if not line:
            break
        text += line
        try:
            ast.parse(textwrap.dedent(text))
            break
        except SyntaxError:
            continue
    return textwrap.dedent(text).strip()


def require(cond, *context):
    """Fail the step unless cond holds. The message names the caller's file
    and line, the source of the require() call and the context values (a str
    as it is, anything else as its repr). Unlike an assert, the context is
    evaluated whether or not cond holds."""
    if cond:
        return
    caller = sys._getframe(1)
    where = "%s:%d" % (os.path.basename(caller.f_code.co_filename), caller.f_lineno)
    msg = "FAILED at %s: %s" % (where, _statement(caller.f_code.co_filename, caller.f_lineno))
    if context:
        msg += "\n  context: " + ", ".join(c if isinstance(c, str) else repr(c) for c in context)
    raise CheckFailed(msg)


def main(steps):
    """Run the step named by the first command-line argument, a function of
    the calling file (pass its globals()), with the further arguments as
    strings. A failed require() exits 1 with its message on stderr."""
    own = {k: f for k, f in steps.items()
           if callable(f) and getattr(f, "__module__", None) == "__main__" and not k.startswith("_")}
    if len(sys.argv) < 2 or sys.argv[1] not in own:
        sys.exit("usage: %s STEP [ARGUMENTS...], STEP one of: %s" % (sys.argv[0], " ".join(own)))
    try:
        own[sys.argv[1]](*sys.argv[2:])
    except CheckFailed as e:
        sys.stdout.flush()
        print("%s %s: %s" % (os.path.basename(sys.argv[0]), sys.argv[1], e), file=sys.stderr)
        sys.exit(1)


def group(path, name="/"):
    """The group (or dataset) name of the HDF5 file path, opened read-only;
    the file's root group without a name."""
    return h5py.File(path, "r")[name]


def attr_str(obj, name):
    """The string attribute name of obj (an h5py file, group or dataset, or
    its .attrs) as a str, whether it is stored as bytes (nltopo's fixed-length
    strings) or as str (h5py's own)."""
    s = (obj.attrs if hasattr(obj, "attrs") else obj)[name]
    return s.decode() if isinstance(s, bytes) else s


def complete(path):
    """The root attribute complete of an nltopo output: 1 for a finished run,
    0 for a checkpoint or an interrupted one."""
    return h5py.File(path, "r").attrs["complete"]


def study_of(path):
    """The study that wrote path (root attribute study)."""
    return attr_str(h5py.File(path, "r"), "study")


def same(x, y):
    """x and y (h5py datasets or arrays) hold the same values bit for bit:
    the same shape, equal entries, NaN where the other has NaN."""
    x, y = np.asarray(x[()]), np.asarray(y[()])
    return x.shape == y.shape and np.array_equal(x, y, equal_nan=True)


def rel(a, b):
    """|a / b - 1|, the relative difference of a from b (elementwise for arrays)."""
    return np.abs(a / b - 1)


def multipliers(branch):
    """The Floquet multipliers of a continuation branch, one row per orbit, as
    one complex array: multipliers_re + i multipliers_im."""
    return branch["multipliers_re"][:] + 1j * branch["multipliers_im"][:]
