#!/usr/bin/python3
"""The return map's fill fraction and the Lyapunov estimate of one coupled
run, as they were at earlier times: the run's file cut at each time T
(the map's points with t <= T, the last /lyapunov/estimate at or before
T).  What fixed the 20 s of the start scans (docs/models/coupled.md,
"How long").

usage: fig9_duration.py FILE.h5 [T ...]      (default T: 20 50 200 s)"""
import argparse
import math

import numpy as np

from bfplot import ballfilm, map_fill


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("file")
    ap.add_argument("times", nargs="*", type=float, default=[20, 50, 200])
    a = ap.parse_args()
    f = ballfilm.load(a.file)
    rm = np.asarray(f["/coupled/return_map"])
    lt = np.asarray(f["/lyapunov/time"]) if "/lyapunov/time" in f else []
    le = np.asarray(f["/lyapunov/estimate"]) if "/lyapunov/estimate" in f else []
    print("%8s %8s %8s %12s" % ("T (s)", "points", "fill", "lambda (1/s)"))
    for T in a.times:
        pts = rm[rm[:, 0] <= T] if len(rm) else rm
        fill = map_fill(pts[:, 1], pts[:, 2]) if len(pts) else math.nan
        k = np.searchsorted(lt, T, side="right") - 1 if len(lt) else -1
        lam = le[k] if k >= 0 else math.nan
        print("%8g %8d %8.2f %12.3g" % (T, len(pts), fill, lam))


if __name__ == "__main__":
    main()
