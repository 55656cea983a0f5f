#!/usr/bin/python3
"""test_xdmf.py: the XDMF sidecars open in ParaView.

Short film, balls, Greenspan and MAC runs write OUT.xmf beside OUT.h5
(ballfilm run does it at the end of every run).  ParaView's XDMF Reader
(pvpython, Debian's paraview package, through xdmf_probe.py) must see,
for every block, the number of points, cells and time steps the HDF5
file implies (read here with h5py) and one array's range equal to that
of the dataset row.  Also: `ballfilm xdmf -o` into another folder names
the HDF5 file relatively, and --max-steps thins the time steps.

usage: test_xdmf.py BIN/ballfilm WORKDIR   (make test-xdmf)
Ends with 'xdmf: N passed, N failed'; exit 1 on a failure."""
import json
import os
import re
import resource
import shutil
import signal
import subprocess
import sys

import h5py
import numpy as np

from pychecks import Checks, run, run_scene

HERE = os.path.dirname(os.path.abspath(__file__))
RUNS = {
    "film": ("runs/kink_steady.ini", ["scene.t_end=1",
                                      "scene.output_every=0.1 s",
                                      "film.profile_every=0.1 s"]),
    "balls": ("runs/two_balls_B.ini", ["scene.t_end=1"]),
    "greenspan72": ("runs/greenspan72_ex2.ini", ["scene.t_end=1",
                                                 "scene.output_every=5"]),
    "mac": ("runs/stratres.ini", ["scene.t_end=1", "scene.output_every=2"]),
}

CK = Checks("xdmf")
check = CK.check


def probe(xmf):
    r = run(["pvpython", os.path.join(HERE, "xdmf_probe.py"), xmf])
    for line in r.stdout.splitlines():
        if line.startswith("XDMF-PROBE "):
            return json.loads(line[len("XDMF-PROBE "):])
    print(r.stdout[-2000:], r.stderr[-2000:])
    return None


def block(seen, name):
    """The block of that name (a file of one grid comes back unnamed)."""
    blocks = seen["blocks"]
    for k, v in blocks.items():
        if k.split("@")[0] == name:
            return v
    if len(blocks) == 1 and next(iter(blocks)).startswith("@"):
        return next(iter(blocks.values()))
    return None


def rng(a):
    return [float(np.min(a)), float(np.max(a))]


def expect(h5):
    """{block: (points, cells, array, range at the last row)}, times."""
    with h5py.File(h5, "r") as f:
        if "/film/psi" in f:
            n = f["/film/x"].shape[0]
            return {"film": (n, n - 1, "psi", rng(f["/film/psi"][-1]))}, \
                f["/film/time"].shape[0]
        if "/particles/x" in f:
            n = f["/particles/x"].shape[1]
            return {"particles": (n, n, "vx",
                                  rng(f["/particles/vx"][-1]))}, \
                f["/particles/step"].shape[0]
        if "/mac/p" in f:
            ni, nj = (int(v) for v in f["/mac/grid"][:2])
            slots = f["/mac/particles/x"].shape[1]
            return {"mac_cells": ((ni + 1) * (nj + 1), ni * nj, "p",
                                  rng(f["/mac/p"][-1])),
                    "mac_u": ((ni + 1) * nj, ni * (nj - 1), "u",
                              rng(f["/mac/u"][-1])),
                    "mac_v": (ni * (nj + 1), (ni - 1) * nj, "v",
                              rng(f["/mac/v"][-1])),
                    "mac_markers": (slots, slots, "density",
                                    rng(f["/mac/particles/density"][-1]))}, \
                f["/time"].shape[0]
        n = f["/balls/position"].shape[1]
        return {"balls": (n, n, "velocity",
                          rng(f["/balls/velocity"][-1]))}, f["/time"].shape[0]


def compare(name, xmf, h5):
    seen = probe(xmf)
    check(seen is not None, "%s: pvpython reads %s" % (name, xmf))
    if seen is None:
        return
    want, ntimes = expect(h5)
    check(len(seen["times"]) == ntimes, "%s: %d time steps" % (name, ntimes),
          "ParaView sees %d" % len(seen["times"]))
    for b, (pts, cells, arr, r) in want.items():
        got = block(seen, b)
        if got is None:
            check(False, "%s: block %s" % (name, b), "not in %s"
                  % sorted(seen["blocks"]))
            continue
        check(got["points"] == pts and got["cells"] == cells,
              "%s: %s has %d points, %d cells" % (name, b, pts, cells),
              "ParaView sees %d, %d" % (got["points"], got["cells"]))
        g = got["arrays"].get(arr)
        check(g is not None and np.allclose(g, r, rtol=1e-12, atol=0),
              "%s: %s range of %s at the last step = h5py's %s"
              % (name, b, arr, r), "ParaView: %s" % g)


