#!/usr/bin/python3
"""The ball on a vibrating table (runs/vibrating_table.ini,
docs/models/vibrating_table.md): the bifurcation diagram of the impact
phase against Gamma = A (2 pi f)^2 / g from a `ballfilm sweep` over
[floor] amplitude, beside the hard-impact theory.

Left: the phase 2 pi f t mod 2 pi of the impacts in the last LAST seconds
of each case (the instants of /return_map/time: the ball's lowest point in
each floor contact), against Gamma; over it the theory's period-1 branches
arccos(Gamma_1 / Gamma) (one impact per n table periods, n = 1, 2: solid
where stable, dashed beyond the period doubling), the thresholds Gamma_1
and Gamma_2, and grey dots: the exact hard-impact map iterated from the
same drop (instantaneous impacts on the sine table, Newton's restitution
law; a ball whose rebound falls below 1e-6 of g/(2 pi f) sticks and leaves
where the table's acceleration reaches -g).  Right: the ball and the table
over the last periods of the scene's own run, with its impacts.

Printed: the thresholds, the phase of the scene's run against the theory,
and a check of Gamma_2 on the exact map (period 1 just below, period 2
just above).

usage: vibrating_table.py SWEEP_DIR RUN.h5 -o vibrating_table.png [--last S]"""
import argparse
import glob
import math
import os

import numpy as np

from bfplot import GAMMA, attr_str, ballfilm, legend_below, plt, save

ap = argparse.ArgumentParser()
ap.add_argument("dir", help="the sweep's directory (case_NNNNN.h5)")
ap.add_argument("run", help="a run of runs/vibrating_table.ini")
ap.add_argument("-o", "--output", default="vibrating_table.png")
ap.add_argument("--last", type=float, default=2.0,
                help="seconds at the end of each case whose impacts are drawn")
a = ap.parse_args()


def thresholds(e, n):
    """Gamma_1 (existence) and Gamma_2 (period doubling) of the orbit with
    one impact per n table periods, exact sine-table map; and Gamma_2 of
    the high-bounce approximation (docs/models/vibrating_table.md)."""
    g1 = n * math.pi * (1 - e) / (1 + e)
    b = 2 * (1 + e * e) / (1 + e) ** 2
    return g1, math.hypot(g1, b), math.hypot(g1, 1.0)


def next_impact(t, x, v, A, w, g):
    """The first time after t at which a ball at height x (cm, its bottom)
    with velocity v (cm/s) meets the table A sin(w t): the first sign change
    of the gap on a grid of 1/400 period, then bisection to 1e-15 s."""
    def gap(tau):
        return x + v * tau - 0.5 * g * tau * tau - A * np.sin(w * (t + tau))
    h = 2 * math.pi / w / 400
    lo = 0.0
    if gap(h) <= 0:  # a flight shorter than the grid: halve until above
        hi = h
        lo = h / 2
        while gap(lo) <= 0 and lo > 1e-14:
            hi, lo = lo, lo / 2
    else:
        taus = h * np.arange(1, 401)
        for _ in range(50):  # at most 50 table periods in flight
            gs = gap(lo + taus)
            below = np.nonzero(gs <= 0)[0]
            if below.size:
                k = below[0]
                hi = lo + taus[k]
                lo = lo + (taus[k - 1] if k else 0.0)
                break
            lo += taus[-1]
        else:
            return None
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        if gap(mid) > 0:
            lo = mid
        else:
            hi = mid
    return t + hi


def hard_orbit(gamma, e, f, g, h0, impacts=150, t_keep=2.0):
    """Impact phases of the exact hard-impact map for a ball dropped from
    rest with its bottom h0 above the table's mean, in the last t_keep
    seconds of the first `impacts` impacts."""
    w = 2 * math.pi * f
    A = gamma * g / w ** 2
    t, x, v = 0.0, h0, 0.0
    times = []
    slow = 1e-6 * g / w
    while len(times) < impacts:
        tn = next_impact(t, x, v, A, w, g)
        if tn is None:
            break
        u = A * w * math.cos(w * tn)
        vin = v - g * (tn - t)
        times.append(tn)
        t, x, v = tn, A * math.sin(w * tn), u - e * (vin - u)
        if v - u < slow:  # stuck: leave where the table's acceleration is -g
            if gamma <= 1:
                break
            lift = math.asin(1 / gamma)
            t = (math.floor(w * t / (2 * math.pi)) * 2 * math.pi + lift) / w
            while t < tn:
                t += 2 * math.pi / w
            x, v = A * math.sin(w * t), A * w * math.cos(w * t)
    times = np.array(times)
    if times.size == 0:
        return times
    keep = times[times > times[-1] - t_keep]
    return (w * keep) % (2 * math.pi)


def period_of(phases, tol=1e-6):
    """1 if the last phases repeat every impact, 2 every other, else 0."""
    p = phases[-8:]
    if len(p) < 8:
        return 0
    if np.ptp(p) < tol:
        return 1
    if np.ptp(p[::2]) < tol and np.ptp(p[1::2]) < tol:
        return 2
    return 0


# ---- the sweep's cases ----
cases = sorted(glob.glob(os.path.join(a.dir, "case_*.h5")))
if not cases:
    raise SystemExit("vibrating_table.py: no case_*.h5 in %s" % a.dir)
