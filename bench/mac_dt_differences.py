#!/usr/bin/python3
"""Does the MAC scheme converge in dt?  Runs runs/stratres.ini (the
reservoir, exact pressure solve: pressure_solver = direct) to T at
dt = DT0, DT0/2, ... and prints, for the velocities u and v and the
pressure p at T, the largest difference between the runs at dt and dt/2
and log2 of the ratio of successive differences (the observed order in
dt if the scheme converges: 1 for its forward-Euler predictor).

    /usr/bin/python3 bench/mac_dt_differences.py [T] [DT0] [N] [--set s.k=v]...

(defaults 0.1, 0.025, 6; the --set overrides go to every run, e.g.
--set mac.inflow=prescribed; bin/ballfilm must be built; runs in a few
seconds).  docs/accuracy.md quotes its output."""
import os
import subprocess
import sys
import tempfile

import h5py
import numpy as np

args = sys.argv[1:]
sets = []
while "--set" in args:
    k = args.index("--set")
    sets += args[k:k + 2]
    del args[k:k + 2]
T = float(args[0]) if len(args) > 0 else 0.1
DT0 = float(args[1]) if len(args) > 1 else 0.025
N = int(args[2]) if len(args) > 2 else 6
root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
fields = {"u": [], "v": [], "p": []}
dts = [DT0 / 2**k for k in range(N)]
with tempfile.TemporaryDirectory() as tmp:
    for dt in dts:
        steps = round(T / dt)
        out = os.path.join(tmp, "mac.h5")
        subprocess.run([os.path.join(root, "bin", "ballfilm"), "run",
                        os.path.join(root, "runs", "stratres.ini"),
                        "--set", "scene.dt=%.17g" % dt,
                        "--set", "scene.t_end=%.17g" % (steps * dt),
                        "--set", "scene.output_every=%d" % steps,
                        "--set", "mac.pressure_solver=direct"] + sets +
                       ["-q", "-o", out], check=True,
                       stdout=subprocess.DEVNULL)
        with h5py.File(out, "r") as f:
            for k in fields:
                fields[k].append(f["mac/" + k][-1])
print("T = %g, dt = %g ... %g" % (T, dts[0], dts[-1]))
for k, runs in fields.items():
    d = [np.max(np.abs(runs[i] - runs[i + 1])) for i in range(N - 1)]
    orders = [np.log2(d[i] / d[i + 1]) for i in range(len(d) - 1)]
    print("%s: max |f(dt) - f(dt/2)| %s; orders %s" % (
        k, " ".join("%.3g" % x for x in d),
        " ".join("%.2f" % x for x in orders)))
