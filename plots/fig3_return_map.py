#!/usr/bin/python3
"""Yasuda (2010) Fig. 3: first-return maps for the lower ball 0.8 g and the
upper 1 g with other integrators: (A) Verlet dt = 1e-4 s, (B) Verlet
1e-5 s, (C) RK4, (D) RK3 and (E) implicit mid-point at 1e-4 s; (F) the
running Lyapunov estimates.  Each file is a run of runs/two_balls_B.ini.

usage: fig3_return_map.py A.h5 B.h5 C.h5 D.h5 E.h5 -o fig3.png"""
import argparse

import numpy as np

from bfplot import attr_str, load, plt, save

ap = argparse.ArgumentParser()
ap.add_argument("files", nargs=5)
ap.add_argument("-o", "--output", default="fig3_return_map.png")
a = ap.parse_args()

fig, ax = plt.subplots(2, 3, figsize=(15, 9.5))
ax = ax.ravel()
for k, path in enumerate(a.files):
    (z, v), attrs = load(path, "/return_map/z", "/return_map/v")
    lt, le = load(path, "/lyapunov/time", "/lyapunov/estimate")[0]
    dt = float(attrs["scene.dt"])
    integ = attr_str(attrs, "scene.integrator")
    status = attr_str(attrs, "status")
    tf = float(attrs["t_final"])
    emax = float(attrs.get("max_relative_energy_error", np.nan))
    it = int(attrs.get("iterations", 0))
    steps = int(attrs.get("steps_done", 1))
    extra = ", %.2f iterations/step" % (it / steps) if it else ""
    p = ax[k]
    p.plot(z, v, ",", color="C%d" % k)
    p.set_title("(%s) %s dt = %g s%s\n%d points to t = %g s, Lyapunov %.3g "
                "1/s, max |dE|/E %.1e%s"
                % ("ABCDE"[k], integ, dt, extra, len(z), tf,
                   float(attrs["lyapunov_exponent"]), emax,
                   "" if status == "ok" else " [" + status + "]"))
    p.set_xlabel("z of the upper ball [cm]")
    p.set_ylabel("v of the upper ball [cm/s]")
    ax[5].loglog(lt, np.maximum(le, 1e-3), color="C%d" % k,
                 label="(%s) %s %g s" % ("ABCDE"[k], integ, dt))
ax[5].set_title("(F) running Lyapunov estimates")
ax[5].set_xlabel("t [s]")
ax[5].set_ylabel("estimate [1/s]")
ax[5].legend()
fig.suptitle("First-return maps, lower ball 0.8 g, upper 1 g, other "
             "integrators (Yasuda 2010, Fig. 3), 1000 s")
save(fig, a.output)
