"""_share.py: where the package finds its scenes (runs/*.ini), plot scripts
(plots/*.py) and version, however it was installed.

The share directory (the one holding runs/ and plots/), first found wins:
  1. ballfilm/share inside the package (pip install: package data);
  2. the repository, when this package is the repository's python/ballfilm
     (from the root, or pip install -e .);
  3. PREFIX/share/ballfilm of `make install` (_install.py).
The version: _version.py (written by pip's build and by make install),
else BF_VERSION of the repository's include/ballfilm/version.h.
"""
import os
import re

HERE = os.path.dirname(os.path.realpath(__file__))
REPO = os.path.normpath(os.path.join(HERE, "..", ".."))


def _candidates():
    yield os.path.join(HERE, "share")
    yield REPO
    try:
        from . import _install
        yield _install.SHARE
    except (ImportError, AttributeError):
        pass


def share_dir():
    """The directory that holds the shipped runs/ and plots/."""
    tried = []
    for d in _candidates():
        if (os.path.isdir(os.path.join(d, "runs")) and
                os.path.isdir(os.path.join(d, "plots"))):
            return d
        tried.append(d)
    raise FileNotFoundError("ballfilm: no runs/ and plots/ in " +
                            ", ".join(tried))


def _find(sub, name, ext):
    d = os.path.join(share_dir(), sub)
    base = name if name.endswith(ext) else name + ext
    path = os.path.join(d, base)
    if not os.path.isfile(path):
        have = sorted(f[:-len(ext)] for f in os.listdir(d) if f.endswith(ext))
        raise FileNotFoundError(f"ballfilm: no {sub[:-1]} {name!r} in {d} "
                                f"(there are: {', '.join(have)})")
    return path


def scene(name):
    """The path of a shipped scene: scene("bouncing_ball") is
    .../runs/bouncing_ball.ini."""
    return _find("runs", name, ".ini")


def scenes():
    """The names of the shipped scenes (runs/*.ini), sorted."""
    d = os.path.join(share_dir(), "runs")
    return sorted(f[:-4] for f in os.listdir(d) if f.endswith(".ini"))


def plot_script(name):
    """The path of a shipped plot script: plot_script("animate") is
    .../plots/animate.py (run it with a Python that has matplotlib)."""
    return _find("plots", name, ".py")


def version():
    try:
        from ._version import version as v
        return v
    except ImportError:
        pass
    with open(os.path.join(REPO, "include", "ballfilm", "version.h")) as f:
        m = re.search(r'^#define BF_VERSION "([^"]+)"', f.read(), re.M)
    return m.group(1) if m else "unknown"
