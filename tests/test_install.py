#!/usr/bin/python3
"""test_install.py: `make install` into a fresh temporary prefix, used as a
user would, then `make uninstall`.

  - every file is there: the program, both libraries with the soname
    links, the public headers, ballfilm.pc, the man page, the package,
    the scenes and plot scripts (PREFIX/share/ballfilm/runs, plots) and
    the documentation (PREFIX/share/doc/ballfilm);
  - the shared library exports only bf_ symbols, exactly the functions
    and variables the installed headers declare (internals such as the
    ball system and the built-in descriptors are hidden);
  - examples/yoshida.c compiled with nothing but
    `pkg-config --cflags --libs ballfilm` (PKG_CONFIG_PATH into the
    prefix) links the shared library and runs (its exit status is its
    own check, the observed order 4); then the same with the shared
    library removed from a copy of the prefix and `--static`: the program
    needs no libballfilm.so and runs;
  - from a directory outside the repository and with no BALLFILM_ROOT,
    the installed program runs an installed scene, `ballfilm animate`
    makes a movie of it (the program finds PREFIX/share/ballfilm/plots
    beside itself), and an installed figure script (fig1_phase.py) draws
    the figure;
  - the installed Python package, from outside the repository, finds the
    installed library, its version and the installed scenes, and runs
    one;
  - `make uninstall` leaves no file behind.

usage: test_install.py   (make test-install; from the repository root)
Ends with the line 'install: N passed, N failed'; exit 1 on a failure."""
import os
import re
import shutil
import subprocess
import sys
import tempfile

from pychecks import Checks, run

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), ".."))
PY = "/usr/bin/python3"  # Debian's, with numpy, matplotlib and h5py
with open(os.path.join(ROOT, "include", "ballfilm", "version.h")) as _f:
    VERSION = re.search(r'^#define BF_VERSION "([^"]+)"', _f.read(),
                        re.M).group(1)
CK = Checks("install")
check = CK.check


def files_under(d):
    out = []
    for base, _, names in os.walk(d):
        out += [os.path.relpath(os.path.join(base, n), d) for n in names]
    return sorted(out)


def declared_names(prefix):
    """Every bf_ identifier of the installed headers, comments stripped."""
    names = set()
    inc = os.path.join(prefix, "include", "ballfilm")
    for h in sorted(os.listdir(inc)):
        r = run(["gcc", "-fpreprocessed", "-dD", "-E", "-P",
                 os.path.join(inc, h)])
        for tok in r.stdout.replace("(", " ").replace(")", " ").split():
            tok = tok.strip("*,;&[]{}")
            if tok.startswith("bf_"):
                names.add(tok)
    return names


def compile_example(prefix, out, static=False):
    env = dict(os.environ, PKG_CONFIG_PATH=os.path.join(prefix, "lib",
                                                        "pkgconfig"))
    r = run(["pkg-config", "--cflags", "--libs"] +
            (["--static"] if static else []) + ["ballfilm"], env=env)
    if not check(r.returncode == 0, "pkg-config finds ballfilm" +
                 (" (--static)" if static else ""), r.stderr):
        return None
    flags = r.stdout.split()
    cmd = ["gcc", "-std=c11", "-O2", "-Wall", "-Wextra", "-Werror",
           os.path.join(ROOT, "examples", "yoshida.c"), "-o", out] + flags + \
          ["-lm"]
    r = run(cmd)
    check(r.returncode == 0, "yoshida.c compiles with pkg-config alone" +
          (" (static)" if static else ""), " ".join(cmd) + "\n" + r.stderr)
    return cmd


def listed(sub, ext):
    return sorted(f for f in os.listdir(os.path.join(ROOT, sub))
                  if f.endswith(ext))


