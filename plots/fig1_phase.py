#!/usr/bin/python3
"""Yasuda (2010) Fig. 1: phase portraits (z, v) of the bouncing ball,
Verlet (A, B) beside MV2M (C, D); B and D enlarge the top of the bounce,
where each bounce's apex shows that bounce's energy error.

usage: fig1_phase.py VERLET.h5 MV2M.h5 -o fig1_phase.png
(the files come from `make fig1`, i.e. runs/bouncing_ball.ini)"""
import argparse

import numpy as np
from matplotlib.ticker import FuncFormatter, MaxNLocator

from bfplot import attr_str, load, plt, save

ap = argparse.ArgumentParser()
ap.add_argument("verlet")
ap.add_argument("mv2m")
ap.add_argument("-o", "--output", default="fig1_phase.png")
a = ap.parse_args()

fig, ax = plt.subplots(2, 2, figsize=(10, 8))
for col, (path, label) in enumerate([(a.verlet, "Verlet"), (a.mv2m, "MV2M")]):
    (z, v, e), attrs = load(path, "/balls/position", "/balls/velocity",
                            "/energy/total")
    z, v = z[:, 0], v[:, 0]
    dt = attrs["scene.dt"]
    integ = attr_str(attrs, "scene.integrator")
    rel = np.max(np.abs(e - e[0]) / abs(e[0]))
    top, zoom = ax[0][col], ax[1][col]
    top.plot(z, v, ",", color="C%d" % col)
    top.set_title("(%s) %s, dt = %g s: max |dE|/E = %.2e"
                  % ("AC"[col], integ, dt, rel))
    top.set_xlabel("z [cm]")
    top.set_ylabel("v [cm/s]")
    near = (np.abs(v) < 1.5) & (z > 0.19)
    zoom.plot(z[near], v[near], ",", color="C%d" % col)
    zoom.set_title("(%s) enlargement near the apex (z = 0.2 cm)"
                   % "BD"[col])
    zoom.set_ylabel("v [cm/s]")
    zoom.set_xlim(0.1985, 0.2005)
    zoom.set_ylim(-1.5, 1.5)
    # four ticks with the distance from the apex: the full numbers
    # (0.1985, 0.1990, ...) overlapped at this width
    zoom.xaxis.set_major_locator(MaxNLocator(4))
    zoom.xaxis.set_major_formatter(FuncFormatter(
        lambda z, _: "%+g" % round((z - 0.2) * 1e4, 6)))
    zoom.set_xlabel("z - 0.2 cm [1e-4 cm]")
fig.suptitle("Bouncing ball (Yasuda 2010, Fig. 1): R = 0.1 cm, k = 1e7, "
             "m = 1 g, 100 s")
save(fig, a.output)
