"""Shared helpers of the figure scripts: the options a file was written with,
and the infinite lattice's band edges from them (model.md)."""
import re
import numpy as np


def options(f):
    """The options database text stored in an nltopo HDF5 file's root."""
    o = f.attrs["options"]
    return o.decode() if isinstance(o, bytes) else str(o)


def opt(text, name, default):
    m = re.search(r"-%s\s+(\S+)" % name, text)
    return float(m.group(1)) if m else default


def bands(f):
    """[(acoustic bottom, top), (optical bottom, top)] in rad/s."""
    text = options(f)
    k, g, g0 = opt(text, "lattice_k", 1.0), opt(text, "lattice_gamma", 0.4), opt(text, "lattice_gamma0", 1.0)
    k1, k2 = k * (1 + g), k * (1 - g)
    kh = k1 + k2 + g0
    return [(np.sqrt(max(kh - k1 - k2, 0)), np.sqrt(kh - abs(k1 - k2))), (np.sqrt(kh + abs(k1 - k2)), np.sqrt(kh + k1 + k2))]