def from_prefix(prefix, work):
    """The installed program, scene, movie and figure, away from the
    repository and without BALLFILM_ROOT."""
    where = os.path.join(work, "elsewhere")
    os.makedirs(where, exist_ok=True)
    env = {k: v for k, v in os.environ.items()
           if not k.startswith("BALLFILM_") and k != "PYTHONPATH"}
    prog = os.path.join(prefix, "bin", "ballfilm")
    scene = os.path.join(prefix, "share", "ballfilm", "runs",
                         "bouncing_ball.ini")

    def go(cmd):
        return subprocess.run(cmd, cwd=where, env=env, capture_output=True,
                              text=True)
    for m in ("verlet", "mv2m"):
        r = go([prog, "run", scene, "-q", "-o", m + ".h5", "--set",
                "scene.t_end=0.5", "--set", "scene.integrator=" + m])
        check(r.returncode == 0, "the installed program runs the installed "
              "scene bouncing_ball.ini (%s)" % m, r.stdout + r.stderr)
    r = go([prog, "animate", "mv2m.h5", "-o", "movie.mp4", "--frames", "8",
            "-q"])
    movie = [f for f in ("movie.mp4", "movie.gif")
             if os.path.exists(os.path.join(where, f))]
    check(r.returncode == 0 and movie, "`ballfilm animate` from the prefix, "
          "without BALLFILM_ROOT, makes a movie", r.stdout + r.stderr)
    script = os.path.join(prefix, "share", "ballfilm", "plots",
                          "fig1_phase.py")
    r = go([PY, script, "verlet.h5", "mv2m.h5", "-o", "fig1.png"])
    check(r.returncode == 0 and os.path.exists(os.path.join(where,
                                                            "fig1.png")),
          "the installed fig1_phase.py draws Fig. 1 from the prefix",
          r.stdout + r.stderr)


