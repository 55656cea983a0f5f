#!/usr/bin/python3
"""Yasuda (2010) Figs 8 and 9: four balls coupled to the two-phase film.
(A) first-return map of the fourth ball (x, v when the third ball is
closest to the origin while touching the second); (B) positions of the
third and fourth balls over 40-50 s; (C) psi(0.3, t) - psi(0.3, 0) over
40-50 s; (D) left/right symmetry error of balls and film, and the relative
change of the film's phase totals, against time (and, for a run with
[coupled] symmetrize = yes, the largest relative change of the symmetry
projection per output interval).  Prints the statistics compared with the
paper in docs/models/coupled.md, among them the return map's fill fraction (the share
of its bounding box visited on a grid of about four points per bin, the
definition of bf_sweep_map_fill in src/sweep/sweep.c).

usage: fig8_coupled.py RUN.h5 -o fig8.png [--window 40 50]"""
import argparse

import numpy as np

from bfplot import PSI, attr_str, load, plt, save

ap = argparse.ArgumentParser()
ap.add_argument("run")
ap.add_argument("-o", "--output", default="fig8_coupled.png")
ap.add_argument("--window", nargs=2, type=float, default=[40, 50])
a = ap.parse_args()

(t, x, rm, probe, sb, sf, md, mc, e), attrs = load(
    a.run, "/time", "/balls/position", "/coupled/return_map",
    "/coupled/psi_probe", "/coupled/sym_balls", "/coupled/sym_film",
    "/film/mass_d", "/film/mass_c", "/energy/total")
L = attrs["film.length"]
sym = attr_str(attrs, "coupled.symmetrize").lower() in ("yes", "true", "on",
                                                         "1")
if sym:
    (corr, corr_max), _ = load(a.run, "/coupled/sym_correction",
                               "/coupled/sym_correction_max")


def map_fill(z, v):
    """bf_sweep_map_fill: visited share of a B x B grid over the box,
    B = floor(sqrt(n/4)) clipped to [5, 64]."""
    n = len(z)
    B = int(min(max(np.floor(np.sqrt(n / 4.0)), 5), 64))
    dz = (z.max() - z.min()) / B if z.max() > z.min() else 1.0
    dv = (v.max() - v.min()) / B if v.max() > v.min() else 1.0
    i = np.clip(((z - z.min()) / dz).astype(int), 0, B - 1)
    j = np.clip(((v - v.min()) / dv).astype(int), 0, B - 1)
    return len(set(zip(i, j))) / float(B * B), B
t0, t1 = a.window
w = (t >= t0) & (t <= t1)
fig, ax = plt.subplots(2, 2, figsize=(11, 9))
p = ax[0][0]
p.plot(rm[:, 1], rm[:, 2], ".", ms=2)
p.set_xlabel("x4 [cm]")
p.set_ylabel("v4 [cm/s]")
p.set_title("(A) first-return map of ball 4 (%d points)" % len(rm))
p = ax[0][1]
p.plot(t[w], x[w, 2], lw=0.6, label="ball 3")
p.plot(t[w], x[w, 3], lw=0.6, label="ball 4")
p.set_xlabel("t [s]")
p.set_ylabel("x [cm]")
p.set_title("(B) balls 3 and 4, %g-%g s" % (t0, t1))
p.legend()
p = ax[1][0]
dpsi = probe - probe[0]
p.plot(t[w], dpsi[w], lw=0.6)
p.set_xlabel("t [s]")
p.set_ylabel(r"%s(%g, t) $-$ %s(%g, 0) [1]"
             % (PSI, attrs["coupled.probe"], PSI, attrs["coupled.probe"]))
p.set_title("(C) order parameter at x = %g cm" % attrs["coupled.probe"])
p = ax[1][1]
p.semilogy(t, np.maximum(sb, 1e-18), lw=0.7,
           label=r"balls max$|x_i + x_{5-i}|$ [cm]")
p.semilogy(t, np.maximum(sf, 1e-18), lw=0.7, label=r"film max$|\psi_i + \psi_{N-i}|$ [1]")
drift = np.maximum(np.abs(md - md[0]) / md[0], np.abs(mc - mc[0]) / mc[0])
p.semilogy(t, np.maximum(drift, 1e-18), lw=0.7, label="phase totals, relative")
if sym:
    for k, lab in enumerate((r"film $\alpha h$", "film u", "ball x",
                             "ball v")):
        p.semilogy(t, np.maximum(corr[:, k], 1e-18), lw=0.5, alpha=0.7,
                   label="projection change, %s (rel.)" % lab)
p.set_xlabel("t [s]")
p.set_ylabel("error [cm] or relative [1]")
p.set_title("(D) symmetry error, conservation")
p.legend()
every = attrs["coupled.film_every"]  # a number, or the text "auto"
if isinstance(every, bytes):
    every = every.decode()
fig.suptitle("Four balls in the film, L = %g cm (Yasuda 2010, Fig. %s), "
             "dt = %g s, film_every = %s%s"
             % (L, "8" if abs(L - 50) < 1e-9 else "9", attrs["scene.dt"],
                every if isinstance(every, str) else "%d" % every,
                ", forced mirror symmetry" if sym else ""))
save(fig, a.output)
print("%s: L = %g cm, %g s%s" % (a.run, L, t[-1],
                                ", symmetrize = yes" if sym else ""))
print("  return map: %d points, x4 in [%.4f, %.4f] cm, v4 in [%.3f, %.3f] cm/s"
      % (len(rm), rm[:, 1].min(), rm[:, 1].max(), rm[:, 2].min(),
         rm[:, 2].max()))
fill, B = map_fill(rm[:, 1], rm[:, 2])
print("  return map fill fraction %.2f (%d x %d grid)" % (fill, B, B))
print("  balls 3, 4 over %g-%g s: x3 in [%.4f, %.4f], x4 in [%.4f, %.4f] cm"
      % (t0, t1, x[w, 2].min(), x[w, 2].max(), x[w, 3].min(), x[w, 3].max()))
print("  psi(%g) - psi(%g, 0) over %g-%g s: [%.3e, %.3e]"
      % (attrs["coupled.probe"], attrs["coupled.probe"], t0, t1,
         dpsi[w].min(), dpsi[w].max()))
print("  phase totals: largest relative change %.2e" % drift.max())
for lev in (1e-12, 1e-9, 1e-6, 1e-3):
    above = np.nonzero(sb > lev)[0]
    print("  ball symmetry error first above %g cm at t = %s s"
          % (lev, "%.3f" % t[above[0]] if len(above) else "never"))
if sym:
    print("  symmetrize: largest relative change of one projection: film "
          "alpha h %.2e, film u %.2e, ball x %.2e, ball v %.2e"
          % tuple(corr_max))
