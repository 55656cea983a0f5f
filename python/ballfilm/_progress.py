"""_progress.py: the progress line of ballfilm.run(..., progress=True).

A heartbeat of the run (sim.h, every STRIDE steps) records the simulated
time and the steps done; the calling thread, which waits for the run
(runner._in_thread), draws the line from them at most every PERIOD
seconds and once at the end: a bar, the simulated time of t_end, the
steps per second of wall time and the time left.  In a Jupyter kernel
the line is one display (IPython.display, updated in place; no
ipywidgets), elsewhere it is redrawn on stderr with a carriage return.
"""
import ctypes
import sys
import time

from . import _lib

STRIDE = 100     # steps between heartbeats: cheap beside even the fastest step
PERIOD = 0.2     # s of wall time between redraws
WIDTH = 24       # characters of the bar


def _notebook_display():
    """IPython.display.display when a Jupyter kernel runs this code,
    else None."""
    try:
        from IPython import get_ipython
        from IPython.display import display
    except ImportError:
        return None
    ip = get_ipython()
    if ip is None or getattr(ip, "kernel", None) is None:
        return None
    return display


def _clock(seconds):
    if seconds != seconds or seconds == float("inf"):
        return "--:--"
    s = int(round(seconds))
    h, s = divmod(s, 3600)
    m, s = divmod(s, 60)
    return f"{h}:{m:02d}:{s:02d}" if h else f"{m}:{s:02d}"


class _Text(str):
    """The line as a display object: plain text, and the same in HTML
    (monospaced) for the notebook."""

    def _repr_html_(self):
        import html
        return f"<pre style='margin:0'>{html.escape(self)}</pre>"


class Progress:
    """The progress of one run: .heartbeat() is what bf_sim_heartbeat
    calls (in the run's thread), .tick() redraws (the caller's thread),
    .finish() draws the last line."""

    def __init__(self, stream=None):
        self.t = self.t_end = 0.0
        self.steps = self.total = 0
        self.start = time.monotonic()
        self.last_draw = 0.0
        self.display = _notebook_display()
        self.stream = stream if stream is not None else sys.stderr
        self.handle = None
        self.drawn = False
        self.c = _lib.HEARTBEAT(self._beat)

    def attach(self, lib, sim, err):
        """Register the heartbeat with the sim; nonzero on failure."""
        return lib.bf_sim_heartbeat(sim, STRIDE, self.c, None,
                                    ctypes.byref(err))

    def _beat(self, ctx, sim, err):
        lib = _lib.lib()
        self.t = lib.bf_sim_time(sim)
        self.steps = lib.bf_sim_steps_done(sim)
        if not self.total:
            self.total = lib.bf_sim_steps_total(sim)
            self.t_end = self.total * lib.bf_sim_dt(sim)
        return 0

    def line(self):
        wall = time.monotonic() - self.start
        frac = 0.0
        if self.total:
            frac = self.steps / self.total
        if self.t_end > 0:
            frac = max(frac, self.t / self.t_end)
        frac = min(max(frac, 0.0), 1.0)
        fill = int(frac * WIDTH)
        bar = "#" * fill + "-" * (WIDTH - fill)
        rate = self.steps / wall if wall > 0 else 0.0
        left = wall * (1 - frac) / frac if frac > 0 else float("nan")
        return (f"{100 * frac:3.0f}% [{bar}] t {self.t:.4g} s of "
                f"{self.t_end:.4g} s, {self.steps} steps, {rate:,.0f} steps/s,"
                f" ETA {_clock(left)}")

    def _draw(self):
        text = self.line()
        if self.display is not None:
            if self.handle is None:
                self.handle = self.display(_Text(text), display_id=True)
            else:
                self.handle.update(_Text(text))
        else:
            self.stream.write("\r" + text)
            self.stream.flush()
        self.drawn = True

    def tick(self):
        now = time.monotonic()
        if self.total and now - self.last_draw >= PERIOD:
            self.last_draw = now
            self._draw()

    def finish(self, lib, sim):
        """The last line: where the run ended or stopped (read from the
        sim once its thread is done)."""
        if self.total:
            self.t = lib.bf_sim_time(sim)
            self.steps = lib.bf_sim_steps_done(sim)
        if self.total or self.drawn:
            self._draw()
        if self.display is None and self.drawn:
            self.stream.write("\n")
            self.stream.flush()
