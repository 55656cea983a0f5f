#!/usr/bin/python3
"""The 200704-particle mixing run (runs/greenspan72_large.ini): the heavy
(red) and light (blue) particles at the saved steps, and the mean height of
each fluid and the kinetic energy over time.

usage: fig_g72_large.py LARGE.h5 -o fig_g72_large.png"""
import argparse

import numpy as np

from bfplot import load, plt, save

ap = argparse.ArgumentParser()
ap.add_argument("h5")
ap.add_argument("-o", "--output", default="fig_g72_large.png")
a = ap.parse_args()

(x, y, pstep, tag, step, mean, kin), attrs = load(
    a.h5, "/particles/x", "/particles/y", "/particles/step", "/particles/tag",
    "/step", "/diag/mean_y", "/diag/kinetic")
L = attrs["greenspan72.width"]
heavy = tag == 1
rows = np.linspace(0, len(pstep) - 1, min(6, len(pstep))).astype(int)
fig = plt.figure(figsize=(14, 10))
gs = fig.add_gridspec(3, 6)
for k, r in enumerate(rows):
    ax = fig.add_subplot(gs[k // 3, 2 * (k % 3):2 * (k % 3) + 2])
    ax.scatter(x[r, ~heavy], y[r, ~heavy], s=0.02, c="C0", lw=0,
               rasterized=True)
    ax.scatter(x[r, heavy], y[r, heavy], s=0.02, c="C3", lw=0,
               rasterized=True)
    ax.set_xlim(0, L)
    ax.set_ylim(0, L)
    ax.set_aspect("equal")
    ax.set_title("step %d" % pstep[r])
    ax.set_xlabel("x [cm]")
    ax.set_ylabel("y [cm]")
ax = fig.add_subplot(gs[2, 0:3])
ax.plot(step, mean[:, 0], "C3", label="heavy")
ax.plot(step, mean[:, 1], "C0", label="light")
ax.set_xlabel("step")
ax.set_ylabel("mean height [cm]")
ax.legend()
ax = fig.add_subplot(gs[2, 3:6])
ax.semilogy(step, kin[:, 0], "k")
ax.set_xlabel("step")
ax.set_ylabel("kinetic energy [erg]")
fig.suptitle("%d particles (%d heavy), box %g cm, Example 2 physics"
             % (len(tag), heavy.sum(), L))
save(fig, a.output)
