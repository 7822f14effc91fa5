"""Shared helpers of the figure scripts."""


def bands(group):
    """The infinite lattice's bands [(acoustic bottom, top), (optical bottom, top)]
    in rad/s, from the *_inf attributes of a group (/linear/bloch, /continuation,
    /sweep; outputs.md schema: src/io/schema.cpp)."""
    a = group.attrs
    return [(float(a["acoustic_bottom_inf"]), float(a["acoustic_top_inf"])), (float(a["optical_bottom_inf"]), float(a["optical_top_inf"]))]
