#!/usr/bin/python3
"""Yasuda (2010) Fig. 8C: the offset of the order parameter at the probe,
psi(x_p, t) - psi(x_p, 0) (/coupled/psi_probe), over a time window, for
several runs (make fig8-offset): the paper's set-up from the analytic kink,
the same film without the balls' coupling (V0 = 0: the analytic kink
relaxing on the grid), and the balls in the film relaxed that way (the
discrete kink).  Prints min, max and mean per run; draws nothing.

usage: psi_offset.py LABEL=FILE ... [--window 40 50]"""
import argparse

import numpy as np

from bfplot import load

ap = argparse.ArgumentParser()
ap.add_argument("runs", nargs="+")
ap.add_argument("--window", type=float, nargs=2, default=[40.0, 50.0])
a = ap.parse_args()

t0, t1 = a.window
print("psi(probe) - psi(probe, 0) over %g-%g s" % (t0, t1))
print("%-44s %11s %11s %11s" % ("run", "min", "max", "mean"))
for spec in a.runs:
    label, path = spec.split("=", 1)
    (t, p), attrs = load(path, "/time", "/coupled/psi_probe")
    p = np.asarray(p).reshape(len(t), -1)[:, 0]
    d = p - p[0]
    m = (t >= t0) & (t <= t1)
    print("%-44s %11.3e %11.3e %11.3e" % (label, d[m].min(), d[m].max(),
                                          d[m].mean()))