gam, phase = [], []
first = None
for path in cases:
    r = ballfilm.load(path)
    if r.status != "ok":
        print("vibrating_table.py: %s ended %s" % (path, r.status))
        continue
    p = r.params
    A, f, g = (p["floor.amplitude"], p["floor.frequency"], p["gravity.g"])
    first = first or p
    t = r["return_map/time"]
    t = t[t > t[-1] - a.last] if len(t) else t
    gm = A * (2 * math.pi * f) ** 2 / g
    gam.extend([gm] * len(t))
    phase.extend((2 * math.pi * f * t) % (2 * math.pi))
gam, phase = np.array(gam), np.array(phase)
e, f, g = (first["floor.restitution"], first["floor.frequency"],
           first["gravity.g"])
h0 = first["ball.1.position"] - first["ball.1.radius"]
w = 2 * math.pi * f

# ---- the theory ----
gmin, gmax = gam.min(), gam.max()
print("hard-impact theory, e = %g:" % e)
branches = []
for n in (1, 2, 3):
    g1, g2, g2hb = thresholds(e, n)
    print("  n = %d: Gamma_1 = %.4f, Gamma_2 = %.4f (high-bounce "
          "approximation %.4f)" % (n, g1, g2, g2hb))
    if g1 < gmax:
        branches.append((n, g1, g2))
g1, g2, g2hb = thresholds(e, 1)
for s in (0.995, 1.005):
    ph = hard_orbit(s * g2, e, f, g, h0, impacts=400)
    print("  exact map at %.3f Gamma_2 (%.4f): period %d" %
          (s, s * g2, period_of(ph)))
grid = np.linspace(gmin, gmax, 111)
hard_g, hard_p = [], []
for gm in grid:
    ph = hard_orbit(gm, e, f, g, h0, t_keep=a.last)
    hard_g.extend([gm] * len(ph))
    hard_p.extend(ph)

# ---- the scene's run ----
run = ballfilm.load(a.run)
rp = run.params
rA = rp["floor.amplitude"]
rgam = rA * w ** 2 / g
rt = run["return_map/time"]
rphi = (w * rt[-10:]) % (2 * math.pi)
theory = math.acos(g1 / rgam) if rgam >= g1 else float("nan")
print("the scene's run, Gamma = %.4f: last 10 impact phases %.5f +- %.1e "
      "rad, theory %.5f (difference %+.2e)" %
      (rgam, rphi.mean(), np.ptp(rphi) / 2, theory, rphi.mean() - theory))

# ---- draw ----
fig, ax = plt.subplots(1, 2, figsize=(16, 8.5),
                       gridspec_kw={"width_ratios": [1.5, 1]})
ax[0].plot(hard_g, hard_p, ".", ms=2.5, color="0.65",
           label="exact hard-impact map (same drop)")
ax[0].plot(gam, phase, ".", ms=2, color="C0",
           label="simulation: impacts of the last %g s" % a.last)
for n, b1, b2 in branches:
    c = "C%d" % (n + 1)
    gs = np.linspace(b1, min(b2, gmax), 200)
    ax[0].plot(gs, np.arccos(b1 / gs), "-", color=c, lw=1.5,
               label="theory, n = %d: arccos(%s$_1$/%s), %s$_1$ = %.3f, "
               "%s$_2$ = %.3f" % (n, GAMMA, GAMMA, GAMMA, b1, GAMMA, b2))
    if b2 < gmax:
        gs = np.linspace(b2, gmax, 200)
        ax[0].plot(gs, np.arccos(b1 / gs), "--", color=c, lw=1)
        ax[0].axvline(b2, color=c, lw=0.8, ls="-.")
    ax[0].axvline(b1, color=c, lw=0.8, ls=":")
# what the line styles mean, once
ax[0].plot([], [], "k--", lw=1, label="unstable beyond %s$_2$" % GAMMA)
ax[0].plot([], [], "k:", lw=0.8, label="%s$_1$: the orbit appears" % GAMMA)
ax[0].plot([], [], "k-.", lw=0.8, label="%s$_2$: period doubling" % GAMMA)
ax[0].axvline(g2hb, color="0.4", lw=1, ls=(0, (1, 3)),
              label="%s$_2$ = %.3f of the high-bounce approximation (n = 1)"
              % (GAMMA, g2hb))
ax[0].plot([rgam], [rphi.mean()], "*", ms=13, color="k", mfc="none",
           label="the scene, %s = %.3f" % (GAMMA, rgam))
ax[0].set_xlim(gmin, gmax)
ax[0].set_ylim(0, 2 * math.pi)
ax[0].set_xlabel("%s = A (2πf)$^2$/g" % GAMMA)
ax[0].set_ylabel("impact phase 2πf t mod 2π [rad]")
ax[0].set_title("bifurcation diagram, e = %g, f = %g Hz, k = %.0e"
                % (e, f, first["floor.k"]))
legend_below(ax[0], ncol=2)

T = 1 / f
tt = run.time
sel = tt > tt[-1] - 4 * T
ax[1].plot(tt[sel], run["balls/position"][sel, 0] - rp["ball.1.radius"],
           color="C0", label="ball (its bottom)")
ax[1].plot(tt[sel], rA * np.sin(w * tt[sel]), color="C3", label="table")
imp = rt[rt > tt[-1] - 4 * T]
ax[1].plot(imp, rA * np.sin(w * imp), "kv", label="impacts")
ax[1].set_xlabel("t [s]")
ax[1].set_ylabel("height above the table's mean [cm]")
ax[1].set_title("%s = %.3f: impact phase %.4f rad (theory %.4f)"
                % (GAMMA, rgam, rphi.mean(), theory))
legend_below(ax[1], ncol=3)
fig.suptitle("%s: the impact phase against the table's acceleration"
             % attr_str(run.attrs, "scene.title"))
save(fig, a.output)
