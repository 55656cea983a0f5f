#!/usr/bin/python3
"""Multirate coupling error against wall time (runs/coupled_fig8.ini over a
short window).  The reference is the single-rate run (film_every = 1,
dt = 1e-5 s); the scene's tolerance is the single-rate run's own time error,
the distance between dt = 1e-5 s and dt = 5e-6 s.  Each multirate run
(film step film_every x dt, balls sub-cycled at dt) is compared with the
reference: max over the window of max_i |x_i - x_i,ref| (cm, at the common
output rows).  Prints the table quoted in docs/models/coupled.md (Multirate coupling).

usage: multirate.py TIMES.txt -o multirate.png
TIMES.txt: lines "label file.h5 wall_seconds" (the first: the reference,
the second: the half-step run)."""
import argparse

import numpy as np

from bfplot import load, plt, save

ap = argparse.ArgumentParser()
ap.add_argument("times")
ap.add_argument("-o", "--output", default="multirate.png")
a = ap.parse_args()

rows = [line.split() for line in open(a.times) if line.strip()]
(tr, xr), attrs = load(rows[0][1], "/time", "/balls/position")
wref = float(rows[0][2])


def dist(path):
    (t, x), _ = load(path, "/time", "/balls/position")
    # common output times (the half-step run writes every 200 steps of 5e-6)
    common, ia, ib = np.intersect1d(np.round(tr, 9), np.round(t, 9),
                                    return_indices=True)
    return np.abs(xr[ia] - x[ib]).max()


tol = dist(rows[1][1])
print("multirate coupling error, window 0-%g s (reference: single rate, "
      "dt = 1e-5 s, %.2f s wall)" % (tr[-1], wref))
print("  tolerance (single rate, dt = 1e-5 vs 5e-6 s): %.3e cm" % tol)
lab, err, wall = [], [], []
for label, path, w in rows[2:]:
    e = dist(path)
    lab.append(label)
    err.append(e)
    wall.append(float(w))
    print("  %-16s error %.3e cm  wall %.2f s  speed-up %.1f  %s"
          % (label, e, float(w), wref / float(w),
             "within tolerance" if e <= tol else "outside tolerance"))
fig, ax = plt.subplots(figsize=(7, 5))
ax.loglog(wall, err, "o-")
for l, w, e in zip(lab, wall, err):
    ax.annotate(l, (w, e), fontsize=8)
ax.axhline(tol, color="k", ls="--", label="single-rate dt vs dt/2")
ax.plot([wref], [tol], "s", label="single rate (wall)")
ax.set_xlabel("wall time [s]")
ax.set_ylabel("max |x - x_ref| over the window [cm]")
ax.set_title("Multirate film/ball coupling, Fig. 8 scene")
ax.legend()
save(fig, a.output)