def main():
    work = tempfile.mkdtemp(prefix="ballfilm-install-")
    prefix = os.path.join(work, "prefix")
    try:
        r = run(["make", "--no-print-directory", "install", "PREFIX=" + prefix])
        if not check(r.returncode == 0, "make install PREFIX=" + prefix,
                     r.stdout + r.stderr):
            return CK.done()
        have = files_under(prefix)
        py = [f for f in have if f.endswith("ballfilm/__init__.py")]
        for f in ["bin/ballfilm", "lib/libballfilm.a", "lib/libballfilm.so",
                  "lib/libballfilm.so.0.2", "lib/libballfilm.so.0.2.0",
                  "lib/pkgconfig/ballfilm.pc", "include/ballfilm/run.h",
                  "include/ballfilm/sim.h", "share/man/man1/ballfilm.1"]:
            check(f in have, "installed " + f)
        check(len(py) == 1, "installed the Python package", str(py))
        for sub, ext in (("runs", ".ini"), ("plots", ".py")):
            want = ["share/ballfilm/%s/%s" % (sub, f) for f in listed(sub, ext)]
            check(want and set(want) <= set(have), "installed every %s/*%s "
                  "(%d) in share/ballfilm/%s" % (sub, ext, len(want), sub),
                  str(sorted(set(want) - set(have))))
        docs = ["share/doc/ballfilm/README.md"] + \
            ["share/doc/ballfilm/docs/" + f for f in listed("docs", ".md")] + \
            ["share/doc/ballfilm/docs/models/" + f
             for f in listed(os.path.join("docs", "models"), ".md")]
        check(set(docs) <= set(have), "installed the documentation (%d "
              "pages) in share/doc/ballfilm" % len(docs),
              str(sorted(set(docs) - set(have))))
        from_prefix(prefix, work)
        n_headers = len([f for f in have if f.startswith("include/ballfilm/")])
        check(n_headers == len(os.listdir(os.path.join(ROOT, "include",
                                                       "ballfilm"))),
              f"all {n_headers} public headers installed")
        so = os.path.join(prefix, "lib", "libballfilm.so")
        r = run(["readelf", "-d", so])
        check("Library soname: [libballfilm.so.0.2]" in r.stdout,
              "soname libballfilm.so.0.2")
        r = run(["nm", "-D", "--defined-only", so])
        exported = {ln.split()[-1] for ln in r.stdout.splitlines()
                    if len(ln.split()) == 3}
        api = declared_names(prefix)
        check(exported and all(s.startswith("bf_") for s in exported),
              f"the .so exports only bf_ symbols ({len(exported)})",
              str(sorted(s for s in exported if not s.startswith("bf_"))))
        check(exported <= api, "every export is declared in a public header",
              str(sorted(exported - api)))
        for internal in ("bf_ballsys_create", "bf_filmsys_create",
                         "bf_h5_lock", "bf_model_balls", "bf_integrator_verlet",
                         "bf_sim_beat"):
            check(internal not in exported, "hidden: " + internal)
        for public in ("bf_run_from_text", "bf_sim_heartbeat", "bf_sim_set",
                       "bf_catalog_add_effect", "bf_sizeof", "bf_h5_list"):
            check(public in exported, "exported: " + public)
        exe = os.path.join(work, "yoshida")
        if compile_example(prefix, exe):
            r = run(["readelf", "-d", exe])
            check("libballfilm.so.0.2" in r.stdout,
                  "the example needs libballfilm.so.0.2")
            r = run([exe], env=dict(os.environ, LD_LIBRARY_PATH=os.path.join(
                prefix, "lib")))
            check(r.returncode == 0 and "observed order 4.0" in r.stdout,
                  "the example runs against the installed library",
                  r.stdout + r.stderr)
        static = os.path.join(work, "static")
        shutil.copytree(prefix, static, symlinks=True)
        for f in os.listdir(os.path.join(static, "lib")):
            if f.startswith("libballfilm.so"):
                os.remove(os.path.join(static, "lib", f))
        pc = os.path.join(static, "lib", "pkgconfig", "ballfilm.pc")
        with open(pc) as f:
            text = f.read().replace(prefix, static)
        with open(pc, "w") as f:
            f.write(text)
        exe = os.path.join(work, "yoshida_static")
        if compile_example(static, exe, static=True):
            r = run(["readelf", "-d", exe])
            check("libballfilm" not in r.stdout,
                  "linked statically: no libballfilm.so needed")
            r = run([exe])
            check(r.returncode == 0, "the static example runs",
                  r.stdout + r.stderr)
        if py:
            env = dict(os.environ, PYTHONPATH=os.path.join(
                prefix, os.path.dirname(os.path.dirname(py[0]))))
            env.pop("BALLFILM_LIB", None)
            code = ("import ballfilm; "
                    "s = ballfilm.scene('bouncing_ball'); "
                    "r = ballfilm.run(s, t_end=1); "
                    "print(ballfilm.library_path()); print(s); "
                    "print(ballfilm.__version__); print(r.energy_error)")
            r = subprocess.run([sys.executable, "-c", code], cwd=work,
                               capture_output=True, text=True, env=env)
            lines = r.stdout.split()
            check(r.returncode == 0 and lines and
                  lines[0] == os.path.join(prefix, "lib",
                                           "libballfilm.so.0.2"),
                  "the installed package uses the installed library",
                  r.stdout + r.stderr)
            check(len(lines) > 2 and lines[1] == os.path.join(
                prefix, "share", "ballfilm", "runs", "bouncing_ball.ini"),
                "the installed package finds the installed scenes",
                r.stdout + r.stderr)
            check(len(lines) > 2 and lines[2] == VERSION,
                  "the installed package's __version__ is " + VERSION,
                  r.stdout + r.stderr)
        r = run(["make", "--no-print-directory", "uninstall",
                 "PREFIX=" + prefix])
        left = files_under(prefix)
        check(r.returncode == 0 and not left, "make uninstall removes "
              "every file", r.stderr + " ".join(left))
    finally:
        shutil.rmtree(work, ignore_errors=True)
    return CK.done()


if __name__ == "__main__":
    os.chdir(ROOT)
    sys.exit(main())
