#!/usr/bin/python3
"""Checks of the sweep_shard scene (tests/scenes/sweep_shard.sh); usage: sweep_shard.py STEP [ARGUMENTS]."""
import os
import shutil
import sys
sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
import h5py
import numpy as np
from scene_check import main, require

WALL = {"seconds"}  # per-point wall times: the only /sweep dataset that may differ


def text(x):
    return x.decode() if isinstance(x, bytes) else str(x)


def merged(path):
    """path (a merge of shard0..2) equals whole.h5 bit for bit in every /sweep dataset and attribute but
    the wall times; the shards' provenance is kept; the Python reader reads it as the whole sweep."""
    with h5py.File(path, "r") as m, h5py.File("whole.h5", "r") as w:
        gm, gw = m["sweep"], w["sweep"]
        require(sorted(gm) == sorted(gw), sorted(set(gm) ^ set(gw)))
        for k in gw:
            a, b = gw[k][()], gm[k][()]
            require(a.dtype == b.dtype and a.shape == b.shape, k, a.dtype, b.dtype, a.shape, b.shape)
            require(k in WALL or a.tobytes() == b.tobytes(), "dataset differs", k)
        require(sorted(gm.attrs) == sorted(gw.attrs), sorted(set(gm.attrs) ^ set(gw.attrs)))
        for k in gw.attrs:
            require(np.array_equal(gw.attrs[k], gm.attrs[k]), "attribute differs", k)
        require(text(m.attrs["study"]) == "merge" and int(m.attrs["complete"]) == 1)
        require(int(m["merge"].attrs["shard_count"]) == 3 and int(m["merge"].attrs["points_computed"]) == 12)
        for i in range(3):
            p = m["merge/shards/%d" % i].attrs
            require(text(p["study"]) == "sweep" and int(p["shard_index"]) == i and int(p["points"]) == 4, i, dict(p))
            require(("-sweep_shard %d/3" % i) in text(p["options"]) and text(p["file"]).startswith("shard%d" % i), i, p["file"])
        print("%s = whole.h5 bit for bit in %d datasets (%d attributes) of /sweep but %s; provenance of 3 shards"
              % (path, len(gw), len(gw.attrs), ", ".join(WALL)))
    sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "..", "python"))  # python/nltopo
    import nltopo
    rm, rw, r0 = nltopo.Run(path), nltopo.Run("whole.h5"), nltopo.Run("shard0.h5")
    require(rm.sweep.shard is None and r0.sweep.shard == (0, 3))
    require(sorted(rm.sweep.maps) == sorted(rw.sweep.maps) and "mcr" in rm.sweep.maps)
    for k, v in rw.sweep.maps.items():
        require(k in WALL or np.array_equal(np.asarray(v), np.asarray(rm.sweep.maps[k]), equal_nan=v.dtype.kind == "f"), k)
    s = r0.sweep.maps["mcr"]
    require(s.count() == 4 and np.array_equal(s.compressed(), np.asarray(rw.sweep.maps["mcr"]).ravel()[r0.sweep["shard_points"]]))
    print("the Python reader reads %s as the whole sweep, and a shard's maps masked outside it" % path)


def undone(src, dst, partial="0"):
    """dst: a copy of the shard src with its first point marked not done (an incomplete shard); with
    partial 1 also complete = 0 (what an interrupted shard leaves at <output>.partial.h5)."""
    shutil.copyfile(src, dst)
    with h5py.File(dst, "r+") as f:
        d = f["sweep/done"][()]
        d[0] = 0
        f["sweep/done"][...] = d
        if partial == "1":
            f.attrs["complete"] = np.int32(0) if f.attrs["complete"].dtype == np.int32 else 0


def resumed(path, ref):
    """path, a shard resumed from an incomplete copy of ref, equals ref bit for bit (but the wall times),
    one point computed again."""
    with h5py.File(path, "r") as a, h5py.File(ref, "r") as b:
        for k in b["sweep"]:
            require(k in WALL or a["sweep"][k][()].tobytes() == b["sweep"][k][()].tobytes(), "dataset differs", k)
        require(int(a["sweep"].attrs["points_computed"]) == 1 and int(a.attrs["complete"]) == 1)
    print("%s: the shard resumed (1 point computed) = %s bit for bit" % (path, ref))


if __name__ == "__main__":
    main(globals())
