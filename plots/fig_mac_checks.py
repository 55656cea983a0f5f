#!/usr/bin/python3
"""The thesis's two checks of the MAC solver: (a) the stratified tank at
rest, largest face speed against time; (b) the uniform stream, largest
deviation from it; (c) with --homogeneous, the same tank of one density
(mac.rho_amp = 0).  One curve per velocity update and pressure solver.
Prints the largest face speed of every tank run.

usage: fig_mac_checks.py --rest LABEL=FILE ... --uniform LABEL=FILE ...
       [--homogeneous LABEL=FILE ...] [-o mac_checks.png]
(the files come from `make mac-checks`: runs/mac_rest.ini and
runs/mac_uniform.ini with --set mac.update=... mac.pressure_solver=...)"""
import argparse

import numpy as np

from bfplot import load, plt, save

ap = argparse.ArgumentParser()
ap.add_argument("--rest", nargs="+", default=[])
ap.add_argument("--uniform", nargs="+", default=[])
ap.add_argument("--homogeneous", nargs="+", default=[])
ap.add_argument("-o", "--output", default="mac_checks.png")
a = ap.parse_args()

FLOOR = 1e-17


def style(label):
    ls = "-" if "direct" in label else "--"
    col = {"printed": "C3", "consistent": "C0", "original": "C2"}
    c = next((v for k, v in col.items() if k in label), "k")
    return ls, c


npanel = 3 if a.homogeneous else 2
fig, ax = plt.subplots(1, npanel, figsize=(6 * npanel, 4.6))
print("%-34s %10s %10s" % ("tank at rest: update, solver", "max |u|",
                           "max |v|"))


def tank(p, specs, kind):
    for spec in specs:
        label, path = spec.split("=", 1)
        (t, diag), _ = load(path, "/time", "/mac/diag")
        speed = np.maximum(diag[:, 0], diag[:, 1])
        print("%-34s %10.2e %10.2e" % (kind + ", " + label,
                                       diag[1:, 0].max(), diag[1:, 1].max()))
        ls, c = style(label)
        p.semilogy(t[1:], np.maximum(speed[1:], FLOOR), ls, color=c,
                   label=label)
    p.set_xlabel("t [L/W]")
    p.set_ylabel("speed [W]")
    p.legend()


tank(ax[0], a.rest, "stratified")
ax[0].set_title("(a) stratified tank at rest: max |u|, |v| on fluid faces")
if a.homogeneous:
    tank(ax[2], a.homogeneous, "homogeneous")
    ax[2].set_title("(c) homogeneous tank at rest (rho_amp = 0): max |u|, "
                    "|v|")

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
