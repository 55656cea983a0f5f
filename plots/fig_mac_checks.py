#!/usr/bin/python3
"""The thesis's two checks of the MAC solver: (a) the stratified tank at
rest, largest face speed against time; (b) the uniform stream, largest
deviation from it.  One curve per velocity update and pressure solver.

usage: fig_mac_checks.py --rest LABEL=FILE ... --uniform LABEL=FILE ...
       [-o mac_checks.png]
(the files come from `make mac-checks`: runs/mac_rest.ini and
runs/mac_uniform.ini with --set mac.update=... mac.pressure_solver=...)"""
import argparse

import numpy as np

from bfplot import load, plt, save

ap = argparse.ArgumentParser()
ap.add_argument("--rest", nargs="+", default=[])
ap.add_argument("--uniform", nargs="+", default=[])
ap.add_argument("-o", "--output", default="mac_checks.png")
a = ap.parse_args()

FLOOR = 1e-17


def style(label):
    ls = "-" if "direct" in label else "--"
    col = {"printed": "C3", "consistent": "C0", "original": "C2"}
    c = next((v for k, v in col.items() if k in label), "k")
    return ls, c


fig, ax = plt.subplots(1, 2, figsize=(12, 4.6))
for spec in a.rest:
    label, path = spec.split("=", 1)
    (t, diag), _ = load(path, "/time", "/mac/diag")
    speed = np.maximum(diag[:, 0], diag[:, 1])
    ls, c = style(label)
    ax[0].semilogy(t[1:], np.maximum(speed[1:], FLOOR), ls, color=c,
                   label=label)
ax[0].set_title("(a) stratified tank at rest: max |u|, |v| on fluid faces")
ax[0].set_xlabel("t [L/W]")
ax[0].set_ylabel("speed [W]")
ax[0].legend()

for spec in a.uniform:
    label, path = spec.split("=", 1)
    (t, u, v, flags, grid), attrs = load(path, "/time", "/mac/u", "/mac/v",
                                         "/mac/flags", "/mac/grid")
    ni, nj = int(grid[0]), int(grid[1])
    u0 = attrs["mac.u0"]
    dev = []
    for k in range(len(t)):
        U = u[k].reshape(ni + 1, nj)
        V = v[k].reshape(ni, nj + 1)
        F = flags[k].reshape(ni, nj)
        full = F == 10
        # u faces I = 2..ni (0-based 1..ni-1) next to a FULL cell
        mask = np.zeros_like(U, dtype=bool)
        mask[1:ni, :] = full[0:ni - 1, :] | full[1:ni, :]
        du = np.abs(U[mask] - u0).max() if mask.any() else 0.0
        dv = np.abs(V[1:ni - 1, 1:nj]).max()
        dev.append(max(du, dv))
    ls, c = style(label)
    if "0.1" in label:
        c = "C1"
    ax[1].semilogy(t[1:], np.maximum(np.array(dev[1:]), FLOOR), ls, color=c,
                   label=label)
ax[1].set_title("(b) uniform stream: max |u - u0|, |v| on fluid faces")
ax[1].set_xlabel("t [L/W]")
ax[1].set_ylabel("deviation [W]")
ax[1].legend()
fig.suptitle("MAC solver, the thesis's two checks (16 x 16 cells, dt = 0.05, "
             "200 steps); solid: exact pressure solve, dashed: listing's "
             "relaxation")
save(fig, a.output)
