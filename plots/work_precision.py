#!/usr/bin/python3
"""Work-precision diagram of a `ballfilm converge` table, any model: the
error of the first state group at the final time (ball positions, the
film's psi, particle positions, ...) against wall time and against
right-hand-side evaluations, log-log, one line per method (failed runs are
left out, and counted in the legend).  --group NAME picks another group,
--norm max|rms the error over the output rows instead of at T.
--cheapest E1,E2,... also prints, per accuracy E, the cheapest run (wall
time) of each method whose error is at most E, and which method wins.

usage: work_precision.py CONVERGE.h5 -o work_precision.png
       [--group NAME] [--norm final|max|rms] [--cheapest 1e-5,1e-7,1e-9]
(CONVERGE.h5 from `ballfilm converge SCENE.ini --methods ... -o ...`)"""
import argparse

import numpy as np

from bfplot import attr_str, ballfilm, plt, save


ap = argparse.ArgumentParser()
ap.add_argument("table")
ap.add_argument("-o", "--output", default="work_precision.png")
ap.add_argument("--group", default=None,
                help="state group (default: the first)")
ap.add_argument("--norm", default="final", choices=["final", "max", "rms"])
ap.add_argument("--cheapest", default=None,
                help="accuracies E1,E2,...: print the cheapest run per method")
a = ap.parse_args()

table = ballfilm.load(a.table)
c = table.group("converge")
methods = attr_str(table.attrs, "methods").split(",")
scene = attr_str(table.attrs, "scene_file")
model = attr_str(table.attrs, "model") or "balls"
t_end = float(table.attrs["t_end"])
ref = table.attrs_of("reference")
ref_name = attr_str(ref, "method")
if "error" in c:  # the table of every model
    cattrs = table.attrs_of("converge")
    groups = attr_str(cattrs, "groups").split(",")
    units = attr_str(cattrs, "units").split(",")
    g = groups.index(a.group) if a.group else 0
    key = {"final": "error", "max": "error_max", "rms": "error_rms"}
    errs = np.atleast_2d(c[key[a.norm]])[:, g]
    est = table["reference/estimated_error" if a.norm == "final"
                else "reference/estimated_error_max"]
    ref_err = float(np.atleast_1d(est)[g])
    gname, gunit = groups[g], units[g]
else:  # tables of ball scenes before every model had one
    errs = c["err_x"]
    ref_err = float(ref["estimated_error_x"])
    gname, gunit = "x", "cm"

where = {"final": "at T", "max": "max over the output rows",
         "rms": "RMS over the output rows"}[a.norm]
fig, ax = plt.subplots(1, 2, figsize=(12, 5))
for m, name in enumerate(methods):
    sel = (c["method"] == m) & (c["status"] == 0)
    failed = int(np.sum((c["method"] == m) & (c["status"] != 0)))
    label = name + (" (%d failed)" % failed if failed else "")
    if not np.any(sel):
        continue
    err = np.maximum(errs[sel], 1e-300)
    style = "s--" if np.any(c["adaptive"][sel]) else "o-"
    ax[0].loglog(c["wall"][sel], err, style, label=label)
    ax[1].loglog(c["evals"][sel], err, style, label=label)
for k, xl in enumerate(["wall time of the stepping loop [s] (min of repeats)",
                        "right-hand-side evaluations"]):
    ax[k].axhline(ref_err, color="grey", ls=":", lw=1,
                  label="reference's estimated error")
    ax[k].set_xlabel(xl)
    ax[k].set_ylabel("max |%s - ref| %s [%s]" % (gname, where, gunit))
    ax[k].grid(True, which="both", alpha=0.3)
ax[1].legend()
fig.suptitle("work-precision, %s (model %s) to T = %g s (reference: %s)"
             % (scene, model, t_end, ref_name))
save(fig, a.output)

if a.cheapest:
    print("cheapest run reaching each accuracy (%s, %s, wall time of the "
          "stepping loop):" % (gname, where))
    for acc in [float(v) for v in a.cheapest.split(",")]:
        best = []
        for m, name in enumerate(methods):
            sel = np.nonzero((c["method"] == m) & (c["status"] == 0)
                             & (errs <= acc))[0]
            if len(sel):
                k = sel[np.argmin(c["wall"][sel])]
                step = "tol %g" % c["tol"][k] if c["adaptive"][k] else \
                    "dt %g" % c["dt"][k]
                best.append((float(c["wall"][k]), name, step,
                             float(errs[k])))
        line = "  %-8g" % acc + "".join(
            "  %s: %.3g s (%s, err %.2g);" % (n, w, st, e)
            for w, n, st, e in best)
        if best:
            w0 = min(best)
            line += "  cheapest: %s" % w0[1]
        print(line if best else "  %-8g none reaches it" % acc)
