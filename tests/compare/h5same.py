#!/usr/bin/python3
"""h5same.py A.h5 B.h5: exit 0 if both files hold the same datasets with the
same bits (dtype, shape and raw bytes, so NaN payloads and -0.0 count) and
the same root attributes; print every difference otherwise.

Root attributes that describe the build or the wall clock (version,
wall-time figures) are not compared, nor datasets of wall times (their path
ends in 'wall'): they differ between any two runs.  The scene's text
(scene_text) is the run's input, not its result: a difference there (an
edited comment in a scene file) is printed as a note and does not fail.
Nor is a scene key compared that only one file has and that file took at
its default (KEY with KEY.default = 1, and its KEY.unit): a key added at
a default that keeps the old behaviour ([scene] compress = 0) changes no
result.
"""
import sys

import h5py
import numpy as np

SKIP_ATTRS = {"version"}
NOTE_ATTRS = {"scene_text"}


def datasets(f):
    out = {}

    def visit(name, obj):
        if isinstance(obj, h5py.Dataset):
            out[name] = obj

    f.visititems(visit)
    return out


def raw(d):
    a = d[()]
    if isinstance(a, bytes):
        return a
    a = np.asarray(a)
    return a.dtype.str, a.shape, a.tobytes()


def attr_bytes(v):
    if isinstance(v, bytes):
        return v
    if isinstance(v, str):
        return v.encode()
    a = np.asarray(v)
    return a.dtype.str, a.shape, a.tobytes()


def new_default_keys(f, mine, other):
    """The attributes of scene keys that only f has, at their defaults."""
    out = set()
    for k in mine - other:
        if k + ".default" in mine and f.attrs[k + ".default"] == 1:
            out |= {k, k + ".default", k + ".unit"}
    return out


def main(a, b):
    bad, notes = [], []
    with h5py.File(a, "r") as fa, h5py.File(b, "r") as fb:
        da, db = datasets(fa), datasets(fb)
        for k in sorted(set(da) | set(db)):
            if k.endswith("wall"):
                continue
            if k not in da or k not in db:
                bad.append(f"dataset {k}: only in {a if k in da else b}")
            elif raw(da[k]) != raw(db[k]):
                bad.append(f"dataset {k}: differs")
        ka, kb = set(fa.attrs), set(fb.attrs)
        new_default = new_default_keys(fa, ka, kb) | new_default_keys(fb, kb,
                                                                      ka)
        for k in sorted(ka | kb):
            if k in SKIP_ATTRS or "wall" in k or k in new_default:
                continue
            if k not in ka or k not in kb:
                bad.append(f"attribute {k}: only in {a if k in ka else b}")
            elif attr_bytes(fa.attrs[k]) != attr_bytes(fb.attrs[k]):
                if k in NOTE_ATTRS:
                    notes.append(f"attribute {k} differs (input, not compared)")
                else:
                    bad.append(f"attribute {k}: {fa.attrs[k]!r} != "
                               f"{fb.attrs[k]!r}")
    for line in bad:
        print(f"  {line}")
    for line in notes:
        print(f"  note: {line}", file=sys.stderr)
    return 1 if bad else 0


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit("usage: h5same.py A.h5 B.h5")
    sys.exit(main(sys.argv[1], sys.argv[2]))
