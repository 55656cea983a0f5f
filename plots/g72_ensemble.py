#!/usr/bin/python3
"""Greenspan (1972) Example 1 ensemble: summarises runs of
runs/greenspan72_ex1.ini whose velocities were perturbed by tiny amounts
(make fig-g72-ex1-ensemble).  For each settling criterion (model
greenspan72, dataset diag/settle) it prints how many runs satisfy it at
step 2080 (the paper's complete interchange) and at every output row from
2080 to 3040, and draws the fraction of runs satisfying it over time.
It only summarises; nothing here decides pass/fail.

usage: g72_ensemble.py RUN1.h5 RUN2.h5 ... -o OUT.png [--table OUT.txt]"""
import argparse

import numpy as np

from bfplot import load, plt, save

ap = argparse.ArgumentParser()
ap.add_argument("files", nargs="+")
ap.add_argument("-o", "--output", default="g72_ex1_ensemble.png")
ap.add_argument("--table", default=None)
ap.add_argument("--label", default="")
a = ap.parse_args()

names = ["(a) every heavy below every light",
         "(b) all 4 heavy in the bottom band y < 25",
         "(c) at least 3 heavy in the bottom band",
         "(d) mean height heavy < mean height light"]
rows = []
steps = None
for f in a.files:
    (st, s), attrs = load(f, "/step", "/diag/settle")
    nh = int(np.sum(load(f, "/particles/tag")[0][0] == 1))
    held = np.stack([s[:, 0] > 0, s[:, 1] > 0, s[:, 2] + 1 >= nh,
                     s[:, 3] > 0], axis=1)
    rows.append(held)
    steps = st
held = np.array(rows)  # runs x rows x 4
n = held.shape[0]
i2080 = int(np.searchsorted(steps, 2080))
after = steps >= 2080
lines = ["Example 1 ensemble %s: %d runs" % (a.label, n),
         "%-45s %12s %16s" % ("criterion", "at t_2080", "t_2080..t_3040")]
for k, nm in enumerate(names):
    at = held[:, i2080, k].sum()
    always = held[:, after, k].all(axis=1).sum()
    lines.append("%-45s %5d (%3.0f%%) %8d (%3.0f%%)"
                 % (nm, at, 100.0 * at / n, always, 100.0 * always / n))
text = "\n".join(lines)
print(text)
if a.table:
    with open(a.table, "w") as fh:
        fh.write(text + "\n")

fig, ax = plt.subplots(figsize=(9, 4.5))
for k, nm in enumerate(names):
    ax.plot(steps, held[:, :, k].mean(axis=0), label=nm)
ax.axvline(2080, color="C7", ls=":", lw=1)
ax.set_xlabel("step")
ax.set_ylabel("fraction of runs")
ax.set_ylim(-0.02, 1.02)
ax.legend(loc="upper left")
ax.set_title("Example 1, %d runs, initial velocities perturbed by up to "
             "+-0.005 %s" % (n, a.label))
save(fig, a.output)
