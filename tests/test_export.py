#!/usr/bin/python3
"""test_export.py: `ballfilm export` writes H5MD and extxyz that other
programs read, with the values of the run's file.

Short balls, coupled, Greenspan 1972 and 1973 and MAC runs, each exported
as H5MD and as extended XYZ:
- H5MD (read with h5py): /h5md version 1 1, author, creator; position,
  velocity (Greenspan 1972: the half-step times and their description),
  species, mass, box, observables against the run's datasets, with their
  H5MD units;
- H5MD --mdanalysis of the Greenspan 1972 run, read by MDAnalysis's
  H5MDReader: atoms, frames, times, positions and velocities converted to
  its units (Angstrom, ps) agree with the file;
- extxyz read back with ASE (ase.io.read, format extxyz): frames, times,
  positions, velocities and species agree with the file;
- refusals: a missing input and a run without particles (status 2, naming
  what is supported), a symbolic link at the output and the input itself
  as output (refused, nothing written through), SIGTERM (status 6) and a
  write that fails half way (status 5): no file left behind.

usage: test_export.py BIN/ballfilm WORKDIR   (make test-export)
Ends with 'export: N passed, N failed'; exit 1 on a failure."""
import os
import resource
import shutil
import signal
import subprocess
import sys
import warnings

import h5py
import numpy as np

from pychecks import MODEL_RUNS, Checks, run, run_scene

RUNS = MODEL_RUNS

CK = Checks("export")
check = CK.check


def same(a, b, rtol=1e-12):
    a, b = np.asarray(a, dtype=float), np.asarray(b, dtype=float)
    return a.shape == b.shape and np.allclose(a, b, rtol=rtol, atol=0)


def text(v):
    return v.decode() if isinstance(v, bytes) else str(v)


def particles_of(f):
    """(group, dim, [x, y], [vx, vy], species [rows x n], mass, times,
    steps, half-step, units) of a run's file."""
    dt = float(f.attrs["scene.dt"])
    if "/balls/position" in f:
        x = f["/balls/position"][()]
        return ("balls", 1, [x], [f["/balls/velocity"][()]],
                np.ones(x.shape), f["/balls/mass"][()], f["/time"][()],
                f["/step"][()], False, ("cm", "cm s-1", "s"))
    if "/particles/x" in f:
        x = f["/particles/x"][()]
        if "/particles/tag" in f:
            sp = np.tile(f["/particles/tag"][()], (len(x), 1))
        else:
            sp = np.tile(1 + (f["/particles/fixed"][()] != 0), (len(x), 1))
        half = "/particles/step" in f
        steps = f["/particles/step"][()] if half else f["/step"][()]
        times = steps * dt if half else f["/time"][()]
        return ("greenspan", 2, [x, f["/particles/y"][()]],
                [f["/particles/vx"][()], f["/particles/vy"][()]], sp,
                f["/particles/mass"][()], times, steps, half,
                ("cm", "cm s-1", "s"))
    x = f["/mac/particles/x"][()]
    return ("markers", 2, [x, f["/mac/particles/y"][()]], [],
            f["/mac/particles/flag"][()], None, f["/time"][()],
            f["/step"][()], False, ("L", None, "L W-1"))


