#!/usr/bin/python3
"""Yasuda (2010) Fig. 6: balls in the potential of the (static) kink.
(A) phase portrait of both balls at dt = 1e-4 s, every 100 steps;
(B) the same at dt = 8e-4 s; (C) the right ball's peaks (largest position
between collisions) against time for dt = 1e-4, 5.5e-4, 8e-4 s, with the
ensemble of slightly shifted starts at the two large steps; (D) one ball
from -0.2 cm, 500 s at dt = 8e-4 s.  Prints the peak numbers quoted in
docs/models/coupled.md.

usage: fig6_kink_balls.py A.h5 B.h5 C55.h5 D.h5 [ENSEMBLE.h5 ...]
       -o fig6_kink_balls.png"""
import argparse

import numpy as np

from bfplot import load, plt, save

ap = argparse.ArgumentParser()
ap.add_argument("a")
ap.add_argument("b")
ap.add_argument("c55")
ap.add_argument("d")
ap.add_argument("ensemble", nargs="*")
ap.add_argument("-o", "--output", default="fig6_kink_balls.png")
a = ap.parse_args()


def peaks(path):
    (pk, x), attrs = load(path, "/coupled/peaks", "/balls/position")
    return pk, x[0, -1], attrs["scene.dt"]


fig, ax = plt.subplots(2, 2, figsize=(11, 9))
for col, path, tag in [(0, a.a, "A"), (1, a.b, "B")]:
    (x, v), attrs = load(path, "/balls/position", "/balls/velocity")
    p = ax[0][col]
    p.plot(x[:, 0], v[:, 0], ",", color="C0", label="ball 1")
    p.plot(x[:, 1], v[:, 1], ",", color="C1", label="ball 2")
    p.set_xlabel("x [cm]")
    p.set_ylabel("v [cm/s]")
    p.set_title("(%s) dt = %g s, every 100 steps, %g s"
                % (tag, attrs["scene.dt"], attrs["scene.t_end"]))
p = ax[1][0]
print("Fig. 6C: the right ball's peaks (relative deviation from the start)")
for path, c in [(a.a, "C0"), (a.c55, "C1"), (a.b, "C2")]:
    pk, x0, dt = peaks(path)
    rel = (pk[:, 1] - x0) / x0
    p.plot(pk[:, 0], pk[:, 1], ".", ms=2, color=c, label="dt = %g" % dt)
    for T in (10, 30, 100):
        w = pk[:, 0] <= T
        if w.any():
            print("  dt = %-7g window 0-%g s: %4d peaks, largest relative "
                  "deviation %.3e, last peak %.5f cm"
                  % (dt, T, w.sum(), rel[w].min(), pk[w][-1, 1]))
ens = {}
for path in a.ensemble:
    pk, x0, dt = peaks(path)
    p.plot(pk[:, 0], pk[:, 1], ",", color="0.6")
    ens.setdefault(dt, []).append((x0, pk))


def at(pk, T):
    """the last peak at or before T"""
    w = pk[:, 0] <= T
    return pk[w][-1, 1] if w.any() else np.nan


def below(pk, v):
    """first time a peak is below v"""
    w = np.nonzero(pk[:, 1] < v)[0]
    return pk[w[0], 0] if len(w) else np.nan


paper = {5.5e-4: 0.194, 8e-4: 0.173}
for path in (a.c55, a.b):
    pk0, x00, dt = peaks(path)
    runs = [(x00, pk0)] + ens.get(dt, [])
    print("  dt = %g: peak at 10 / 30 / 100 s, first below the paper's %.3f "
          "cm:" % (dt, paper.get(dt, np.nan)))
    for x0, pk in runs:
        print("    start %+.0e cm: %.4f / %.4f / %.4f cm, below at t = %.1f s"
              % (x0 - 0.2, at(pk, 10), at(pk, 30), at(pk, 100),
                 below(pk, paper.get(dt, 0))))
p.set_xlabel("t [s]")
p.set_ylabel("peak of the right ball [cm]")
p.set_title("(C) peaks (grey: shifted starts)")
p.legend()
(x, v, e), attrs = load(a.d, "/balls/position", "/balls/velocity",
                        "/energy/total")
p = ax[1][1]
p.plot(x[:, 0], v[:, 0], ",")
pk, x0, dt = peaks(a.d)
print("Fig. 6D: one ball, dt = %g s, %g s: peaks %.6f .. %.6f cm, max "
      "relative energy error %.2e"
      % (dt, attrs["scene.t_end"], pk[:, 1].min(), pk[:, 1].max(),
         np.abs(e - e[0]).max() / abs(e[0])))
p.set_xlabel("x [cm]")
p.set_ylabel("v [cm/s]")
p.set_title("(D) one ball from -0.2 cm, dt = %g s, %g s"
            % (dt, attrs["scene.t_end"]))
fig.suptitle("Balls in the kink potential (Yasuda 2010, Fig. 6), MV2M, "
             "R = 0.1, m = 1, k = 1e7, V0 = 0.01, r0 = 0.5, M = 1e5")
save(fig, a.output)
