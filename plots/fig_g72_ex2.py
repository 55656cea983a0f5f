#!/usr/bin/python3
"""Greenspan (1972) Example 2, Figs 3.10-3.14, in both readings of the
captions (step k, and step 100k since the text says "t_300, that is,
30000 time steps"), and the diagnostics over the 30000 steps.

  Figs 3.10-3.12: particles at t_2, t_69, t_300 (A heavy, B light)
  Fig 3.13: the particle that starts at (53.1, 46.9) every 10 steps to t_300
  Fig 3.14: the direction of every particle's velocity at t_92

usage: fig_g72_ex2.py SHORT.h5 LONG.h5 -o FIG.png --long FIG2.png
                      --diag DIAG.png
SHORT.h5: runs/greenspan72_ex2.ini with t_end = 3, output_every = 1;
LONG.h5: runs/greenspan72_ex2.ini (30000 steps, a row every 10 steps).
Velocities are the leapfrog half-step ones (t - dt/2)."""
import argparse

import numpy as np

from bfplot import load, plt, save

ap = argparse.ArgumentParser()
ap.add_argument("short")
ap.add_argument("long")
ap.add_argument("-o", "--output", default="fig_g72_ex2.png")
ap.add_argument("--long-output", dest="longout", default=None)
ap.add_argument("--diag", default=None)
a = ap.parse_args()

TRACK = 136  # particle 137 of the listing's order: (53.125, 46.875)


def figure(path, scale, out, title):
    (x, y, vx, vy, step, tag), attrs = load(
        path, "/particles/x", "/particles/y", "/particles/vx",
        "/particles/vy", "/particles/step", "/particles/tag")
    heavy = tag == 1
    row = {int(s): r for r, s in enumerate(step)}
    fig, axs = plt.subplots(2, 3, figsize=(13, 8.6))
    for k, s in enumerate([2, 69, 300]):
        ax = axs[0][k]
        r = row[s * scale]
        for i in np.argsort(heavy):  # heavy drawn last, on top
            ax.text(x[r, i], y[r, i], "A" if heavy[i] else "B",
                    ha="center", va="center", fontsize=6,
                    color="C3" if heavy[i] else "C0")
        ax.set_title("Fig. 3.%d: step %d" % (10 + k, s * scale))
    ax = axs[1][0]
    rs = [row[10 * k * scale] for k in range(31)]
    ax.plot(x[rs, TRACK], y[rs, TRACK], "-o", ms=3, lw=0.8, color="C2")
    ax.plot(x[rs[0], TRACK], y[rs[0], TRACK], "ks", ms=5)
    ax.set_title("Fig. 3.13: particle at (53.1, 46.9), every %d steps"
                 % (10 * scale))
    ax = axs[1][1]
    r = row[92 * scale]
    sp = np.hypot(vx[r], vy[r])
    sp[sp == 0] = 1
    ax.quiver(x[r], y[r], vx[r] / sp, vy[r] / sp,
              color=np.where(heavy, "C3", "C0"), scale=40, width=0.004)
    ax.set_title("Fig. 3.14: velocity directions, step %d" % (92 * scale))
    ax = axs[1][2]
    ax.axis("off")
    ax.text(0, 0.9, title, fontsize=10, va="top", wrap=True)
    for ax in list(axs[0]) + [axs[1][0], axs[1][1]]:
        ax.set_xlim(0, 100)
        ax.set_ylim(0, 100)
        ax.set_xlabel("x [cm]")
        ax.set_ylabel("y [cm]")
        ax.set_aspect("equal")
    save(fig, out)


figure(a.short, 1, a.output,
       "Reading 1: t_k = step k (dt = 0.01).\n"
       "A: heavy fluid L1 (64 particles),\nB: light fluid L2 (192).\n"
       "Velocities: GSL mt19937, seed 1972,\nuniform in [-500, 500];\n"
       "particle 137 set to (63.0, 133.9).")
if a.longout:
    figure(a.long, 100, a.longout,
           "Reading 2: t_k = step 100 k\n(\"t_300, that is, 30000 time "
           "steps\").\nSame run continued to step 30000;\nthe track is "
           "sampled every 1000 steps.")
# The report's sentences against the diagnostics, t_k = step k (the short
# run has a row per step): the heavy particles per quarter (bottom first),
# all particles per quarter, the kinetic energy and the mean heights.
(step, kin, mean, quart), attrs = load(
    a.short, "/step", "/diag/kinetic", "/diag/mean_y", "/diag/quarters")
print("Example 2, t_k = step k: quarters y in [0,25), [25,50), [50,75), "
      "[75,100)")
print("%6s %-18s %-18s %12s %14s" % ("step", "heavy per quarter",
                                     "all per quarter", "kinetic [erg]",
                                     "mean y h, l"))
for k in (0, 2, 69, 250, 300):
    i = int(np.searchsorted(step, k))
    if i >= len(step):
        continue
    h = quart[i, :4].astype(int)
    t = (quart[i, :4] + quart[i, 4:]).astype(int)
    print("%6d %-18s %-18s %12.3g %7.1f %6.1f"
          % (step[i], " ".join("%3d" % x for x in h),
             " ".join("%3d" % x for x in t), kin[i, 0], mean[i, 0],
             mean[i, 1]))
if a.diag:
    (step, kin, mean, quart), attrs = load(
        a.long, "/step", "/diag/kinetic", "/diag/mean_y", "/diag/quarters")
    fig, axs = plt.subplots(3, 1, figsize=(9, 10), sharex=True)
    ax = axs[0]
    ax.semilogy(step, kin[:, 0], label="all")
    ax.semilogy(step, kin[:, 1], label="heavy L1")
    ax.semilogy(step, kin[:, 2], label="light L2")
    ax.set_ylabel("kinetic energy [erg]")
    ax.legend()
    ax.set_title("Example 2 over %d steps (half-step velocities)"
                 % step[-1])
    ax = axs[1]
    ax.plot(step, mean[:, 0], label="heavy L1")
    ax.plot(step, mean[:, 1], label="light L2")
    ax.set_ylabel("mean height [cm]")
    ax.legend()
    ax = axs[2]
    tot = quart[:, :4] + quart[:, 4:]
    for q in range(4):
        ax.plot(step, tot[:, q], label="quarter %d (y in [%d, %d))"
                % (q + 1, 25 * q, 25 * (q + 1)))
    ax.set_ylabel("particles")
    ax.set_xlabel("step")
    ax.legend()
    save(fig, a.diag)
