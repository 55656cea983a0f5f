#!/usr/bin/python3
"""The first-return map of the ball on the vibrating floor
(examples/vibrating_floor.c): at each release from the floor, the floor's
phase 2 pi f t mod 2 pi against the ball's velocity, coloured by time;
beside it the ball's height over the run.

usage: vibrating_floor_map.py vibrating_floor.h5 -o vibrating_floor_map.png
(the file is written by examples/vibrating_floor [T], T the simulated
seconds; a few hundred seconds fill the map)"""
import argparse

import numpy as np

from bfplot import attr_str, ballfilm, plt, save

ap = argparse.ArgumentParser()
ap.add_argument("run")
ap.add_argument("-o", "--output", default="vibrating_floor_map.png")
a = ap.parse_args()

r = ballfilm.load(a.run)
phase, vel = r["floor_map/phase"], r["floor_map/velocity"]
t, x = r.time, r["balls/position"][:, 0]
A, f = r.params["vibrating_floor.amplitude"], r.params["vibrating_floor.frequency"]
gamma = A * (2 * np.pi * f) ** 2 / r.params["gravity.g"]
fig, ax = plt.subplots(1, 2, figsize=(12, 5))
sc = ax[0].scatter(phase, vel, c=np.arange(len(phase)), s=4, cmap="viridis")
ax[0].set_xlim(0, 2 * np.pi)
ax[0].set_xlabel("floor phase at release, 2 pi f t mod 2 pi [rad]")
ax[0].set_ylabel("ball velocity at release [cm/s]")
ax[0].set_title("first-return map at the floor contacts (%d points)"
                % len(phase))
fig.colorbar(sc, ax=ax[0], label="release number")
ax[1].plot(t, x, lw=0.5)
ax[1].set_xlabel("t [s]")
ax[1].set_ylabel("ball centre x [cm]")
ax[1].set_title("height over the run")
fig.suptitle("%s: A = %g cm, f = %g Hz, A (2 pi f)^2 / g = %.2f"
             % (attr_str(r.attrs, "scene.title"), A, f, gamma))
save(fig, a.output)
