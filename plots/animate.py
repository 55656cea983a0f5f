#!/usr/bin/python3
"""animate.py: a movie of a ballfilm run, one frame per output row (thinned
to --frames rows spread evenly over --t0..--t1).

  balls        positions against time with the contacts marked, and the
               phase point (x, v) of every ball with its recent trail;
  film,        psi(x) and h(x) with the balls drawn on the film and the
  coupled      coupling kernel exp(-|x - X_i|/r0) under each ball; time
               and the relative energy change above the axes (Yasuda 2010,
               Fig. 8 in motion);
  greenspan72  the particles coloured by fluid inside the box's walls;
  greenspan73  fluid particles and wall particles (fixed ones outlined);
  mac          the markers coloured by density over the speed (or
               pressure) field, walls, inflow and the sink marked.

Legends stand beside or under the axes and the time stamp above them,
never over the data; the title is the run's own (its scene title, with
the steps the file holds and its perturbation).  Text is sized with the
frame's height (bfplot.fonts); --talk makes 1920x1080 frames for a talk.

Rows are read one at a time (h5py slices), so memory does not grow with
the run's length or particle count.  MP4 needs Debian's ffmpeg; without
it the movie is a GIF written through Pillow (and the script says so).

usage: animate.py OUT.h5 [-o MOVIE.mp4] [--fps N] [--frames N]
                  [--t0 T] [--t1 T] [--size WxH] [--field speed|p]
                  [--xlim A B] [--talk] [--quiet]
(`ballfilm animate OUT.h5 ...` runs this script.)"""
import argparse
import os
import re
import shutil
import sys
import tempfile
import textwrap

try:
    import h5py
    import numpy as np
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib import animation
    from matplotlib.lines import Line2D
    from bfplot import PSI, fonts, legend_below, legend_beside
except ImportError as e:  # pragma: no cover - depends on the machine
    sys.exit("animate: %s; it needs Debian's packages: sudo apt-get install "
             "-y python3-numpy python3-matplotlib python3-h5py (ffmpeg for "
             "MP4, python3-pil for GIF)" % e)

TRAIL = 40  # the phase-plane trail: 1/TRAIL of the shown rows


def attr(f, key, default=None):
    v = f.attrs.get(key, default)
    if isinstance(v, bytes):
        v = v.decode()
    if isinstance(v, np.ndarray) and v.shape == ():
        v = v[()]
    return v


def frames_of(times, nframes, t0, t1):
    """Indices of at most nframes rows with t0 <= t <= t1, evenly spread,
    first and last included (floor(x + 1/2) keeps them distinct)."""
    lo = -np.inf if t0 is None else t0
    hi = np.inf if t1 is None else t1
    idx = np.nonzero((times >= lo - 1e-12) & (times <= hi + 1e-12))[0]
    if len(idx) == 0:
        sys.exit("animate: no output row in %s..%s" % (t0, t1))
    if len(idx) <= nframes:
        return idx
    pos = np.floor(np.linspace(0, len(idx) - 1, nframes) + 0.5).astype(int)
    return idx[pos]


def strided(ds, i0, i1, most=4000):
    """Rows i0..i1 of ds, every k-th so that at most `most` come back, and
    their indices."""
    step = max(1, int(np.ceil((i1 - i0 + 1) / most)))
    return np.arange(i0, i1 + 1, step), ds[i0:i1 + 1:step]


def stamp(ax):
    """The time stamp: a title on the right above the axes (outside the
    data), monospaced so that it keeps its width from frame to frame; the
    axes carry no other title."""
    return ax.set_title(" ", loc="right", family="monospace",
                        fontsize="medium")


def run_title(f, fallback):
    """The run's title: its scene title without a step count of its own
    (the scene's, not necessarily the file's)."""
    title = str(attr(f, "scene.title", "") or fallback)
    return re.sub(r"(,\s*)?\b\d+ steps\b", "", title).strip(" ,:")


