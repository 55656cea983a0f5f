#!/usr/bin/python3
"""Space-time picture of the film: psi(x, t) minus the analytic kink (left)
and the velocity of the minor phase on each side (right: u_d for x < 0,
u_c for x > 0), from the profile rows of a film run.

usage: film_spacetime.py RUN.h5 -o film_spacetime.png"""
import argparse

import numpy as np
from matplotlib.colors import SymLogNorm

from bfplot import PSI, attr_str, load, plt, save

ap = argparse.ArgumentParser()
ap.add_argument("run")
ap.add_argument("-o", "--output", default="film_spacetime.png")
a = ap.parse_args()

(x, T, psi, ud, uc), attrs = load(a.run, "/film/x", "/film/time",
                                  "/film/psi", "/film/u_d", "/film/u_c")
A, B, G = attrs["film.a"], attrs["film.b"], attrs["film.gamma"]
kink = np.sqrt(A / B) * np.tanh((x - attrs["film.center"])
                                / (np.sqrt(2) * np.sqrt(G / A)))
dpsi = psi - kink[None, :]
umin = np.where(x[None, :] < 0, ud, uc)
fig, ax = plt.subplots(1, 2, figsize=(12, 5), sharey=True)
ext = [x[0], x[-1], T[0], T[-1]]
lim = max(np.abs(dpsi).max(), 1e-12)
im = ax[0].imshow(dpsi, aspect="auto", origin="lower", extent=ext,
                  cmap="RdBu_r", norm=SymLogNorm(1e-6, vmin=-lim, vmax=lim))
fig.colorbar(im, ax=ax[0], label=r"%s $-$ kink [1]" % PSI)
ax[0].set_xlabel("x [cm]")
ax[0].set_ylabel("t [s]")
ax[0].set_title(r"%s(x, t) $-$ $\tanh(x/\sqrt{2})$" % PSI)
lim = max(np.abs(umin).max(), 1e-12)
im = ax[1].imshow(umin, aspect="auto", origin="lower", extent=ext,
                  cmap="PuOr", vmin=-lim, vmax=lim)
fig.colorbar(im, ax=ax[1], label="velocity of the minor phase [cm/s]")
ax[1].set_xlabel("x [cm]")
ax[1].set_title("minor phase velocity ($u_d$ for x < 0, $u_c$ for x > 0)")
fig.suptitle("Film space-time, %g s to %g s: %s"
             % (T[0], T[-1], attr_str(attrs, "scene.title") or "film run"))
save(fig, a.output)
