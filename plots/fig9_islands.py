#!/usr/bin/python3
"""Island chains of the four-ball coupled scene: the first-return maps
(x4, v4) of chosen start-scan runs (runs/start_scan.sh), drawn as the kind
of map of Yasuda 2010, Fig. 9; fill fraction and Lyapunov exponent in
each title (fill as `ballfilm sweep`'s return_map_fill; the exponent if
the run estimated it).

usage: fig9_islands.py LABEL=PATH [LABEL=PATH ...] [--per-scan N]
                       [--lyap-max L] -o islands.png

PATH is a run file, or a scan directory: then up to N of its regular runs
(exponent at most --lyap-max, as plots/fig9_scan.py) are drawn, the ones
with the smallest fill fraction."""
import argparse
import glob
import math
import os

from bfplot import ballfilm, map_fill, plt, save



ap = argparse.ArgumentParser()
ap.add_argument("maps", nargs="+", help="LABEL=PATH")
ap.add_argument("--per-scan", type=int, default=2)
ap.add_argument("--lyap-max", type=float, default=0.5)
ap.add_argument("-o", "--output", default="fig9_islands.png")
a = ap.parse_args()


def final_lyap(f):
    return (f["/lyapunov/estimate"][-1] if "/lyapunov/estimate" in f
            else math.nan)


def picks(label, path):
    """(label, file) of a run file, or of the chosen runs of a scan"""
    if not os.path.isdir(path):
        return [(label, path)]
    cand = []
    for p in sorted(glob.glob(os.path.join(path, "x_*.h5"))):
        f = ballfilm.load(p)
        m = f["/coupled/return_map"]
        if len(m) > 1 and final_lyap(f) <= a.lyap_max:
            cand.append((map_fill(m[:, 1], m[:, 2]), p))
    cand.sort()
    return [("%s, X = %s cm" % (label, os.path.basename(p)[2:-3]), p)
            for _, p in cand[:a.per_scan]]


chosen = []
for spec in a.maps:
    label, path = spec.rsplit("=", 1)
    chosen += picks(label, path)
if not chosen:
    raise SystemExit("fig9_islands.py: no regular run to draw")
n = len(chosen)
cols = min(n, 4)
rows = (n + cols - 1) // cols
fig, axes = plt.subplots(rows, cols, figsize=(3.6 * cols, 3.4 * rows),
                         squeeze=False)
for k, (label, path) in enumerate(chosen):
    ax = axes[k // cols][k % cols]
    f = ballfilm.load(path)
    m = f["/coupled/return_map"]
    lam = final_lyap(f)
    fill = map_fill(m[:, 1], m[:, 2])
    ax.plot(m[:, 1], m[:, 2], ".", ms=1.5)
    lam_s = ", λ = %.2g 1/s" % lam if math.isfinite(lam) else ""
    ax.set_title("%s\nfill %.2f%s, %d points"
                 % (label, fill, lam_s, len(m)), fontsize=9)
    ax.locator_params(axis="x", nbins=4)
    ax.set_xlabel("x4 [cm]")
    ax.set_ylabel("v4 [cm/s]")
    print("%s: %d points, x4 %.3f .. %.3f cm, v4 %.2f .. %.2f cm/s, fill "
          "%.3f, lambda %.3g 1/s" % (label, len(m), m[:, 1].min(),
                                      m[:, 1].max(), m[:, 2].min(),
                                      m[:, 2].max(), fill, lam))
for k in range(n, rows * cols):
    axes[k // cols][k % cols].axis("off")
fig.suptitle("Return maps of ball 4 from symmetric starts (the kind of "
             "Yasuda 2010, Fig. 9)")
save(fig, a.output)
