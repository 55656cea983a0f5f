"""bfplot.py: small helpers shared by the plot scripts (reading ballfilm
HDF5 files through the ballfilm package, and labelling figures with the
run's provenance).

Plot scripts only draw; they never decide pass/fail.  Run them with
/usr/bin/python3 (Debian's numpy, matplotlib, h5py).  The package is the
installed one or, when none is, the repository's python/ballfilm (reading
files needs only h5py, not the C library)."""
import os
import sys

import matplotlib

try:
    import ballfilm
except ImportError:
    sys.path.insert(0, os.path.join(os.path.dirname(
        os.path.realpath(__file__)), "..", "python"))
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
