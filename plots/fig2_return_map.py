#!/usr/bin/python3
"""Yasuda (2010) Fig. 2: first-return maps of the upper ball (its z and v
each time the lower ball is at its lowest point on the floor), lower ball
1.2 g (A) and 0.8 g (B), upper ball 1 g, MV2M.  Each file is one run of
runs/two_balls_A.ini / two_balls_B.ini with the Lyapunov estimate on; rows
of the figure are step sizes (the paper's 1e-4 s first).  The last column
shows the running Lyapunov estimate of every run.

usage: fig2_return_map.py A.h5 B.h5 [A2.h5 B2.h5 ...] -o fig2.png"""
import argparse

import numpy as np

from bfplot import attr_str, load, plt, save

ap = argparse.ArgumentParser()
ap.add_argument("files", nargs="+")
ap.add_argument("-o", "--output", default="fig2_return_map.png")
a = ap.parse_args()
if len(a.files) % 2:
    ap.error("give the runs in pairs (lower 1.2 g, lower 0.8 g)")
rows = len(a.files) // 2

fig, ax = plt.subplots(rows, 3, figsize=(15, 4.6 * rows), squeeze=False)
for k, path in enumerate(a.files):
    r, c = divmod(k, 2)
    (z, v, m), attrs = load(path, "/return_map/z", "/return_map/v",
                            "/balls/mass")
    lt, le = load(path, "/lyapunov/time", "/lyapunov/estimate")[0]
    lam = float(attrs["lyapunov_exponent"])
    dt = float(attrs["scene.dt"])
    integ = attr_str(attrs, "scene.integrator")
    emax = float(attrs.get("max_relative_energy_error", np.nan))
    p = ax[r][c]
    p.plot(z, v, ",", color="C%d" % c)
    p.set_title("(%s) lower %.1f g, upper %.1f g: %s dt = %g s\n"
                "%d points, Lyapunov %.3g 1/s, max |dE|/E %.1e"
                % ("AB"[c], m[0], m[1], integ, dt, len(z), lam, emax))
    p.set_xlabel("z of the upper ball [cm]")
    p.set_ylabel("v of the upper ball [cm/s]")
    ax[r][2].loglog(lt, np.maximum(le, 1e-3), color="C%d" % c,
                    ls="-" if r == 0 else "--",
                    label="lower %.1f g, dt = %g s" % (m[0], dt))
ax[0][2].set_title("running Lyapunov estimate (sum log(d/d0) / t)")
for r in range(rows):
    ax[r][2].set_xlabel("t [s]")
    ax[r][2].set_ylabel("estimate [1/s]")
    ax[r][2].legend()
    if r:
        ax[r][2].set_visible(False)
fig.suptitle("First-return maps of two falling balls (Yasuda 2010, Fig. 2), "
             "1000 s")
save(fig, a.output)
