#!/usr/bin/python3
"""The stratified reservoir with a point sink (thesis, Figure 5): marker
particles coloured by density at several times, and the particle counts
and mass that entered and left.

usage: fig_stratres.py OUT.h5 [-o stratres.png] [--times 0 1 2 4 7 10]
(the file comes from `make stratres`, i.e. runs/stratres.ini)"""
import argparse

import numpy as np

from bfplot import attr_str, load, plt, save

ap = argparse.ArgumentParser()
ap.add_argument("h5")
ap.add_argument("-o", "--output", default="stratres.png")
ap.add_argument("--times", type=float, nargs="+",
                default=[0, 1, 2, 4, 7, 10])
a = ap.parse_args()

(t, x, y, dens, flag, counts, mass, grid, flags), attrs = load(
    a.h5, "/time", "/mac/particles/x", "/mac/particles/y",
    "/mac/particles/density", "/mac/particles/flag", "/mac/counts",
    "/mac/mass", "/mac/grid", "/mac/flags")
ni, nj, dx, dy = int(grid[0]), int(grid[1]), grid[2], grid[3]
width, depth = (ni - 2) * dx, (nj - 2) * dy
live = flag > 1
dmin = dens[live].min()
dmax = dens[live].max()

times = [tt for tt in a.times if tt <= t[-1] + 1e-9]
ncol = 3
nrow = (len(times) + ncol - 1) // ncol
fig = plt.figure(figsize=(4.2 * ncol + 0.6, 4.0 * nrow + 3.6))
gs = fig.add_gridspec(nrow + 1, ncol + 1, height_ratios=[4.0] * nrow + [3.0],
                      width_ratios=[1.0] * ncol + [0.06])
sc = None
for k, tt in enumerate(times):
    row = int(np.argmin(np.abs(t - tt)))
    ax = fig.add_subplot(gs[k // ncol, k % ncol])
    sel = flag[row] > 1
    sc = ax.scatter(x[row][sel], y[row][sel], c=dens[row][sel],
                    s=7.0 * (0.1 / dx) ** -2,
                    cmap="viridis_r", vmin=dmin, vmax=dmax)
    # walls, inflow and the sink, from the cell flags of this row
    f = flags[row].reshape(ni, nj)
    ax.plot([0, width, width], [depth, depth, 0], "k-", lw=1)
    ax.plot([0, 0], [0, depth], "b--", lw=1)
    for i in range(ni):
        x0 = (i - 1) * dx
        if f[i, 0] == 3:
            ax.plot([x0, x0 + dx], [0, 0], "r-", lw=3)
        elif 1 <= i <= ni - 2:
            ax.plot([x0, x0 + dx], [0, 0], "k-", lw=1)
    ax.set_xlim(-0.15, width + 0.05)
    ax.set_ylim(-0.15, depth + 0.05)
    ax.set_aspect("equal")
    ax.set_title("t = %.3f" % t[row])
    ax.set_xlabel("x [L]")
    ax.set_ylabel("y [L]")
cb = fig.colorbar(sc, cax=fig.add_subplot(gs[0:nrow, ncol]))
cb.set_label("particle density [R]")

axc = fig.add_subplot(gs[nrow, 0:2])
axc.plot(t, counts[:, 4], "C0-o", ms=3, label="entered (IN -> fluid)")
axc.plot(t, counts[:, 5], "C3-o", ms=3, label="into the sink (OUT cells)")
axc.plot(t, counts[:, 6], "C2-", label="back into the IN column")
axc.plot(t, counts[:, 7], "k-", label="lost through a wall")
axc.plot(t, counts[:, 1] - counts[0, 1], "C1--",
         label="fluid particles - initial (%d)" % counts[0, 1])
axc.set_xlabel("t [L/W]")
axc.set_ylabel("particles")
axc.legend()
axc.set_title("particle counts (cumulative)")
axm = fig.add_subplot(gs[nrow, 2:])
axm.plot(t, mass[:, 0], "C0-", label="mass in")
axm.plot(t, mass[:, 1], "C3-", label="mass out (sink)")
axm.plot(t, mass[:, 2] - mass[0, 2], "C1--", label="fluid mass - initial")
axm.plot(t, mass[:, 0] - mass[:, 1] - mass[:, 3] - (mass[:, 2] - mass[0, 2]),
         "k:", label="in - out - lost - change")
axm.set_xlabel("t [L/W]")
axm.set_ylabel("mass [R L^2]")
axm.legend()
axm.set_title("mass balance of the markers")
extra = ""
if attr_str(attrs, "mac.void_fix").lower() in ("true", "yes", "on", "1"):
    extra = ", void_fix"
fig.suptitle("Stratified reservoir with a point sink (thesis Fig. 5)\n"
             "%dx%d cells, dt = %g, update = %s, solver = %s, OUT cells "
             "from I = %d (16x16 numbering)%s"
             % (ni, nj, attrs["scene.dt"], attr_str(attrs, "mac.update"),
                attr_str(attrs, "mac.pressure_solver"),
                int(attrs["mac.out_first"]), extra))
save(fig, a.output)