def main(prog, work):
    if not shutil.which("pvpython"):
        print("SKIP  xdmf: pvpython not found (Debian package paraview; "
              "make test-xdmf installs it as root)")
        print("xdmf: 0 passed, 0 failed, 1 skipped")
        return 0
    os.makedirs(os.path.join(work, "sub"), exist_ok=True)
    for name, (scene, sets) in RUNS.items():
        h5 = os.path.join(work, name + ".h5")
        xmf = os.path.join(work, name + ".xmf")
        if os.path.exists(xmf):
            os.remove(xmf)
        r = run_scene(prog, scene, h5, sets)
        check(r.returncode == 0 and os.path.exists(xmf),
              "%s: ballfilm run writes %s" % (name, xmf), r.stderr)
        if os.path.exists(xmf):
            compare(name, xmf, h5)
    # on demand, into another folder: the HDF5 file named relatively
    h5 = os.path.join(work, "film.h5")
    moved = os.path.join(work, "sub", "film.xmf")
    r = run([prog, "xdmf", h5, "-o", moved])
    text = open(moved).read() if r.returncode == 0 else ""
    check(">../film.h5:/film/psi<" in text,
          "xdmf -o sub/: names ../film.h5", r.stderr)
    compare("film in sub/", moved, h5)
    # thinned
    h5 = os.path.join(work, "balls.h5")
    thin = os.path.join(work, "thin.xmf")
    r = run([prog, "xdmf", h5, "-o", thin, "--max-steps", "10"])
    times = re.findall(r'<Time Value="([^"]+)"', open(thin).read()) \
        if r.returncode == 0 else []
    with h5py.File(h5, "r") as f:
        t_last = float(f["/time"][-1])
    check(2 <= len(times) <= 10 and float(times[-1]) == t_last,
          "xdmf --max-steps 10: at most 10 steps, the last row kept",
          "%d steps, last %s" % (len(times), times[-1:] or None))
    # a longer sidecar written over by a shorter one (the file is written
    # in place and then cut to its new length): the same bytes as the
    # shorter one written afresh
    over = os.path.join(work, "over.xmf")
    r1 = run([prog, "xdmf", h5, "-o", over, "--all"])
    long_size = os.path.getsize(over) if r1.returncode == 0 else 0
    r2 = run([prog, "xdmf", h5, "-o", over, "--max-steps", "10"])
    same = r2.returncode == 0 and open(over, "rb").read() == \
        open(thin, "rb").read()
    check(long_size > os.path.getsize(thin) and same,
          "xdmf over a longer sidecar: the bytes of a fresh one",
          "%s %s %d bytes before" % (r1.stderr, r2.stderr, long_size))
    # not a regular file: nothing to cut, and not an error
    r = run([prog, "xdmf", h5, "-o", os.devnull])
    check(r.returncode == 0, "xdmf -o /dev/null", r.stderr)
    # a write that fails half way (file size limit of 4 KiB) over a whole
    # sidecar: exit 5 and an empty file, not the new start followed by the
    # old sidecar's tail (which would end in a well-formed </Xdmf>)

    def small_files():
        signal.signal(signal.SIGXFSZ, signal.SIG_IGN)
        resource.setrlimit(resource.RLIMIT_FSIZE, (4096, 4096))

    r = subprocess.run([prog, "xdmf", h5, "-o", over, "--all"],
                       capture_output=True, text=True,
                       preexec_fn=small_files)
    check(long_size > 4096 and r.returncode == 5 and
          os.path.getsize(over) == 0,
          "xdmf failing half way over a sidecar: exit 5, an empty file",
          "exit %d, %d bytes: %s" % (r.returncode, os.path.getsize(over),
                                     r.stderr))
    return CK.done()


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    sys.exit(main(sys.argv[1], sys.argv[2]))
