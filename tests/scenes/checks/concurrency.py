#!/usr/bin/python3
"""Checks of the concurrency scene (tests/scenes/concurrency.sh); usage: concurrency.py STEP [ARGUMENTS]."""
import os
import re
import sys
sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
from scene_check import complete, group, main, require, same


def _options(f):
    """The root attribute options without -output (the one option two runs of a scene may differ in)."""
    o = f.attrs["options"]
    o = o.decode() if isinstance(o, bytes) else str(o)
    return re.sub(r"-output \S+ ", "", o + " ").strip()


def same_result(out, ref):
    """out holds, complete, the result of the scene ref was written by alone: the same options (-output
    aside) and every dataset equal bit for bit (wall times and the cost card aside)."""
    require(complete(out) == 1, out)
    a, b = group(out), group(ref)
    require(_options(a) == _options(b), out, _options(a), _options(b))
    names = []
    b.visititems(lambda n, o: names.append(n) if hasattr(o, "shape") and not n.startswith("cost") and "seconds" not in n else None)
    require(names, ref)
    for n in names:
        require(n in a and same(a[n], b[n]), out, n)
    print("%s: complete, %d datasets equal to %s" % (out, len(names), ref))


if __name__ == "__main__":
    main(globals())
