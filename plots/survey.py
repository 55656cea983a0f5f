#!/usr/bin/python3
"""Survey of first-return maps from a `ballfilm sweep` directory (issue:
parameter sweeps).  Top: the largest Lyapunov exponent and the fraction of
the map's bounding box that the map visits, against the swept parameter.
Bottom: a grid of small return maps of selected cases.

usage: survey.py SWEEP_DIR -o survey.png [--label TEXT] [--maps N]"""
import argparse
import os

import numpy as np

from bfplot import attr_str, ballfilm, plt, save

ap = argparse.ArgumentParser()
ap.add_argument("dir")
ap.add_argument("-o", "--output", default="survey.png")
ap.add_argument("--label", default=None, help="x-axis label")
ap.add_argument("--maps", type=int, default=16, help="return maps to show")
a = ap.parse_args()

summary = ballfilm.load(os.path.join(a.dir, "summary.h5"))
params, lyap = summary["params"], summary["lyapunov"]
fill, status = summary["return_map_fill"], summary["status"]
keys = attr_str(summary.attrs_of("params"), "keys")
x = params[:, 0]
ok = status == 0
label = a.label or keys.split(",")[0]

nmaps = min(a.maps, len(x))
cols = 8 if nmaps > 8 else nmaps
rows = (nmaps + cols - 1) // cols
fig = plt.figure(figsize=(2.1 * cols, 3.2 + 2.1 * rows))
gs = fig.add_gridspec(1 + rows, cols, height_ratios=[1.6] + [1] * rows)
has_lyap = np.isfinite(lyap[ok]).any()
ax = fig.add_subplot(gs[0, : cols // 2])
if has_lyap:
    ax.plot(x[ok], lyap[ok], "o-", ms=3)
else:
    ax.text(0.5, 0.5, "no Lyapunov estimate for this model",
            ha="center", transform=ax.transAxes)
if (~ok).any():
    ax.plot(x[~ok], np.ones((~ok).sum()), "rx",
            label="failed case")
    ax.legend()
ax.set_xlabel(label)
ax.set_ylabel("largest Lyapunov exponent [1/s]")
if has_lyap and (lyap[ok] > 0).all():
    ax.set_yscale("log")
ax.grid(True, which="both", alpha=0.3)
ax2 = fig.add_subplot(gs[0, cols // 2:])
ax2.plot(x[ok], fill[ok], "o-", ms=3, color="C1")
ax2.set_xlabel(label)
ax2.set_ylabel("return map: fraction of its box visited")
ax2.set_ylim(0, 1)
ax2.grid(True, alpha=0.3)
pick = np.unique(np.linspace(0, len(x) - 1, nmaps).round().astype(int))
for n, k in enumerate(pick):
    sub = fig.add_subplot(gs[1 + n // cols, n % cols])
    path = os.path.join(a.dir, "case_%05d.h5" % k)
    try:
        case = ballfilm.load(path)
        if "/return_map/z" in case:
            z, v = case["/return_map/z"], case["/return_map/v"]
        else:  # the coupled model: rows (t, x, v)
            m = case["/coupled/return_map"]
            z, v = m[:, 1], m[:, 2]
        sub.plot(z, v, ",", color="C0" if fill[k] > 0.3 else "C1")
    except (OSError, KeyError):
        sub.text(0.5, 0.5, "no map", ha="center", transform=sub.transAxes)
    sub.set_title("%s = %.4g\nλ = %.3g/s, fill %.2f"
                  % (label.split()[0], x[k], lyap[k], fill[k]))
    sub.set_xticks([])
    sub.set_yticks([])
fig.suptitle("Survey of first-return maps: %s (%d cases, %s)"
             % (keys, len(x), os.path.basename(os.path.normpath(a.dir))))
save(fig, a.output)