def check_h5md(name, h5, out):
    with h5py.File(h5, "r") as f, h5py.File(out, "r") as g:
        grp, dim, pos, vel, sp, mass, times, steps, half, units = \
            particles_of(f)
        dt = float(f.attrs["scene.dt"])
        h = g["h5md"]
        check(list(h.attrs["version"]) == [1, 1] and
              "name" in h["author"].attrs and
              text(h["creator"].attrs["name"]) == "ballfilm" and
              "version" in h["creator"].attrs,
              "%s: /h5md version 1 1, author, creator name and version"
              % name)
        p = g["particles"][grp]
        box = p["box"]
        check(int(box.attrs["dimension"]) == dim and
              [text(b) for b in box.attrs["boundary"]] == ["none"] * dim,
              "%s: box of dimension %d, boundary none" % (name, dim))
        want = np.stack(pos, axis=-1)
        check(same(p["position/value"][()], want) and
              same(p["position/time"][()], times) and
              list(p["position/step"][()]) == list(steps) and
              text(p["position/value"].attrs["unit"]) == units[0] and
              text(p["position/time"].attrs["unit"]) == units[2],
              "%s: position [%d x %d x %d] in %s with step and time (%s)"
              % ((name,) + want.shape + (units[0], units[2])))
        if vel:
            vt = np.where(steps > 0, times - 0.5 * dt, times) if half \
                else times
            v = p["velocity"]
            check(same(v["value"][()], np.stack(vel, axis=-1)) and
                  same(v["time"][()], vt) and
                  text(v["value"].attrs["unit"]) == units[1],
                  "%s: velocity in %s at %s" % (
                      name, units[1], "the half steps (k - 1/2) dt"
                      if half else "the times of the positions"))
            if half:
                check("half-step" in text(v.attrs.get("description", "")),
                      "%s: velocity described as half-step" % name)
        if mass is not None:
            check(same(p["mass"][()], mass) and
                  text(p["mass"].attrs["unit"]) == "g",
                  "%s: mass [%d] in g" % (name, len(mass)))
        got = p["species/value"][()] if isinstance(p["species"],
                                                   h5py.Group) \
            else np.tile(p["species"][()], (len(times), 1))
        check(same(got, sp), "%s: species" % name)
        if grp != "markers":
            obs = g.get("observables")
            keys = sorted(obs.keys()) if obs is not None else []
            ok = bool(keys)
            for k in keys:
                src = "/diag/kinetic" if "/diag/kinetic" in f else \
                    "/energy/" + k.split("_")[0]
                val = f[src][()]
                val = val[:, 0] if val.ndim == 2 else val
                ok &= same(obs[k]["value"][()], val) and \
                    same(obs[k]["time"][()], f["/time"][()]) and \
                    text(obs[k]["value"].attrs["unit"]) == "erg"
            check(ok, "%s: observables %s in erg" % (name, keys))


def check_mdanalysis(h5, out):
    warnings.simplefilter("ignore")
    from MDAnalysis.coordinates.H5MD import H5MDReader
    r = H5MDReader(out)
    with h5py.File(h5, "r") as f:
        x, y = f["/particles/x"][()], f["/particles/y"][()]
        vx, vy = f["/particles/vx"][()], f["/particles/vy"][()]
        t = f["/particles/step"][()] * float(f.attrs["scene.dt"])
    check(r.n_atoms == x.shape[1] and r.n_frames == x.shape[0],
          "MDAnalysis H5MDReader: %d atoms, %d frames" % x.shape[::-1],
          "%d atoms, %d frames" % (r.n_atoms, r.n_frames))
    bad = []
    for ts in r:
        k = ts.frame
        # MDAnalysis units: Angstrom (1e-8 cm), ps (1e-12 s), Angstrom/ps
        if not (same(ts.positions[:, 0], x[k] * 1e8, 1e-6) and
                same(ts.positions[:, 1], y[k] * 1e8, 1e-6) and
                not ts.positions[:, 2].any() and
                same(ts.velocities[:, 0], vx[k] * 1e-4, 1e-6) and
                same(ts.velocities[:, 1], vy[k] * 1e-4, 1e-6) and
                abs(ts.time - t[k] * 1e12) <= 1e-6 * max(1.0, t[k] * 1e12)):
            bad.append(k)
    check(not bad, "MDAnalysis: positions (Angstrom), velocities "
          "(Angstrom/ps) and times (ps) of every frame = the file's",
          "frames %s" % bad[:5])


def check_extxyz(name, h5, out):
    import ase.io
    frames = ase.io.read(out, index=":", format="extxyz")
    with h5py.File(h5, "r") as f:
        grp, dim, pos, vel, sp, mass, times, steps, half, units = \
            particles_of(f)
    n = len(times)
    check(len(frames) == n, "%s: ASE reads %d frames" % (name, n),
          "%d" % len(frames))
    bad = []
    for k, a in enumerate(frames[:n]):
        want = np.zeros((pos[0].shape[1], 3))
        for c, p in enumerate(pos):
            want[:, c] = p[k]
        ok = same(a.positions, want) and \
            list(a.numbers) == [int(s) for s in sp[k]] and \
            abs(float(a.info["Time"]) - times[k]) <= 1e-12 * abs(times[k])
        if vel:
            wv = np.zeros_like(want)
            for c, v in enumerate(vel):
                wv[:, c] = v[k]
            ok &= same(a.arrays["velo"], wv)
        if not ok:
            bad.append(k)
    check(not bad, "%s: positions, %sspecies (atomic numbers) and Time "
          "of every frame = the file's" % (name, "velocities, " if vel
                                           else ""), "frames %s" % bad[:5])


