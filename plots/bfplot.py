"""bfplot.py: small helpers shared by the plot scripts (reading ballfilm
HDF5 files through the ballfilm package, and labelling figures with the
run's provenance).

Plot scripts only draw; they never decide pass/fail.  Run them with
/usr/bin/python3 (Debian's numpy, matplotlib, h5py).  The package is the
one Python finds or, when it finds none, the repository's python/ballfilm
(for plots/ of the repository) or the one `make install` put in
PREFIX/lib/python3.X/dist-packages (for PREFIX/share/ballfilm/plots);
reading files needs only h5py, not the C library.

Every script that imports this module draws with style(): text sized for
the figure (tick labels of 11 pt, about 20 px at the 130 dpi of save()),
and no offset on any tick axis (a '1e-6+1' above an axis is never
shown; the full values are).  animate.py draws its frames with fonts()
at a dpi that follows the frame's height, so that text scales with the
frame (--talk, 1920x1080: twice the 960x540 sizes).
Symbols are mathtext: PSI, ALPHA, GAMMA."""
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
    try:
        import ballfilm
    except ImportError as _e:  # animate.py needs only fonts() and h5py

        class _Missing:
            """Stands for the package: any use ends with why it is not
            there (the drawing helpers work without it)."""

            def __getattr__(self, name, why=str(_e)):
                sys.exit("bfplot: the ballfilm package is not found (%s): "
                         "run from the repository or install it" % why)

        ballfilm = _Missing()

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

# the symbols of the models, as labels write them
PSI, ALPHA, GAMMA = r"$\psi$", r"$\alpha$", r"$\Gamma$"


def fonts(scale=1.0):
    """matplotlib rcParams for text sized for a figure: 12 pt body text
    times scale (scale 1: a 540-px movie frame at 100 dpi, or a figure
    saved at 130 dpi), titles a little larger, legends a little smaller,
    and no offset (or scientific factor) on the tick labels of any axis."""
    b = 12.0 * scale
    return {"font.size": b, "axes.labelsize": b, "axes.titlesize": 1.05 * b,
            "figure.titlesize": 1.15 * b, "xtick.labelsize": 0.92 * b,
            "ytick.labelsize": 0.92 * b, "legend.fontsize": 0.85 * b,
            "legend.title_fontsize": 0.85 * b,
            "axes.formatter.useoffset": False,
            "lines.linewidth": 1.5 * scale, "axes.linewidth": 0.8 * scale,
            "xtick.major.width": 0.8 * scale, "ytick.major.width": 0.8 * scale,
            "xtick.major.size": 3.5 * scale, "ytick.major.size": 3.5 * scale}


def style(scale=1.0):
    """Apply fonts(scale) to every figure drawn after it."""
    matplotlib.rcParams.update(fonts(scale))


def legend_beside(ax, **kw):
    """A legend outside the data, to the right of the axes."""
    return ax.legend(loc="upper left", bbox_to_anchor=(1.02, 1.0),
                     borderaxespad=0.0, **kw)


def legend_below(ax, ncol=3, **kw):
    """A legend outside the data, under the axes (and their x label)."""
    return ax.legend(loc="upper center", bbox_to_anchor=(0.5, -0.18),
                     borderaxespad=0.0, ncol=ncol, **kw)


style()


def load(path, *names):
    """Return the datasets `names` of file `path` as numpy arrays, and the
    root attributes as a dict (ballfilm.load)."""
    r = ballfilm.load(path)
    return [r[n] for n in names], r.attrs


def attr_str(attrs, key):
    v = attrs.get(key, "")
    return v.decode() if isinstance(v, bytes) else str(v)


def unlabelled(fig):
    """The axes of fig that show tick labels on an axis without a label
    (colour bars and axes turned off aside): 'title: x' strings."""
    out = []
    for ax in fig.axes:
        if not ax.axison or not ax.get_visible() or hasattr(ax, "_colorbar"):
            continue
        for name, axis in (("x", ax.xaxis), ("y", ax.yaxis)):
            shows = any(t.get_visible() and t.get_text()
                        for t in axis.get_ticklabels())
            if shows and not axis.get_label_text():
                out.append("'%s': %s" % (ax.get_title() or
                                         ax.get_title("left"), name))
    return out


def save(fig, out):
    fig.canvas.draw()
    for what in unlabelled(fig):
        print("bfplot: %s: axes %s without a label" % (out, what),
              file=sys.stderr)
    fig.tight_layout()
    fig.savefig(out, dpi=130)
    plt.close(fig)
    print("wrote", out)


def map_fill(z, v):
    """The share of a return map's bounding box that its points visit, as
    `ballfilm sweep`'s return_map_fill (src/compose/sweep.c,
    bf_sweep_map_fill): a B x B grid, B = floor(sqrt(points / 4)) clamped
    to 5..50; NaN below two points."""
    import math

    import numpy as np
    n = len(z)
    if n < 2:
        return math.nan
    B = min(max(int(math.floor(math.sqrt(n / 4.0))), 5), 50)
    z0, z1, v0, v1 = z.min(), z.max(), v.min(), v.max()
    dz = (z1 - z0) / B if z1 > z0 else 1.0
    dv = (v1 - v0) / B if v1 > v0 else 1.0
    i = np.clip(((z - z0) / dz).astype(int), 0, B - 1)
    j = np.clip(((v - v0) / dv).astype(int), 0, B - 1)
    return len(set(zip(i.tolist(), j.tolist()))) / float(B * B)
