"""Reading HDF5 values as Python and numpy values: strings decoded (fixed-length
strings come back from h5py as bytes, variable-length ones as str or bytes),
numpy scalars turned into int, float and str."""
import numpy as np


def text(value):
    """A string attribute or element as str."""
    if isinstance(value, np.ndarray) and value.shape == ():
        value = value[()]
    if isinstance(value, (bytes, np.bytes_)):
        return bytes(value).decode("utf-8")
    return str(value)


def value(v):
    """An attribute as a Python value: str, int, float, or a numpy array."""
    if isinstance(v, (bytes, np.bytes_, str)):
        return text(v)
    if isinstance(v, np.ndarray):
        if v.shape == () or v.size == 1 and v.ndim <= 1:
            return value(v.reshape(-1)[0] if v.shape else v[()])
        if v.dtype.kind in "SO":
            return np.array([text(x) for x in v.reshape(-1)], dtype=str).reshape(v.shape)
        return v
    if isinstance(v, np.integer):
        return int(v)
    if isinstance(v, np.floating):
        return float(v)
    return v


def _decode_strings(a):
    if a.dtype.kind in "SO":
        flat = [text(x) for x in a.reshape(-1)]
        return np.array(flat, dtype=str).reshape(a.shape) if flat else np.zeros(a.shape, dtype=str)
    return a


def array(ds):
    """A dataset (or an attribute's array) as a numpy array; strings decoded to
    str, and a compound of strings (the `fields` and `options_table` table
    attributes) as a structured array of str."""
    raw = ds[()] if not isinstance(ds, np.ndarray) else ds
    dt = raw.dtype if isinstance(raw, np.ndarray) else ds.dtype
    if dt.names:
        cols = {n: _decode_strings(np.asarray(raw[n])) for n in dt.names}
        out = np.empty(raw.shape, dtype=[(n, cols[n].dtype) for n in dt.names])
        for n in dt.names:
            out[n] = cols[n]
        return out
    if not isinstance(raw, np.ndarray):
        raw = np.asarray(raw)
    return _decode_strings(raw)


def table(ds):
    """A compound dataset or attribute array as a list of dicts (column name -> str or number)."""
    a = array(ds)
    return [{n: value(row[n]) for n in a.dtype.names} for row in a.reshape(-1)]
