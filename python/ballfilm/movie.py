"""movie.py: ballfilm.animate, a movie of a run from Python.

It runs the plot script the package ships (plots/animate.py, found like
the scenes: _share.plot_script), the same script `ballfilm animate`
runs, with $BALLFILM_PYTHON or else this interpreter (it needs
matplotlib, h5py and ffmpeg for MP4, else Pillow for a GIF), and returns
the path of the movie it wrote, which a notebook shows with
IPython.display.Video (MP4) or IPython.display.Image (GIF).
"""
import os
import re
import subprocess
import sys

from ._share import plot_script
from .errors import BallfilmError
from .result import Result

# keyword: (the script's option, how many values)
_OPTIONS = {"output": ("--output", 1), "fps": ("--fps", 1),
            "frames": ("--frames", 1), "t0": ("--t0", 1), "t1": ("--t1", 1),
            "size": ("--size", 1), "field": ("--field", 1),
            "xlim": ("--xlim", 2)}


def _input(path):
    if isinstance(path, Result):
        if path.path is None:
            raise BallfilmError(
                "animate: this Result was read into memory and its temporary "
                "file is gone; run it with output='run.h5' (ballfilm.run"
                "(..., output=...)) and animate that", 2)
        return path.path
    if not isinstance(path, (str, os.PathLike)):
        raise TypeError("animate needs a Result or the path of an output "
                        f"file, not {type(path).__name__}")
    p = os.fspath(path)
    if not os.path.exists(p):
        if os.path.exists(p + ".part"):
            return p + ".part"
        raise BallfilmError(f"animate: {p}: no such file", 2)
    return p


def _args(options):
    args = []
    for k, v in options.items():
        if k not in _OPTIONS:
            raise TypeError(f"animate() got an unexpected keyword argument "
                            f"{k!r} (it takes: {', '.join(_OPTIONS)})")
        if v is None:
            continue
        opt, n = _OPTIONS[k]
        if k == "size" and isinstance(v, (tuple, list)) and len(v) == 2:
            v = f"{v[0]}x{v[1]}"
        if k == "output":
            v = os.fspath(v)
        values = list(v) if n > 1 else [v]
        if len(values) != n:
            raise BallfilmError(f"animate: {k}={v!r}: needs {n} values", 2)
        args += [opt] + [str(x) for x in values]
    return args


def animate(result_or_path, quiet=True, **options):
    """A movie of a run, one frame per output row (thinned to `frames`):
    result_or_path is a Result with a file (ballfilm.run(...,
    output=...), ballfilm.load) or the path of an output file.  Options,
    as `ballfilm animate` takes them: output (the movie; default OUT.mp4
    beside OUT.h5), fps (20), frames (at most 200), t0, t1 (s), size
    ("960x540" or (960, 540)), field ("speed" or "p", mac), xlim ((a, b)
    in cm, film); quiet=False shows the script's progress.  Returns the
    movie's path (a GIF when ffmpeg is missing).  A failure raises
    BallfilmError with the script's message."""
    h5 = _input(result_or_path)
    args = _args(options)
    try:
        script = plot_script("animate")
    except FileNotFoundError as e:
        raise BallfilmError(f"animate: {e}", 5) from None
    python = os.environ.get("BALLFILM_PYTHON") or sys.executable
    cmd = [python, script, h5] + args + (["--quiet"] if quiet else [])
    p = subprocess.run(cmd, stdout=subprocess.PIPE,
                       stderr=subprocess.PIPE if quiet else None, text=True)
    if p.returncode:
        why = (p.stderr or "").strip().splitlines() if quiet else []
        raise BallfilmError(f"animate: {h5}: " + (why[-1] if why else
                            f"{script} ended with status {p.returncode}"), 5
                            if p.returncode != 2 else 2)
    m = re.search(r"^wrote (.+) \(\d+ frames", p.stdout, re.M)
    if not m or not os.path.exists(m.group(1)):
        raise BallfilmError(f"animate: {script} wrote no movie "
                            f"({p.stdout.strip()})", 5)
    return os.path.abspath(m.group(1))
