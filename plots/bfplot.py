"""bfplot.py: small helpers shared by the plot scripts (reading ballfilm
HDF5 files through the ballfilm package, and labelling figures with the
run's provenance).

Plot scripts only draw; they never decide pass/fail.  Run them with
/usr/bin/python3 (Debian's numpy, matplotlib, h5py).  The package is the
one Python finds or, when it finds none, the repository's python/ballfilm
(for plots/ of the repository) or the one `make install` put in
PREFIX/lib/python3.X/dist-packages (for PREFIX/share/ballfilm/plots);
reading files needs only h5py, not the C library."""
import os
import sys

import matplotlib

try:
    import ballfilm
except ImportError:
    _here = os.path.dirname(os.path.realpath(__file__))
    sys.path[:0] = [os.path.join(_here, "..", "python"),
                    os.path.join(_here, "..", "..", "..", "lib",
                                 "python%d.%d" % sys.version_info[:2],
                                 "dist-packages")]
    import ballfilm

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def load(path, *names):
    """Return the datasets `names` of file `path` as numpy arrays, and the
    root attributes as a dict (ballfilm.load)."""
    r = ballfilm.load(path)
    return [r[n] for n in names], r.attrs


def attr_str(attrs, key):
    v = attrs.get(key, "")
    return v.decode() if isinstance(v, bytes) else str(v)


def save(fig, out):
    fig.tight_layout()
    fig.savefig(out, dpi=130)
    plt.close(fig)
    print("wrote", out)
