#!/usr/bin/python3
"""Greenspan (1973), Figs 3.2-3.5: the 34-particle hexagonal flows.
Positions at the printed times in the frame moving with the drift
(x - V t; the paper's plots rescale their axes to the particles, which
amounts to the same), rows P1-P11 / P12-P23 / P24-P34 in three colours;
for V = 300 also the direction field of Fig. 3.4 (direction of v - v_cm,
the motion relative to the bulk; in the lab frame every arrow points along
+x).  An optional second file (same V, smaller dt) is overlaid as open
circles ("what happens at smaller steps").

usage: fig_g73_hex.py RUN.h5 -o OUT.png [--times 0.2 0.4 ...]
                      [--directions] [--compare SMALLDT.h5] [--label TEXT]"""
import argparse

import numpy as np

from bfplot import load, plt, save

ap = argparse.ArgumentParser()
ap.add_argument("h5")
ap.add_argument("-o", "--output", required=True)
ap.add_argument("--times", type=float, nargs="+",
                default=[0.2, 0.4, 0.6, 0.8, 1.0])
ap.add_argument("--directions", action="store_true")
ap.add_argument("--compare", default=None)
ap.add_argument("--label", default="")
a = ap.parse_args()

(x, y, vx, vy, t, e), attrs = load(a.h5, "/particles/x", "/particles/y",
                                   "/particles/vx", "/particles/vy", "/time",
                                   "/diag/energy")
V = attrs["greenspan73.speed"]
dt = attrs["scene.dt"]
cmp = None
if a.compare:
    (cx, cy, ct), cattrs = load(a.compare, "/particles/x", "/particles/y",
                                "/time")
    cmp = (cx, cy, ct, cattrs["scene.dt"])
rows = [range(0, 11), range(11, 23), range(23, 34)]
colors = ["C3", "C2", "C0"]
nt = len(a.times)
nrow = 2 if a.directions else 1
fig, axs = plt.subplots(nrow, nt, figsize=(3.2 * nt, 3.6 * nrow),
                        squeeze=False)
for k, tk in enumerate(a.times):
    r = int(np.argmin(np.abs(t - tk)))
    ax = axs[0][k]
    for c, rw in zip(colors, rows):
        idx = list(rw)
        ax.plot(x[r, idx] - V * t[r], y[r, idx], "o", ms=4, color=c)
    if cmp is not None:
        cx, cy, ct, cdt = cmp
        rc = int(np.argmin(np.abs(ct - tk)))
        ax.plot(cx[rc] - V * ct[rc], cy[rc], "o", ms=7, mfc="none",
                color="0.4", lw=0.5)
    for i in (0, 10, 11, 22, 23, 33):
        ax.annotate(str(i + 1), (x[r, i] - V * t[r], y[r, i]), fontsize=6,
                    xytext=(2, 2), textcoords="offset points")
    ax.set_title("t = %.1f s" % t[r])
    ax.set_aspect("equal", adjustable="datalim")
    ax.set_xlabel("x - V t [cm]")
    ax.set_ylabel("y [cm]")
    if a.directions:
        ax = axs[1][k]
        u, w = vx[r] - vx[r].mean(), vy[r] - vy[r].mean()
        s = np.hypot(u, w)
        s[s == 0] = 1
        ax.quiver(x[r] - V * t[r], y[r], u / s, w / s,
                  color=[colors[0]] * 11 + [colors[1]] * 12 + [colors[2]] * 11,
                  scale=25, width=0.008)
        ax.set_title("directions of v - v_cm, t = %.1f s" % t[r])
        ax.set_xlabel("x - V t [cm]")
        ax.set_ylabel("y [cm]")
        ax.set_aspect("equal", adjustable="datalim")
E = e[:, 3]
I = e[:, 4]
title = ("Greenspan 1973 hexagonal flow, V = %g, dt = %g%s\nmax |E - E0|/|E0| "
         "= %.1e, internal energy (E - K_cm) %.1e" % (V, dt, a.label,
                              np.max(np.abs(E - E[0])) / abs(E[0]),
                              np.max(np.abs(I - I[0])) / abs(I[0])))
if cmp is not None:
    title += "\nopen circles: dt = %g" % cmp[3]
fig.suptitle(title)
save(fig, a.output)