def fit_title(fig, text):
    """text with each line broken to fit the figure's width."""
    size = matplotlib.font_manager.FontProperties(
        size=matplotlib.rcParams["figure.titlesize"]).get_size_in_points()
    width = max(20, int(fig.get_figwidth() * 72 / (0.55 * size)))
    return "\n".join(textwrap.fill(line, width)
                      for line in text.split("\n"))


def energy_text(f, t):
    """Relative energy change at the /time row nearest t ('' if none)."""
    if "/energy/total" not in f or "/time" not in f:
        return ""
    times = f["/time"]
    k = min(int(np.searchsorted(times[()], t)), len(times) - 1)
    e = f["/energy/total"]
    e0, ek = e[0], e[k]
    rel = (ek - e0) / abs(e0) if e0 != 0 else ek - e0
    return "   (E - E0)/|E0| = %+.2e" % rel


# --------------------------------------------------------------- balls

class Balls:
    """Balls on a line: x_i(t) with contacts, and the phase plane."""

    def __init__(self, f, a):
        self.f = f
        self.t = f["/time"][()]
        self.frames = frames_of(self.t, a.frames, a.t0, a.t1)
        self.x, self.v = f["/balls/position"], f["/balls/velocity"]
        self.R = f["/balls/radius"][()]
        self.floor = "floor" in str(attr(f, "scene.effects", ""))
        i0, i1 = self.frames[0], self.frames[-1]
        self.ti, self.xs = strided(self.x, i0, i1)
        self.vs = strided(self.v, i0, i1)[1]
        self.contacts = self.find_contacts(i0, i1)

    def find_contacts(self, i0, i1, chunk=65536, most=20000):
        """(t, x) where a contact begins (ball-ball: x_j+1 - x_j <= R_j +
        R_j+1; ball-floor: x_0 <= R_0), scanning every row in chunks."""
        out_t, out_x = [], []
        prev = None
        for c0 in range(i0, i1 + 1, chunk):
            c1 = min(i1 + 1, c0 + chunk)
            x = self.x[c0:c1]
            touch = [x[:, j + 1] - x[:, j] <= self.R[j] + self.R[j + 1]
                     for j in range(x.shape[1] - 1)]
            where = [0.5 * (x[:, j] + x[:, j + 1])
                     for j in range(x.shape[1] - 1)]
            if self.floor:
                touch.append(x[:, 0] <= self.R[0])
                where.append(x[:, 0] - self.R[0])
            if not touch:
                return np.zeros(0), np.zeros(0)
            touch, where = np.array(touch).T, np.array(where).T
            before = np.vstack([prev if prev is not None
                                else np.zeros_like(touch[:1]), touch[:-1]])
            onset = touch & ~before
            r, p = np.nonzero(onset)
            out_t.append(self.t[c0 + r])
            out_x.append(where[r, p])
            prev = touch[-1:]
        t, x = np.concatenate(out_t), np.concatenate(out_x)
        if len(t) > most:
            keep = np.linspace(0, len(t) - 1, most).astype(int)
            t, x = t[keep], x[keep]
        return t, x

    def setup(self, fig):
        axp, axs = fig.subplots(1, 2, gridspec_kw={"width_ratios": [1.6, 1]})
        n = self.xs.shape[1]
        for j in range(n):
            axp.plot(self.t[self.ti], self.xs[:, j], lw=0.7, color="C%d" % j,
                     label="ball %d" % (j + 1))
        ct, cx = self.contacts
        axp.plot(ct, cx, "k|", ms=5, mew=0.6,
                 label="contact begins (%d)" % len(ct))
        self.cursor = axp.axvline(self.t[self.frames[0]], color="k", lw=0.8)
        self.now = axp.plot(np.zeros(n), np.zeros(n), "ko", ms=4)[0]
        axp.set_xlabel("t [s]")
        axp.set_ylabel("position [cm]")
        axp.set_title("positions and contacts", loc="left")
        legend_below(axp, ncol=n + 1)
        self.trails, self.points = [], []
        for j in range(n):
            axs.plot(self.xs[:, j], self.vs[:, j], ",", color="C%d" % j,
                     alpha=0.5)
            self.trails.append(axs.plot([], [], lw=1.2, color="C%d" % j)[0])
            self.points.append(axs.plot([], [], "o", color="C%d" % j,
                                        ms=6, mec="k")[0])
        axs.set_xlabel("position [cm]")
        axs.set_ylabel("velocity [cm/s]")
        self.text = stamp(axs)

    def draw(self, n):
        k = self.frames[n]
        t = self.t[k]
        x, v = self.x[k], self.v[k]
        self.cursor.set_xdata([t, t])
        self.now.set_data(np.full(len(x), t), x)
        # the trail: the last 1/TRAIL of the shown rows, at most 2000
        span = max(1, (self.frames[-1] - self.frames[0]) // TRAIL)
        lo = max(self.frames[0], k - span)
        xt, vt = strided(self.x, lo, k, 2000)[1], strided(self.v, lo, k,
                                                          2000)[1]
        for j in range(len(x)):
            self.trails[j].set_data(xt[:, j], vt[:, j])
            self.points[j].set_data([x[j]], [v[j]])
        self.text.set_text("t = %.4f s%s" % (t, energy_text(self.f, t)
                                             .replace("   ", "\n")))

    def title(self, f, fallback):
        return run_title(f, fallback)


# ---------------------------------------------------------------- film

class Film:
    """psi(x), h(x), the balls and their coupling kernels."""

    def __init__(self, f, a):
        self.f = f
        self.t = f["/film/time"][()]
        self.frames = frames_of(self.t, a.frames, a.t0, a.t1)
        self.xn = f["/film/x"][()]
        self.psi, self.h = f["/film/psi"], f["/film/h"]
        self.balls = "/balls/position" in f
        self.r0 = float(attr(f, "coupling.r0", 0.5))
        lo, hi = self.xn[0], self.xn[-1]
        if self.balls:
            bt = f["/time"][()]
            self.brow = [min(int(np.searchsorted(bt, self.t[k])),
                             len(bt) - 1) for k in self.frames]
            xb = strided(f["/balls/position"], self.brow[0],
                         self.brow[-1])[1]
            margin = max(8 * self.r0, 1.0)
            lo = max(lo, xb.min() - margin)
            hi = min(hi, xb.max() + margin)
        if a.xlim:
            lo, hi = a.xlim
        self.lim = (lo, hi)
        self.win = (self.xn >= lo) & (self.xn <= hi)
        hmin, hmax = np.inf, -np.inf
        for k in self.frames:  # one row of h at a time
            hw = self.h[k][self.win]
            hmin, hmax = min(hmin, hw.min()), max(hmax, hw.max())
        pad = 0.05 * (hmax - hmin) if hmax > hmin else 1e-6 * abs(hmax) + 1e-9
        self.hlim = (hmin - pad, hmax + pad)

    def setup(self, fig):
        axp, axh = fig.subplots(2, 1, sharex=True)
        self.lp = axp.plot([], [], "C0-", label=PSI)[0]
        axp.set_ylim(-1.15, 1.15)
        axp.set_ylabel(r"%s = $\alpha_d - \alpha_c$ [1]" % PSI)
        axp.set_xlim(*self.lim)
        self.lh = axh.plot([], [], "C2-", label="h")[0]
        axh.set_ylim(*self.hlim)
        axh.set_ylabel("h [cm]")
        axh.set_xlabel("x [cm]")
        self.text = stamp(axp)
        self.kern, self.dots = [], None
        if self.balls:
            nb = self.f["/balls/position"].shape[1]
            R = self.f["/balls/radius"][()]
            self.R = R
            for j in range(nb):
                self.kern.append(axp.fill_between(
                    [], [], [], color="C%d" % (j + 1), alpha=0.0))
            self.axp = axp
            self.dots = axh.scatter(np.zeros(nb), np.zeros(nb), s=60,
                                    c=["C%d" % (j + 1) for j in range(nb)],
                                    edgecolors="k", zorder=3)
            self.marks = axp.scatter(np.zeros(nb), np.zeros(nb), s=40,
                                     c=["C%d" % (j + 1) for j in range(nb)],
                                     edgecolors="k", zorder=3, marker="v")
            axp.plot([], [], color="C1", alpha=0.4, lw=6,
                     label="kernel\n$e^{-|x - X_i|/r_0}$\n$r_0$ = %g cm"
                     % self.r0)
            axh.scatter([], [], s=60, c="C1", edgecolors="k",
                        label="balls")
            legend_beside(axh)
        legend_beside(axp)

    def draw(self, n):
        k = self.frames[n]
        x = self.xn[self.win]
        psi, h = self.psi[k][self.win], self.h[k][self.win]
        self.lp.set_data(x, psi)
        self.lh.set_data(x, h)
        extra = ""
        if self.balls:
            br = self.brow[n]
            xb = self.f["/balls/position"][br]
            hb = np.interp(xb, x, h)
            self.dots.set_offsets(np.column_stack([xb, hb]))
            self.marks.set_offsets(np.column_stack([xb, np.full(len(xb),
                                                                 1.08)]))
            for j, c in enumerate(self.kern):
                c.remove()
                w = np.exp(-np.abs(x - xb[j]) / self.r0)
                self.kern[j] = self.axp.fill_between(
                    x, -1.15, -1.15 + 0.6 * w, color="C%d" % (j + 1),
                    alpha=0.35, lw=0)
            extra = energy_text(self.f, self.t[k])
        self.text.set_text("t = %.4f s%s" % (self.t[k], extra))

    def title(self, f, fallback):
        p = float(attr(f, "film.perturbation", 0) or 0)
        return run_title(f, fallback) + (
            "\nkink perturbed by %g" % p if p else "")


# ----------------------------------------------------------- particles

class Particles:
    """Greenspan's particles: fluids by colour, walls, wall particles."""

    def __init__(self, f, a):
        self.f = f
        self.step = None
        if "/particles/step" in f:
            self.step = f["/particles/step"][()]
            self.t = self.step * float(attr(f, "scene.dt"))
        else:
            self.t = f["/time"][()]
        self.frames = frames_of(self.t, a.frames, a.t0, a.t1)
        self.x, self.y = f["/particles/x"], f["/particles/y"]
        self.n = self.x.shape[1]
        self.model = str(attr(f, "scene.model"))
        self.box = None
        if self.model == "greenspan72":
            self.box = (float(attr(f, "greenspan72.width")),
                        float(attr(f, "greenspan72.height")))
            tag = f["/particles/tag"][()]
            self.groups = [("heavy fluid L1", tag == 1, "C3"),
                           ("light fluid L2", tag == 2, "C0")]
        else:
            fixed = (f["/particles/fixed"][()] > 0
                     if "/particles/fixed" in f else np.zeros(self.n, bool))
            wall = np.zeros(self.n, bool)
            if str(attr(f, "greenspan73.layout")) == "wall":
                wall[1:] = True
            self.groups = [("fluid particles", ~wall & ~fixed, "C0"),
                           ("wall particles", wall & ~fixed, "0.45"),
                           ("fixed particles", fixed, "k")]
            self.groups = [g for g in self.groups if g[1].any()]
            self.span = self.extent()

    def extent(self):
        """Half widths of a window that follows the centre of the
        particles and holds them in every frame."""
        wx = wy = 0.0
        for k in self.frames:
            x, y = self.x[k], self.y[k]
            wx = max(wx, np.ptp(x) / 2, abs(x - x.mean()).max())
            wy = max(wy, np.ptp(y) / 2, abs(y - y.mean()).max())
        w = 1.15 * max(wx, wy, 1e-6)
        return w, w

    def setup(self, fig):
        ax = fig.subplots(1, 1)
        self.ax = ax
        self.arts = []
        big = self.n > 20000
        for name, sel, col in self.groups:
            if big:
                art = ax.plot([], [], ",", color=col, label=name)[0]
            else:
                s = 30 if self.n < 100 else max(2, 3000 / self.n)
                art = ax.scatter([], [], s=s, color=col, label=name,
                                 marker="s" if "wall" in name or "fixed" in
                                 name else "o", lw=0)
            self.arts.append((art, sel, big))
        if self.box:
            W, H = self.box
            ax.plot([0, 0, W, W, 0], [0, H, H, 0, 0], "k-", lw=1.5,
                    label="walls")
            m = 0.03 * max(W, H)
            ax.set_xlim(-m, W + m)
            ax.set_ylim(-m, H + m)
        ax.set_aspect("equal")
        ax.set_xlabel("x [cm]")
        ax.set_ylabel("y [cm]")
        handles, labels = ax.get_legend_handles_labels()
        if big:  # pixel markers do not show in a legend: squares instead
            handles = [Line2D([], [], ls="", marker="s", color=h.get_color())
                       if h.get_marker() == "," else h for h in handles]
        ax.legend(handles, labels, loc="upper left", bbox_to_anchor=(1.04, 1),
                  borderaxespad=0, markerscale=1.5 if not big else 1)
        self.text = stamp(ax)

    def draw(self, n):
        k = self.frames[n]
        x, y = self.x[k], self.y[k]
        for art, sel, big in self.arts:
            if big:
                art.set_data(x[sel], y[sel])
            else:
                art.set_offsets(np.column_stack([x[sel], y[sel]]))
        if not self.box:
            wx, wy = self.span
            cx, cy = x.mean(), y.mean()
            self.ax.set_xlim(cx - wx, cx + wx)
            self.ax.set_ylim(cy - wy, cy + wy)
        step = ("step %d" % self.step[k] if self.step is not None
                else "row %d" % k)
        self.text.set_text("t = %.4f s (%s)%s"
                           % (self.t[k], step, energy_text(self.f, self.t[k])
                              if self.model == "greenspan73" else ""))

    def title(self, f, fallback):
        """The scene title with the steps in the file (not the scene's
        own count) and the perturbation of the initial velocities."""
        dt = float(attr(f, "scene.dt", 0) or 0)
        if self.step is not None:
            steps = int(self.step[-1])
        else:
            steps = int(round(self.t[-1] / dt)) if dt else len(self.t) - 1
        title = run_title(f, fallback)
        count = ("" if "N = %d" % self.n in title
                 else "%d particles, " % self.n)
        text = "%s\n%s%d steps of %g s" % (title, count, steps, dt)
        if self.model == "greenspan72":
            p = float(attr(f, "greenspan72.perturb", 0) or 0)
            text += (", velocities perturbed by \u00b1%g cm/s (seed %d)"
                     % (p, int(float(attr(f, "greenspan72.perturb_seed", 0))))
                     if p else ", unperturbed")
        return text


# ----------------------------------------------------------------- MAC

class Mac:
    """Markers coloured by density over the speed or pressure field."""

    def __init__(self, f, a):
        self.f = f
        self.t = f["/time"][()]
        self.frames = frames_of(self.t, a.frames, a.t0, a.t1)
        ni, nj, dx, dy = f["/mac/grid"][()]
        self.ni, self.nj, self.dx, self.dy = int(ni), int(nj), dx, dy
        self.field = a.field
        live = []
        for k in self.frames:
            fl = f["/mac/particles/flag"][k] > 1
            live.append(f["/mac/particles/density"][k][fl])
        live = np.concatenate(live) if live else np.zeros(1)
        self.dlim = (live.min(), live.max()) if live.size else (0, 1)
        vmax = 0.0
        for k in self.frames:  # over the fluid cells (FULL, SUR)
            fluid = np.isin(f["/mac/flags"][k].reshape(self.ni, self.nj),
                            (10, 11))
            vals = np.abs(self.values(k))[fluid]
            if vals.size:
                vmax = max(vmax, np.nanmax(vals))
        vmax = vmax or 1.0
        self.vlim = (0, vmax) if self.field == "speed" else (-vmax, vmax)

    def values(self, k):
        """The field of row k on the cells, [ni x nj]."""
        ni, nj = self.ni, self.nj
        if self.field == "p":
            return self.f["/mac/p"][k].reshape(ni, nj)
        u = self.f["/mac/u"][k].reshape(ni + 1, nj)
        v = self.f["/mac/v"][k].reshape(ni, nj + 1)
        uc = 0.5 * (u[:-1, :] + u[1:, :])
        vc = 0.5 * (v[:, :-1] + v[:, 1:])
        return np.hypot(uc, vc)

    def setup(self, fig):
        ax = fig.subplots(1, 1)
        dx, dy, ni, nj = self.dx, self.dy, self.ni, self.nj
        ext = (-dx, (ni - 1) * dx, -dy, (nj - 1) * dy)
        self.img = ax.imshow(np.zeros((nj, ni)), origin="lower", extent=ext,
                             cmap="Greys" if self.field == "speed" else
                             "RdBu_r", vmin=self.vlim[0], vmax=self.vlim[1],
                             interpolation="nearest")
        cb = fig.colorbar(self.img, ax=ax, fraction=0.04, pad=0.02)
        cb.set_label("|w| [W]" if self.field == "speed" else "p [R W^2]")
        self.sc = ax.scatter([], [], c=[], s=max(4, 9 * (0.1 / dx) ** 2),
                             cmap="viridis_r", vmin=self.dlim[0],
                             vmax=self.dlim[1], lw=0)
        cb2 = fig.colorbar(self.sc, ax=ax, fraction=0.04, pad=0.02)
        cb2.set_label("marker density [R]")
        width, depth = (ni - 2) * dx, (nj - 2) * dy
        ax.plot([0, width, width], [depth, depth, 0], "k-", lw=1.2)
        ax.plot([0, 0], [0, depth], "b--", lw=1.2, label="inflow (IN)")
        flags = self.f["/mac/flags"][self.frames[0]].reshape(ni, nj)
        first = True
        for i in range(ni):
            x0 = (i - 1) * dx
            if flags[i, 0] == 3:
                ax.plot([x0, x0 + dx], [0, 0], "r-", lw=4,
                        label="sink (OUT cells)" if first else None)
                first = False
            elif 1 <= i <= ni - 2:
                ax.plot([x0, x0 + dx], [0, 0], "k-", lw=1.2)
        ax.set_xlim(ext[0], ext[1])
        ax.set_ylim(ext[2], ext[3])
        ax.set_aspect("equal")
        ax.set_xlabel("x [L]")
        ax.set_ylabel("y [L]")
        legend_below(ax, ncol=2)
        self.text = stamp(ax)

    def draw(self, n):
        k = self.frames[n]
        self.img.set_data(self.values(k).T)
        fl = self.f["/mac/particles/flag"][k] > 1
        x = self.f["/mac/particles/x"][k][fl]
        y = self.f["/mac/particles/y"][k][fl]
        self.sc.set_offsets(np.column_stack([x, y]))
        self.sc.set_array(self.f["/mac/particles/density"][k][fl])
        self.text.set_text("t = %.3f L/W   markers %d" % (self.t[k], fl.sum()))

    def title(self, f, fallback):
        return run_title(f, fallback)


SCENES = {"balls": Balls, "film": Film, "coupled": Film,
          "greenspan72": Particles, "greenspan73": Particles, "mac": Mac}


def scene_of(f, a):
    model = str(attr(f, "scene.model", ""))
    if model in SCENES:
        return model, SCENES[model](f, a)
    for path, cls in (("/mac/p", Mac), ("/particles/x", Particles),
                      ("/film/psi", Film), ("/balls/position", Balls)):
        if path in f:
            return model or path, cls(f, a)
    sys.exit("animate: %s holds nothing to animate (model '%s')"
             % (f.filename, model))


def writer_for(out, fps):
    """(writer, path): MP4 through ffmpeg, else a GIF through Pillow."""
    if not out.endswith(".gif") and shutil.which("ffmpeg"):
        return animation.FFMpegWriter(
            fps=fps, codec="libx264",
            extra_args=["-pix_fmt", "yuv420p", "-preset", "veryfast"]), out
    gif = out if out.endswith(".gif") else os.path.splitext(out)[0] + ".gif"
    if gif != out:
        print("animate: ffmpeg is not on PATH (Debian: apt-get install -y "
              "ffmpeg), so no MP4; writing a GIF through Pillow instead: %s"
              % gif, file=sys.stderr)
    try:
        import PIL  # noqa: F401
    except ImportError:
        sys.exit("animate: a GIF needs Pillow (Debian: apt-get install -y "
                 "python3-pil); an MP4 needs ffmpeg")
    return animation.PillowWriter(fps=fps), gif


def new_movie_file(path):
    """A new, empty file beside path, created by this process (O_EXCL: never
    through a link someone planted in a shared directory), which the
    writer fills and which is renamed to path once the movie is whole."""
    if os.path.isdir(path):
        sys.exit("animate: %s is a directory; name a movie file" % path)
    folder = os.path.dirname(path) or "."
    try:
        fd, tmp = tempfile.mkstemp(prefix="." + os.path.basename(path) + ".",
                                   suffix=os.path.splitext(path)[1],
                                   dir=folder)
    except OSError as e:
        sys.exit("animate: cannot create a file in %s for %s: %s"
                 % (folder, path, e.strerror))
    os.close(fd)
    umask = os.umask(0)
    os.umask(umask)
    os.chmod(tmp, 0o666 & ~umask)
    return tmp


def progress(n, total, quiet):
    if quiet:
        return
    w = 30
    done = int(w * n / total)
    sys.stderr.write("\ranimate: [%s%s] %d/%d frames"
                     % ("#" * done, " " * (w - done), n, total))
    if n == total:
        sys.stderr.write("\n")
    sys.stderr.flush()


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("h5")
    ap.add_argument("-o", "--output", default=None,
                    help="movie file (default: OUT.mp4 beside OUT.h5)")
    ap.add_argument("--fps", type=float, default=20)
    ap.add_argument("--frames", type=int, default=200,
                    help="at most this many frames (rows spread evenly)")
    ap.add_argument("--t0", type=float, default=None)
    ap.add_argument("--t1", type=float, default=None)
    ap.add_argument("--size", default=None,
                    help="frame size WxH in pixels (even numbers; "
                    "default 960x540)")
    ap.add_argument("--talk", action="store_true",
                    help="frames for a talk: 1920x1080 (unless --size) "
                    "with fonts to match")
    ap.add_argument("--field", choices=("speed", "p"), default="speed",
                    help="MAC: the field under the markers")
    ap.add_argument("--xlim", type=float, nargs=2, default=None,
                    help="film: the x range shown [cm]")
    ap.add_argument("-q", "--quiet", action="store_true",
                    help="no progress bar")
    a = ap.parse_args()
    if a.frames < 1 or a.fps <= 0:
        sys.exit("animate: --frames and --fps must be positive")
    size = a.size or ("1920x1080" if a.talk else "960x540")
    try:
        w, h = (int(v) for v in size.lower().split("x"))
    except ValueError:
        sys.exit("animate: --size wants WxH, e.g. 960x540")
    w, h = w + w % 2, h + h % 2  # H.264 with yuv420p wants even sizes
    out = a.output or os.path.splitext(a.h5)[0] + ".mp4"
    # the frame is the 960x540 layout drawn at the frame's height: text,
    # lines and markers scale with it (1920x1080, --talk: twice the size)
    dpi = 100.0 * h / 540
    matplotlib.rcParams.update(fonts())
    with h5py.File(a.h5, "r") as f:
        model, sc = scene_of(f, a)
        fig = plt.figure(figsize=(w / dpi, h / dpi), dpi=dpi,
                         layout="constrained")
        sc.setup(fig)
        fig.suptitle(fit_title(fig, sc.title(f, os.path.basename(a.h5))))
        writer, path = writer_for(out, a.fps)
        total = len(sc.frames)
        tmp = new_movie_file(path)
        try:
            with writer.saving(fig, tmp, dpi):
                for n in range(total):
                    sc.draw(n)
                    writer.grab_frame()
                    progress(n + 1, total, a.quiet)
            # a rename replaces a link planted at path instead of writing
            # through it
            os.replace(tmp, path)
        finally:
            if os.path.lexists(tmp):
                os.unlink(tmp)
        plt.close(fig)
    print("wrote %s (%d frames, %dx%d, %g fps)" % (path, total, w, h, a.fps))


if __name__ == "__main__":
    main()
