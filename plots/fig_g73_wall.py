#!/usr/bin/python3
"""Greenspan (1973), friction at a wall and penetration.

  --friction A.h5 [B.h5 ...]: Fig. 3.7, the path of P1 over the wall
      particles P2-P9 (t_0 to t_200), and Fig. 3.8, v_x of P1 over the
      steps, one line per file (the readings of the text and the listing);
  --penetration A.h5 [B.h5 ...]: Fig. 3.10, P1, P4, P5, P6, P7, P10 at
      steps 10, 15, 20, 25 (the first file), and a table of P1 at step 25
      for every file with the reading that produced it.

usage: fig_g73_wall.py --friction F1.h5 F2.h5 -o FRICTION.png
       fig_g73_wall.py --penetration P1.h5 ... -o PEN.png [--table T.txt]"""
import argparse

import numpy as np

from bfplot import attr_str, load, plt, save

ap = argparse.ArgumentParser()
ap.add_argument("--friction", nargs="+")
ap.add_argument("--penetration", nargs="+")
ap.add_argument("-o", "--output", required=True)
ap.add_argument("--table", default=None)
a = ap.parse_args()


def label(attrs):
    return attr_str(attrs, "reading")


if a.friction:
    fig, axs = plt.subplots(2, 1, figsize=(10, 9))
    for k, f in enumerate(a.friction):
        (x, y, vx, step), attrs = load(f, "/particles/x", "/particles/y",
                                       "/particles/vx", "/step")
        if k == 0:
            axs[0].plot(x[0, 1:9], y[0, 1:9], "ks", ms=6, label="P2-P9 at t_0")
        axs[0].plot(x[:, 0], y[:, 0], "-", color="C%d" % k, lw=1.2,
                    label="P1: " + label(attrs))
        axs[0].plot(x[-1, 1:9], y[-1, 1:9], "s", mfc="none", ms=7,
                    color="C%d" % k)
        axs[1].plot(step, vx[:, 0], color="C%d" % k, label=label(attrs))
    axs[0].set_xlabel("x [cm]")
    axs[0].set_ylim(-0.06, 0.16)
    axs[0].set_ylabel("y [cm]")
    axs[0].set_title("Fig. 3.7: P1 from t_0 to t_200 (open squares: wall at "
                     "t_200)")
    axs[0].legend(loc="upper right", ncol=1)
    axs[1].set_xlabel("step")
    axs[1].set_ylabel("v_x of P1 [cm/s]")
    axs[1].set_title("Fig. 3.8: v_x of P1 (the paper: 8.66 at t_0 is "
                     "maximal)")
    axs[1].legend()
    save(fig, a.output)

if a.penetration:
    (x, y, step), attrs = load(a.penetration[0], "/particles/x",
                               "/particles/y", "/step")
    fig, axs = plt.subplots(1, 4, figsize=(16, 5.2))
    show = [0, 3, 4, 5, 6, 9]
    for k, s in enumerate([10, 15, 20, 25]):
        ax = axs[k]
        r = int(np.searchsorted(step, s))
        ax.plot(x[0, 1:], y[0, 1:], "s", mfc="none", color="0.7", ms=7)
        ax.plot(x[r, show[1:]], y[r, show[1:]], "ks", ms=6)
        ax.plot(x[r, 0], y[r, 0], "o", color="C3", ms=7)
        for i in show:
            ax.annotate("P%d" % (i + 1), (x[r, i], y[r, i]), fontsize=7,
                        xytext=(3, 3), textcoords="offset points")
        ax.plot([0.40065], [-0.05244], "+", color="C0", ms=12)
        ax.set_title("step %d" % s)
        ax.set_xlabel("x [cm]")
        if k == 0:
            ax.set_ylabel("y [cm]")
        ax.set_xlim(0.15, 0.65)
        ax.set_ylim(-0.25, 0.15)
        ax.set_aspect("equal")
    fig.suptitle("Fig. 3.10 (%s); grey: the start; +: the paper's P1 at "
                 "t_25, (0.40065, -0.05244)" % label(attrs))
    save(fig, a.output)
    lines = ["P1 at step 25 (the paper: (0.40065, -0.05244), at rest)"]
    for f in a.penetration:
        (x, y, vy, step), attrs = load(f, "/particles/x", "/particles/y",
                                       "/particles/vy", "/step")
        if step[-1] < 25:
            lines.append("  did not reach step 25 (%s): %s"
                         % (attr_str(attrs, "message"), label(attrs)))
            continue
        r = int(np.searchsorted(step, 25))
        lines.append("  (%.5f, %+.6f)  v_y = %+8.3f  dy = %+.1e  %s"
                     % (x[r, 0], y[r, 0], vy[r, 0], y[r, 0] + 0.05244,
                        label(attrs)))
    text = "\n".join(lines)
    print(text)
    if a.table:
        with open(a.table, "w") as fh:
            fh.write(text + "\n")
