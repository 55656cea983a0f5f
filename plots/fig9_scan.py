#!/usr/bin/python3
"""Start scans of the four-ball coupled scene (runs/start_scan.sh): the
return map's fill fraction and the largest Lyapunov exponent against the
outer balls' start X, one curve per scan directory, and a table printed.

usage: fig9_scan.py LABEL=DIR [LABEL=DIR ...] -o scan.png [--lyap-max L]

A case counts as regular when its exponent is at most --lyap-max
(default 0.5 1/s: the exponents of these scans fall into two groups,
below 0.3 and above 2, see docs/models/coupled.md).  The fill fraction
shown is `ballfilm sweep`'s return_map_fill: the share of the map's
bounding box visited, on a B x B grid, B = floor(sqrt(points / 4))
clamped to 5..50; with the ~200 points of a 20 s run (B = 7) an island
chain covers up to half of its box, so the fill does not decide.  The X
of each scan's regular cases go to DIR/regular.txt, one a line (for the
runs that confirm them)."""
import argparse
import glob
import math
import os
import re

import numpy as np

from bfplot import ballfilm, map_fill, plt, save



def load_scan(d):
    """rows (X, fill, lambda, points) of the finished cases of a scan"""
    rows = []
    for path in sorted(glob.glob(os.path.join(d, "x_*.h5"))):
        m = re.search(r"x_([0-9.]+)\.h5$", path)
        if not m:
            continue
        f = ballfilm.load(path)
        rm = f["/coupled/return_map"]
        lam = (f["/lyapunov/estimate"][-1] if "/lyapunov/estimate" in f
               else math.nan)
        fill = map_fill(rm[:, 1], rm[:, 2]) if len(rm) else math.nan
        rows.append((float(m.group(1)), fill, lam, len(rm)))
    return np.array(rows).reshape(-1, 4)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("scans", nargs="+", help="LABEL=DIR")
    ap.add_argument("-o", "--output", default="fig9_scan.png")
    ap.add_argument("--lyap-max", type=float, default=0.5)
    a = ap.parse_args()
    fig, (ax1, ax2) = plt.subplots(2, 1, figsize=(9, 7), sharex=True)
    for k, spec in enumerate(a.scans):
        label, d = spec.rsplit("=", 1)
        r = load_scan(d)
        if not len(r):
            print("%s: no finished case in %s" % (label, d))
            continue
        x, fill, lam, pts = r.T
        reg = lam <= a.lyap_max
        with open(os.path.join(d, "regular.txt"), "w") as f:
            f.writelines("%.4f\n" % v for v in x[reg])
        c = "C%d" % k
        ax1.plot(x, fill, "o-", ms=3, color=c, label=label)
        ax2.plot(x, lam, "o-", ms=3, color=c, label=label)
        ax1.plot(x[reg], fill[reg], "s", ms=7, mfc="none", color=c)
        print("%s: %d cases, X = %.4f .. %.4f cm; regular %d (fraction "
              "%.3f)" % (label, len(x), x.min(), x.max(), reg.sum(),
                         reg.mean()))
        if reg.any() and (~reg).any():
            print("  lambda of the regular %.3f .. %.3f, of the others "
                  "%.2f .. %.2f 1/s" % (lam[reg].min(), lam[reg].max(),
                                        lam[~reg].min(), lam[~reg].max()))
            print("  fill of the regular %.2f .. %.2f, of the others %.2f "
                  ".. %.2f (median %.2f)"
                  % (fill[reg].min(), fill[reg].max(), fill[~reg].min(),
                     fill[~reg].max(), np.median(fill[~reg])))
        print("  fill %.2f .. %.2f (median %.2f), lambda %.2f .. %.2f 1/s "
              "(median %.2f), map points %d .. %d"
              % (np.nanmin(fill), np.nanmax(fill), np.nanmedian(fill),
                 np.nanmin(lam), np.nanmax(lam), np.nanmedian(lam),
                 pts.min(), pts.max()))
        at = np.isclose(x, 0.5)
        if at.any():
            i = np.argmax(at)
            print("  X = 0.5000: fill %.3f, lambda %.3f 1/s, %s"
                  % (fill[i], lam[i], "regular" if reg[i] else "chaotic"))
        for i in np.nonzero(reg)[0]:
            print("  regular X = %.4f: fill %.3f, lambda %.3f 1/s, %d "
                  "points" % (x[i], fill[i], lam[i], pts[i]))
    ax2.axhline(a.lyap_max, color="gray", ls=":", lw=1)
    ax1.set_ylabel("return map fill fraction")
    ax1.set_ylim(0, 1)
    ax1.legend(fontsize=8)
    ax2.set_ylabel("largest Lyapunov exponent [1/s]")
    ax2.set_yscale("symlog", linthresh=0.01)
    ax2.set_xlabel("outer balls at -X, +X: X [cm]")
    for ax in (ax1, ax2):
        ax.grid(True, alpha=0.3)
    ax1.set_title("Start scan: squares are the regular cases "
                  "(λ <= %.2g 1/s)" % a.lyap_max)
    save(fig, a.output)


main()
