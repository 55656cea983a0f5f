"""ballfilm: balls and particle fluids in thin liquid films, from Python.

    import ballfilm
    r = ballfilm.run("runs/bouncing_ball.ini", set={"ball.1.mass": 0.9},
                     t_end=10)
    print(r.energy_error, r["balls/position"].shape)
    r = ballfilm.load("out/bouncing_ball.h5")

load() reads a ballfilm HDF5 file with h5py; run(), restart(), converge()
and sweep() call the C library libballfilm.so through ctypes, in this
process (see _lib.py for where the library is looked for: $BALLFILM_LIB,
the one inside the package, the repository's build/, the installed one,
the system's).  Only Debian's python3-numpy and python3-h5py are needed.
scene("bouncing_ball") is the path of a scene the package ships (runs/),
plot_script("animate") that of a plot script (plots/); animate(result)
makes a movie of a run with it and returns its path; __version__ is
BF_VERSION of include/ballfilm/version.h.  docs/library.md has the tour.
"""
from ._share import plot_script, scene, scenes, share_dir
from ._share import version as _version
from .errors import BallfilmError, Interrupted
from .movie import animate
from .result import Result, load
from .runner import Catalog, State, restart, run, scene_text
from .tables import converge, sweep

__version__ = _version()


def library_path():
    """The libballfilm.so this package uses (loading it if needed)."""
    from . import _lib
    return _lib.path()


def version():
    """The library's version string ("ballfilm 0.2.0 (git ...)")."""
    from . import _lib
    return _lib.lib().bf_version_string().decode()


__all__ = ["load", "run", "restart", "converge", "sweep", "Result", "State",
           "Catalog", "BallfilmError", "Interrupted", "scene_text",
           "library_path", "version", "scene", "scenes", "plot_script",
           "share_dir", "animate", "__version__"]
