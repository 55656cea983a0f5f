#!/usr/bin/python3
"""h5same.py A.h5 B.h5 [--ulps DATASET=N ...] [--new-default KEY ...]: exit 0 if both files hold
the same datasets with the
same bits (dtype, shape and raw bytes, so NaN payloads and -0.0 count) and
the same root attributes; print every difference otherwise.

Root attributes that describe the build, the wall clock or the run itself
(version, wall-time figures, run_id: a random identifier of each run) are
not compared, nor datasets of wall times (their path ends in 'wall'): they
differ between any two runs, and nothing else is skipped.  The scene's
text and its hash (scene_text, scene_hash) are the run's input, not its
result: a difference there (an edited comment in a scene file) is printed
as a note and does not fail.  scene_hash may be only in B, from a
program that added it (a note); only in A it is a difference like any
other.

A scene key that only B records, at its default (B's "KEY.default" is 1),
is a key that B's program added: its record (KEY, KEY.unit, KEY.default)
is not a difference (it is printed as a note).  What the key does at its
default is checked by the datasets like everything else.

--ulps DATASET=N: a change declared on purpose (compare_runs.sh, cases.txt
"!ulps"): DATASET may differ by at most N units in the last place in each
element (same dtype and shape, floating point); the largest difference is
printed as a note.  Anything beyond N is a difference like any other.

--new-default KEY: a scene key whose default was changed on purpose
(cases.txt "!default"): where both files record KEY at its default
(KEY.default is 1 in both), different values of KEY are a note.  Where
either file set KEY explicitly, it is compared like any other attribute.
"""
import sys

import h5py
import numpy as np

SKIP_ATTRS = {"version", "run_id"}
NOTE_ATTRS = {"scene_text", "scene_hash"}
# provenance a later program writes: only in B is a note, not a difference
NEW_PROVENANCE = {"run_id", "scene_hash"}


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


def new_default_key(attrs, other, k):
    """k is part of the record of a scene key that only `attrs` has, at its
    default (the key itself, its .unit or its .default)"""
    base = k
    for suffix in (".unit", ".default"):
        if k.endswith(suffix) and k[:-len(suffix)] in attrs:
            base = k[:-len(suffix)]
    flag = attrs.get(base + ".default")
    return base not in other and flag is not None and int(flag) == 1


def ulps_apart(x, y):
    """the largest distance in units in the last place, element by element"""
    x = np.asarray(x, dtype=np.float64)
    y = np.asarray(y, dtype=np.float64)
    if x.size == 0:
        return 0.0
    if not (np.isfinite(x).all() and np.isfinite(y).all()):
        return np.inf if not np.array_equal(x, y, equal_nan=True) else 0.0
    scale = np.spacing(np.maximum(np.abs(x), np.abs(y)))
    return float(np.max(np.abs(x - y) / scale))


def at_default(attrs, k):
    flag = attrs.get(k + ".default")
    return flag is not None and int(flag) == 1


def main(a, b, ulps, new_defaults=()):
    bad, notes = [], []
    with h5py.File(a, "r") as fa, h5py.File(b, "r") as fb:
        da, db = datasets(fa), datasets(fb)
        for k in sorted(set(da) | set(db)):
            if k.endswith("wall"):
                continue
            if k not in da or k not in db:
                bad.append(f"dataset {k}: only in {a if k in da else b}")
            elif raw(da[k]) != raw(db[k]):
                ra, rb = raw(da[k]), raw(db[k])
                if (k in ulps and ra[:2] == rb[:2] and
                        da[k].dtype.kind == "f"):
                    u = ulps_apart(da[k][()], db[k][()])
                    if u <= ulps[k]:
                        notes.append(f"dataset {k}: {u:g} ulps apart "
                                     f"(declared: at most {ulps[k]})")
                        continue
                    bad.append(f"dataset {k}: differs by {u:g} ulps "
                               f"(declared: at most {ulps[k]})")
                else:
                    bad.append(f"dataset {k}: differs")
        ka, kb = set(fa.attrs), set(fb.attrs)
        for k in sorted(ka | kb):
            if k in NEW_PROVENANCE and k in kb and k not in ka:
                notes.append(f"attribute {k}: new provenance, only in {b}")
                continue
            if k in SKIP_ATTRS or k.endswith("wall"):
                continue
            if k not in ka and new_default_key(fb.attrs, ka, k):
                if not k.endswith((".unit", ".default")):
                    notes.append(f"attribute {k}: a new key, at its default")
                continue
            if k not in ka or k not in kb:
                bad.append(f"attribute {k}: only in {a if k in ka else b}")
            elif attr_bytes(fa.attrs[k]) != attr_bytes(fb.attrs[k]):
                if (k in new_defaults and at_default(fa.attrs, k) and
                        at_default(fb.attrs, k)):
                    notes.append(f"attribute {k}: {fa.attrs[k]!r} -> "
                                 f"{fb.attrs[k]!r}, a default changed on "
                                 "purpose (declared)")
                elif k in NOTE_ATTRS:
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
    args = sys.argv[1:]
    files, ulps, new_defaults = [], {}, set()
    while args:
        x = args.pop(0)
        if x == "--ulps" and args:
            name, _, n = args.pop(0).partition("=")
            ulps[name] = float(n)
        elif x == "--new-default" and args:
            new_defaults.add(args.pop(0))
        else:
            files.append(x)
    if len(files) != 2:
        sys.exit("usage: h5same.py A.h5 B.h5 [--ulps DATASET=N ...] "
                 "[--new-default KEY ...]")
    sys.exit(main(files[0], files[1], ulps, new_defaults))
