#!/usr/bin/python3
"""Yasuda (2010) Fig. 4: difference of the upper ball's velocity between
the Verlet method and the second-order mid-point rule over 500-501 s
(lower ball 0.8 g).

(a) along the MV2M run, at every step: the velocity after one Verlet step
    minus the velocity after one second-order mid-point step, both from the
    same state (/compare/dv with [compare] a = verlet, b = alpha): the two
    formulas MV2M averages (eqs 2.19, 2.20).  Zero in free fall, non-zero
    only during collisions.
(b) two independent runs, Verlet and MV2M, dt = 1e-4 s: the difference of
    their upper-ball velocities in the same window.  By 500 s the runs are
    on unrelated parts of their orbits, so this is not what the paper shows.

usage: fig4_velocity_difference.py MV2M.h5 VERLET.h5 -o fig4.png
(both from `make fig4`: rows at every step between 500 and 501 s)"""
import argparse

import numpy as np

from bfplot import load, plt, save

ap = argparse.ArgumentParser()
ap.add_argument("mv2m")
ap.add_argument("verlet")
ap.add_argument("-o", "--output", default="fig4_velocity_difference.png")
a = ap.parse_args()

(t, dv, vm, zm), _ = load(a.mv2m, "/time", "/compare/dv", "/balls/velocity",
                          "/balls/position")
(tv, vv), _ = load(a.verlet, "/time", "/balls/velocity")
w = (t >= 500) & (t <= 501)
wv = (tv >= 500) & (tv <= 501)
fig, ax = plt.subplots(3, 1, figsize=(11, 9), sharex=True)
ax[0].plot(t[w], dv[w, 1], lw=0.8)
ax[0].set_ylabel("v_Verlet - v_T [cm/s]")
nz = np.mean(np.abs(dv[w, 1]) > 0)
ax[0].set_title("(a) one Verlet step minus one second-order mid-point step "
                "(eqs 2.19 - 2.20) from each state of the MV2M run; non-zero "
                "in %.0f%% of the steps" % (100 * nz))
n = min(np.sum(w), np.sum(wv))
ax[1].plot(t[w][:n], vv[wv][:n, 1] - vm[w][:n, 1], lw=0.8, color="C1")
ax[1].set_ylabel("v2 (Verlet run) - v2 (MV2M run) [cm/s]")
ax[1].set_title("(b) difference of two independent runs, dt = 1e-4 s")
ax[2].plot(t[w], zm[w, 0], label="lower ball", lw=0.8)
ax[2].plot(t[w], zm[w, 1], label="upper ball", lw=0.8)
ax[2].axhline(0.1, color="grey", ls=":", lw=0.8)
ax[2].set_ylabel("z (MV2M run) [cm]")
ax[2].set_xlabel("t [s]")
ax[2].legend()
fig.suptitle("Velocity difference between the Verlet method and the "
             "second-order mid-point rule, lower ball 0.8 g "
             "(Yasuda 2010, Fig. 4)")
save(fig, a.output)
