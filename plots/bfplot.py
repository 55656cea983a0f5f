"""bfplot.py: small helpers shared by the plot scripts (reading ballfilm
HDF5 files and labelling figures with the run's provenance).

Plot scripts only draw; they never decide pass/fail.  Run them with
/usr/bin/python3 (Debian's numpy, matplotlib, h5py)."""
import h5py
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def load(path, *names):
    """Return the datasets `names` of file `path` as numpy arrays, and the
    root attributes as a dict."""
    with h5py.File(path, "r") as f:
        data = [f[n][()] for n in names]
        attrs = {k: f.attrs[k] for k in f.attrs}
    return data, attrs


def attr_str(attrs, key):
    v = attrs.get(key, "")
    return v.decode() if isinstance(v, bytes) else str(v)


def save(fig, out):
    fig.tight_layout()
    fig.savefig(out, dpi=130)
    plt.close(fig)
    print("wrote", out)
