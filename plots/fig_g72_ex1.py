#!/usr/bin/python3
"""Greenspan (1972) Example 1, Figs 3.1-3.9: the sixteen particles at steps
160 + 240k, k = 0..8 (heavy L1 labelled A, light L2 labelled B), and the
heights of the heavy particles over time with the paper's t_2080 marked.

usage: fig_g72_ex1.py EX1.h5 -o fig_g72_ex1.png [--heights OUT2.png]
(EX1.h5 from `make fig-g72-ex1`: runs/greenspan72_ex1.ini, a row per step)"""
import argparse

import numpy as np

from bfplot import legend_below, load, plt, save

ap = argparse.ArgumentParser()
ap.add_argument("h5")
ap.add_argument("-o", "--output", default="fig_g72_ex1.png")
ap.add_argument("--heights", default=None)
a = ap.parse_args()

(x, y, step, tag, settle), attrs = load(
    a.h5, "/particles/x", "/particles/y", "/particles/step", "/particles/tag",
    "/diag/settle")
L = attrs["greenspan72.width"]
H = attrs["greenspan72.height"]
heavy = tag == 1

fig, axs = plt.subplots(3, 3, figsize=(10, 10))
for k in range(9):
    s = 160 + 240 * k
    r = int(np.searchsorted(step, s))
    ax = axs[k // 3][k % 3]
    for i in range(len(tag)):
        ax.text(x[r, i], y[r, i], "A" if heavy[i] else "B",
                ha="center", va="center", fontsize=11,
                color="C3" if heavy[i] else "C0", weight="bold")
    ax.axhline(attrs["greenspan72.interface"], color="0.8", lw=0.8)
    ax.set_xlim(0, L)
    ax.set_ylim(0, H)
    ax.set_aspect("equal")
    ax.set_xticks([0, 50, 100])
    ax.set_yticks([0, 25, 50, 75, 100])
    ax.set_title("Fig. 3.%d: step %d" % (k + 1, s))
    ax.set_xlabel("x [cm]")
    ax.set_ylabel("y [cm]")
fig.suptitle("Greenspan 1972 Example 1: %d particles (A heavy, B light) "
             "at steps 160 + 240k" % len(tag))
save(fig, a.output)

if a.heights:
    fig, ax = plt.subplots(figsize=(9, 4.5))
    for i in np.where(heavy)[0]:
        ax.plot(step, y[:, i], lw=0.9, label="heavy %d" % (i + 1))
    ymean_l = y[:, ~heavy].mean(axis=1)
    ax.plot(step, ymean_l, "k--", lw=1, label="mean of the light")
    ax.axhline(attrs["diag/bottom"] if "diag/bottom" in attrs else 25,
               color="0.6", lw=0.8)
    ax.axvline(2080, color="C7", ls=":", lw=1)
    ax.plot([], [], color="C7", ls=":", lw=1,
            label="step 2080: the paper's complete interchange")
    ax.plot([], [], color="0.6", lw=0.8, label="bottom band y < 25 cm")
    ax.set_xlabel("step [1]")
    ax.set_ylabel("height y [cm]")
    legend_below(ax, ncol=3)
    ax.set_ylim(0, 105)
    ax.set_title("Greenspan 1972 Example 1: heights of the %d heavy particles"
                 % heavy.sum())
    save(fig, a.heights)
