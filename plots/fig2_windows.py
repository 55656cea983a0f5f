#!/usr/bin/python3
"""Yasuda (2010) Figs 2B and 3 in 100 s windows: the first-return map of one
run (runs/two_balls_B.ini, /return_map/time, z, v) split into windows of
`--width` seconds.  Prints, per window, the number of map points and the
range of z and v of the upper ball, and draws the windows named by
`--show` side by side with the whole run.  The 1000 s overlay of a run
whose energy drifts smears curves that are thin within each window; the
printed max z per window measures the drift.

usage: fig2_windows.py B.h5 [--width 100] [--show 0 450 900] -o OUT.png"""
import argparse

import numpy as np

from bfplot import attr_str, load, plt, save

ap = argparse.ArgumentParser()
ap.add_argument("file")
ap.add_argument("--width", type=float, default=100.0)
ap.add_argument("--show", type=float, nargs="+", default=[0.0, 450.0, 900.0],
                help="start times of the windows drawn")
ap.add_argument("-o", "--output", default="fig2_windows.png")
a = ap.parse_args()

(t, z, v, m), attrs = load(a.file, "/return_map/time", "/return_map/z",
                           "/return_map/v", "/balls/mass")
dt = float(attrs["scene.dt"])
integ = attr_str(attrs, "scene.integrator")
t_end = float(t[-1]) if len(t) else 0.0

print("return map of %s (%s, dt = %g s), %d points, windows of %g s"
      % (a.file, integ, dt, len(t), a.width))
print("%-14s %7s %10s %10s %10s %10s"
      % ("window [s]", "points", "min z", "max z", "min v", "max v"))


def window(t0):
    m = (t >= t0) & (t < t0 + a.width)
    return z[m], v[m]


starts = sorted(set(list(np.arange(0.0, t_end, a.width)) + list(a.show)))
for t0 in starts:
    zw, vw = window(t0)
    if len(zw) == 0:
        continue
    print("%6g-%-7g %7d %10.4f %10.4f %10.3f %10.3f"
          % (t0, t0 + a.width, len(zw), zw.min(), zw.max(), vw.min(),
             vw.max()))

n = len(a.show) + 1
fig, ax = plt.subplots(1, n, figsize=(4.6 * n, 4.4), squeeze=False)
ax = ax[0]
ax[0].plot(z, v, ",", color="C1")
ax[0].set_title("whole run, 0-%g s: %d points" % (t_end, len(z)), fontsize=9)
for k, t0 in enumerate(a.show, start=1):
    zw, vw = window(t0)
    ax[k].plot(zw, vw, ",", color="C%d" % (k + 1))
    ax[k].set_title("%g-%g s: %d points, max z %.3f cm"
                    % (t0, t0 + a.width, len(zw),
                       zw.max() if len(zw) else np.nan), fontsize=9)
for p in ax:
    p.set_xlabel("z of the upper ball [cm]")
    p.set_ylabel("v of the upper ball [cm/s]")
    p.set_xlim(ax[0].get_xlim())
    p.set_ylim(ax[0].get_ylim())
fig.suptitle("lower ball %.1f g, upper %.1f g, %s dt = %g s: the map in "
             "%g s windows" % (m[0], m[1], integ, dt, a.width), fontsize=11)
save(fig, a.output)