def refusals(prog, work):
    h5 = os.path.join(work, "greenspan72.h5")
    r = run([prog, "export", os.path.join(work, "none.h5"), "--format",
             "h5md", "-o", os.path.join(work, "none.h5md")])
    check(r.returncode == 2, "a missing input: status 2", r.stderr)
    r = run([prog, "export", os.path.join(work, "film.h5"), "--format",
             "extxyz", "-o", os.path.join(work, "film.xyz")])
    check(r.returncode == 2 and "greenspan72" in r.stderr and
          not os.path.exists(os.path.join(work, "film.xyz")),
          "a film run: status 2, naming what is supported", r.stderr)
    target = os.path.join(work, "target")
    link = os.path.join(work, "link.h5md")
    for p in (target, link):
        if os.path.lexists(p):
            os.remove(p)
    open(target, "w").write("mine\n")
    os.symlink(target, link)
    r = run([prog, "export", h5, "--format", "h5md", "-o", link])
    check(r.returncode == 5 and open(target).read() == "mine\n" and
          os.path.islink(link), "a symbolic link at the output: refused "
          "(status 5), its target untouched", r.stderr)
    os.makedirs(os.path.join(work, "sub"), exist_ok=True)
    other = os.path.join(work, "sub", "..", "greenspan72.h5")
    size = os.path.getsize(h5)
    r = run([prog, "export", h5, "--format", "h5md", "-o", other])
    check(r.returncode == 2 and os.path.getsize(h5) == size,
          "the input itself as output (another name): status 2", r.stderr)
    out = os.path.join(work, "stopped.xyz")

    def pending_term():
        # SIGTERM pending when the program starts: its handler sees it
        signal.pthread_sigmask(signal.SIG_BLOCK, {signal.SIGTERM})
        os.kill(os.getpid(), signal.SIGTERM)

    r = subprocess.run([prog, "export", h5, "--format", "extxyz", "-o", out],
                       capture_output=True, text=True,
                       preexec_fn=pending_term)
    check(r.returncode == 6 and not os.path.exists(out) and
          not os.path.exists(out + ".tmp"),
          "SIGTERM: status 6, no file", "%d %s" % (r.returncode, r.stderr))

    def small_files():
        signal.signal(signal.SIGXFSZ, signal.SIG_IGN)
        resource.setrlimit(resource.RLIMIT_FSIZE, (8192, 8192))

    for fmt in ("h5md", "extxyz"):
        out = os.path.join(work, "full." + fmt)
        r = subprocess.run([prog, "export", h5, "--format", fmt, "-o", out],
                           capture_output=True, text=True,
                           preexec_fn=small_files)
        check(r.returncode == 5 and not os.path.exists(out) and
              not os.path.exists(out + ".tmp"),
              "%s failing half way (file size limit): status 5, no file"
              % fmt, "%d %s" % (r.returncode, r.stderr))


def main(prog, work):
    os.makedirs(work, exist_ok=True)
    for name, (scene, sets) in RUNS.items():
        h5 = os.path.join(work, name + ".h5")
        r = run_scene(prog, scene, h5, sets)
        check(r.returncode == 0, "%s: ballfilm run" % name, r.stderr)
        if name == "film" or r.returncode:
            continue
        for fmt, ext in (("h5md", ".h5md"), ("extxyz", ".xyz")):
            out = os.path.join(work, name + ext)
            r = run([prog, "export", h5, "--format", fmt, "-o", out])
            check(r.returncode == 0 and os.path.exists(out),
                  "%s: export --format %s" % (name, fmt), r.stderr)
            if r.returncode:
                continue
            if fmt == "h5md":
                check_h5md(name, h5, out)
            else:
                check_extxyz(name, h5, out)
    h5 = os.path.join(work, "greenspan72.h5")
    out = os.path.join(work, "greenspan72_md.h5")
    r = run([prog, "export", h5, "--format", "h5md", "--mdanalysis", "-o",
             out])
    check(r.returncode == 0, "greenspan72: export --mdanalysis", r.stderr)
    if r.returncode == 0:
        check_mdanalysis(h5, out)
    refusals(prog, work)
    return CK.done()


if __name__ == "__main__":
    warnings.simplefilter("ignore", DeprecationWarning)
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    for mod, pkg in (("MDAnalysis", "python3-mdanalysis"),
                     ("ase", "python3-ase")):
        try:
            __import__(mod)
        except ImportError:
            print("SKIP  export: %s not found (Debian package %s; make "
                  "test-export installs it as root)" % (mod, pkg))
            print("export: 0 passed, 0 failed, 1 skipped")
            sys.exit(0)
    sys.exit(main(sys.argv[1], sys.argv[2]))
