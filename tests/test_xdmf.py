#!/usr/bin/python3
"""test_xdmf.py: the XDMF sidecars open in ParaView, with either reader.

Short film, balls, coupled, Greenspan 1972 and 1973 and MAC runs write
OUT.xmf beside OUT.h5 (ballfilm run does it at the end of every run).
Both of ParaView's readers (pvpython, Debian's paraview package, through
xdmf_probe.py): OpenDataFile, what File > Open does (the Xdmf3 reader),
and the legacy XDMF Reader, must load every block at every time step the
HDF5 file implies (read here with h5py), with the number of points and
cells, the sums of the point coordinates and each array's minimum,
maximum and sum equal to those of the dataset row of that time (the
coupled run's film: the last profile at or before it).  Also: `ballfilm
xdmf -o` into another folder names the HDF5 file relatively, and
--max-steps thins the time steps.

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

from pychecks import MODEL_RUNS, Checks, run, run_scene

HERE = os.path.dirname(os.path.abspath(__file__))
RUNS = MODEL_RUNS
READERS = ("open", "legacy")

CK = Checks("xdmf")
check = CK.check


def probe(reader, xmf):
    r = run(["pvpython", os.path.join(HERE, "xdmf_probe.py"), reader, xmf])
    for line in r.stdout.splitlines():
        if line.startswith("XDMF-PROBE "):
            return json.loads(line[len("XDMF-PROBE "):])
    print(r.stdout[-2000:], r.stderr[-2000:])
    return None


def stats(a):
    a = np.asarray(a, dtype=float)
    return [float(a.min()), float(a.max()), float(a.sum())]


def points(x, y=None):
    return {"points": len(x), "x": float(np.sum(x)),
            "y": float(np.sum(y)) if y is not None else 0.0}


def expect(h5):
    """The times, and for each time {block: (points, cells, x sum, y sum,
    {array: [min, max, sum]})} from the HDF5 file."""
    with h5py.File(h5, "r") as f:
        g = lambda p: f[p][()]
        if "/balls/position" in f:
            times = g("/time")
        elif "/particles/step" in f:
            times = g("/particles/step") * f.attrs["scene.dt"]
        elif "/film/psi" in f:
            times = g("/film/time")
        else:
            times = g("/time")
        steps = []
        for k, t in enumerate(times):
            b = {}
            if "/film/psi" in f:
                ft = g("/film/time")
                j = int(np.searchsorted(ft, t + 1e-9 * abs(t), "right")) - 1
                j = max(j, 0)
                n = f["/film/x"].shape[0]
                b["film"] = dict(points(g("/film/x")), cells=n - 1, y=0.0,
                                 arrays={a: stats(f["/film/" + a][j])
                                         for a in ("psi", "h", "u_d", "u_c")})
            if "/balls/position" in f:
                x = f["/balls/position"][k]
                b["balls"] = dict(points(x), cells=len(x), arrays={
                    "velocity": stats(f["/balls/velocity"][k]),
                    "mass": stats(g("/balls/mass")),
                    "radius": stats(g("/balls/radius"))})
            if "/particles/x" in f:
                x, y = f["/particles/x"][k], f["/particles/y"][k]
                arr = {"vx": stats(f["/particles/vx"][k]),
                       "vy": stats(f["/particles/vy"][k]),
                       "mass": stats(g("/particles/mass"))}
                for name, p in (("fluid", "tag"), ("inertia", "inertia"),
                                ("fixed", "fixed"), ("gravity", "gravity")):
                    if "/particles/" + p in f:
                        arr[name] = stats(g("/particles/" + p))
                b["particles"] = dict(points(x, y), cells=len(x), arrays=arr)
            if "/mac/p" in f:
                ni, nj, dx, dy = (float(v) for v in f["/mac/grid"][:4])
                ni, nj = int(ni), int(nj)

                def mesh(n1, n2, ox, oy):
                    i, j = np.meshgrid(np.arange(n1), np.arange(n2),
                                       indexing="ij")
                    return points(((i + ox) * dx).ravel(),
                                  ((j + oy) * dy).ravel())
                b["mac_cells"] = dict(mesh(ni + 1, nj + 1, -1, -1),
                                      cells=ni * nj, arrays={
                                          a: stats(f["/mac/" + a][k])
                                          for a in ("p", "rho", "T",
                                                    "flags")})
                b["mac_u"] = dict(mesh(ni + 1, nj, -1, -0.5),
                                  cells=ni * (nj - 1),
                                  arrays={"u": stats(f["/mac/u"][k])})
                b["mac_v"] = dict(mesh(ni, nj + 1, -0.5, -1),
                                  cells=(ni - 1) * nj,
                                  arrays={"v": stats(f["/mac/v"][k])})
                mx, my = f["/mac/particles/x"][k], f["/mac/particles/y"][k]
                b["mac_markers"] = dict(points(mx, my), cells=len(mx), arrays={
                    "density": stats(f["/mac/particles/density"][k]),
                    "flag": stats(f["/mac/particles/flag"][k])})
            steps.append(b)
        return [float(t) for t in times], steps


def close(a, b):
    return np.allclose(a, b, rtol=1e-9, atol=1e-12)


def compare(name, xmf, h5):
    times, want = expect(h5)
    for reader in READERS:
        seen = probe(reader, xmf)
        tag = "%s (%s)" % (name, reader)
        check(seen is not None, "%s: pvpython reads %s" % (tag, xmf))
        if seen is None:
            continue
        check(close(seen["times"], times) if len(seen["times"]) ==
              len(times) else False, "%s: %d time steps, those of the file"
              % (tag, len(times)), "ParaView sees %d" % len(seen["times"]))
        bad = []
        for k, (got, exp) in enumerate(zip(seen["steps"], want)):
            for b, e in exp.items():
                g = got.get(b)
                if g is None:
                    bad.append("t=%g: no block %s" % (times[k], b))
                    continue
                if (g["points"], g["cells"]) != (e["points"], e["cells"]) \
                        or not close([g["x"], g["y"]], [e["x"], e["y"]]):
                    bad.append("t=%g %s: points %s" % (times[k], b, g))
                for a, v in e["arrays"].items():
                    if a not in g["arrays"] or not close(g["arrays"][a], v):
                        bad.append("t=%g %s.%s: %s, h5py %s" % (
                            times[k], b, a, g["arrays"].get(a), v))
        check(not bad and len(seen["steps"]) == len(want),
              "%s: every block with its arrays, the file's values, at every "
              "time step" % tag, "; ".join(bad[:5]))


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
