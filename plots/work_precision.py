#!/usr/bin/python3
"""Work-precision diagram of a `ballfilm converge` table: error at the final
time against wall time and against force evaluations, log-log, one line
per method (failed runs are left out, and listed in the legend).

usage: work_precision.py CONVERGE.h5 -o work_precision.png
(CONVERGE.h5 from `ballfilm converge SCENE.ini --methods ... -o ...`)"""
import argparse

import numpy as np

from bfplot import attr_str, ballfilm, plt, save

ap = argparse.ArgumentParser()
ap.add_argument("table")
ap.add_argument("-o", "--output", default="work_precision.png")
a = ap.parse_args()

table = ballfilm.load(a.table)
c = table.group("converge")
methods = attr_str(table.attrs, "methods").split(",")
scene = attr_str(table.attrs, "scene_file")
t_end = float(table.attrs["t_end"])
ref = table.attrs_of("reference")
ref_err = float(ref["estimated_error_x"])
ref_name = attr_str(ref, "method")

fig, ax = plt.subplots(1, 2, figsize=(12, 5))
for m, name in enumerate(methods):
    sel = (c["method"] == m) & (c["status"] == 0)
    failed = int(np.sum((c["method"] == m) & (c["status"] != 0)))
    label = name + (" (%d failed)" % failed if failed else "")
    if not np.any(sel):
        continue
    err = np.maximum(c["err_x"][sel], 1e-300)
    style = "s--" if np.any(c["adaptive"][sel]) else "o-"
    ax[0].loglog(c["wall"][sel], err, style, label=label)
    ax[1].loglog(c["evals"][sel], err, style, label=label)
for k, xl in enumerate(["wall time of the stepping loop [s] (min of repeats)",
                        "force evaluations"]):
    ax[k].axhline(ref_err, color="grey", ls=":", lw=1,
                  label="reference's estimated error")
    ax[k].set_xlabel(xl)
    ax[k].set_ylabel("max position error at T [cm]")
    ax[k].grid(True, which="both", alpha=0.3)
ax[1].legend(fontsize=8)
fig.suptitle("work-precision, %s to T = %g s (reference: %s)"
             % (scene, t_end, ref_name), fontsize=10)
save(fig, a.output)
