#!/usr/bin/python3
"""Yasuda (2010) Fig. 5: the steady state of the film from a perturbed kink,
psi, h and the phase velocities over -10 <= x <= 10 cm at the end of the
run, with the analytic kink psi = tanh(x/sqrt 2); below, psi minus the
kink over the whole film, and the kink error, smallest volume fraction and
largest speed against time.

usage: fig5_kink.py KINK.h5 -o fig5_kink.png   (from runs/kink_steady.ini)"""
import argparse

import numpy as np

from bfplot import ALPHA, PSI, load, plt, save

ap = argparse.ArgumentParser()
ap.add_argument("run")
ap.add_argument("-o", "--output", default="fig5_kink.png")
a = ap.parse_args()

(x, T, h, psi, ud, uc, t, kerr, amin, umax), attrs = load(
    a.run, "/film/x", "/film/time", "/film/h", "/film/psi", "/film/u_d",
    "/film/u_c", "/time", "/film/kink_error", "/film/min_alpha",
    "/film/max_u")
A, B, G = attrs["film.a"], attrs["film.b"], attrs["film.gamma"]
x0 = attrs["film.center"]
kink = np.sqrt(A / B) * np.tanh((x - x0) / (np.sqrt(2) * np.sqrt(G / A)))
w = np.abs(x) <= 10
fig, ax = plt.subplots(2, 2, figsize=(11, 8))
p = ax[0][0]
p.plot(x[w], psi[-1][w], "o", ms=3, label="%s, t = %g s" % (PSI, T[-1]))
p.plot(x[w], kink[w], "-", lw=1, label=r"$\tanh(x/\sqrt{2})$")
p.plot(x[w], h[-1][w], "-", label="h [cm]")
p.set_xlabel("x [cm]")
p.set_ylabel(r"%s [1],  h [cm]" % PSI)
p.set_title("(A) steady state (Fig. 5)")
p.legend()
p = ax[0][1]
p.plot(x[w], ud[-1][w], label="$u_d$")
p.plot(x[w], uc[-1][w], label="$u_c$")
p.set_xlabel("x [cm]")
p.set_ylabel("u [cm/s]")
p.set_title("(B) phase velocities at t = %g s" % T[-1])
p.legend()
p = ax[1][0]
p.plot(x, psi[-1] - kink, lw=0.8)
p.set_xlabel("x [cm]")
p.set_ylabel(r"%s $-$ kink [1]" % PSI)
p.set_title("(C) %s minus the analytic kink, whole film" % PSI)
p = ax[1][1]
p.semilogy(t, kerr, label=r"max |%s $-$ kink| [1]" % PSI)
p.semilogy(t, np.maximum(amin, 1e-20), label="min volume fraction %s [1]"
           % ALPHA)
p.semilogy(t, umax, label="max |u| [cm/s]")
p.set_xlabel("t [s]")
p.set_ylabel("[1] or [cm/s]")
p.set_title("(D) history")
p.legend()
fig.suptitle("Kink steady state (Yasuda 2010, Fig. 5): dx = %g cm, dt = %g s, "
             "perturbation %g, $\\mu$ Taylor = %s"
             % (attrs["film.dx"], attrs["scene.dt"],
                attrs["film.perturbation"],
                attrs["film.mu_taylor"].decode()
                if isinstance(attrs["film.mu_taylor"], bytes)
                else attrs["film.mu_taylor"]))
save(fig, a.output)
