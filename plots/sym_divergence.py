#!/usr/bin/python3
"""Separation of two symmetrized four-ball runs (runs/coupled_fig8_sym.ini,
runs/coupled_fig9_sym.ini) whose outer balls start 1e-10 cm apart (moved
symmetrically): max over the balls of |x_a - x_b| against time, for each
film length.  Exponential growth (a straight line on the log scale) up to
the size of the motion means the motion inside the symmetric subspace is
itself chaotic; quasi-periodic motion would separate only linearly.  Prints
the largest separation reached by a few times and the growth rate of a
straight-line fit of log(separation) over 1e-9..1e-5 cm.

usage: sym_divergence.py A.h5 B.h5 [A2.h5 B2.h5 ...] -o out.png"""
import argparse

import numpy as np

from bfplot import load, plt, save

ap = argparse.ArgumentParser()
ap.add_argument("runs", nargs="+")
ap.add_argument("-o", "--output", default="sym_divergence.png")
a = ap.parse_args()
if len(a.runs) % 2:
    ap.error("give the runs in pairs")

fig, ax = plt.subplots(figsize=(7, 4.5))
for k in range(0, len(a.runs), 2):
    (ta, xa), attrs = load(a.runs[k], "/time", "/balls/position")
    (tb, xb), _ = load(a.runs[k + 1], "/time", "/balls/position")
    n = min(len(ta), len(tb))
    t = ta[:n]
    d = np.abs(xa[:n] - xb[:n]).max(axis=1)
    env = np.maximum.accumulate(d)
    L = attrs["film.length"]
    ax.semilogy(t, np.maximum(d, 1e-18), lw=0.6, label="L = %g cm" % L)
    fit = (env > 1e-9) & (env < 1e-5)
    rate = np.polyfit(t[fit], np.log(env[fit]), 1)[0] if fit.sum() > 2 \
        else float("nan")
    print("L = %g cm: initial separation %.1e cm; largest by t = %s s: %s cm;"
          " growth rate %.2f 1/s (fit of the running maximum over 1e-9..1e-5"
          " cm)" % (L, d[0], "/".join("%g" % T for T in (2, 4, 6, 8, 10, 20)),
                    " / ".join("%.1e" % env[min(np.searchsorted(t, T), n - 1)]
                               for T in (2, 4, 6, 8, 10, 20)), rate))
ax.set_xlabel("t [s]")
ax.set_ylabel("max_i |x_i(a) - x_i(b)| [cm]")
ax.set_title("forced mirror symmetry: runs 1e-10 cm apart")
ax.legend()
save(fig, a.output)
