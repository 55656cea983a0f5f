#!/usr/bin/python3
"""test_pip.py: the Python package installed with pip, offline, as a user
would, into fresh virtual environments (python3 -m venv
--system-site-packages: numpy and h5py come from Debian), then used from a
directory outside the repository with no BALLFILM_* variable and no
PYTHONPATH:

  - `pip install --no-build-isolation --no-index .` builds a wheel tagged
    for the platform (it holds libballfilm) and installs it;
  - `import ballfilm` loads the library inside the installed package,
    ballfilm.__version__ is BF_VERSION of include/ballfilm/version.h, the
    shipped scenes and plot scripts are in the installed package, and a
    shipped scene runs (its energy error is the one `ballfilm run` gives);
  - `pip install -e .` (development) imports the repository's
    python/ballfilm with the repository's build/libballfilm.so and runs the
    same scene.

usage: test_pip.py   (make test-pip; from the repository root)
Ends with the line 'pip: N passed, N failed'; exit 1 on a failure."""
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile

from pychecks import Checks, run

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), ".."))
CK = Checks("pip")
check = CK.check

PROBE = """
import json, ballfilm
r = ballfilm.run(ballfilm.scene("bouncing_ball"), t_end=1, output="b.h5")
print(json.dumps({"file": ballfilm.__file__, "version": ballfilm.__version__,
                  "lib": ballfilm.library_path(),
                  "scene": ballfilm.scene("bouncing_ball"),
                  "animate": ballfilm.plot_script("animate"),
                  "scenes": ballfilm.scenes(),
                  "energy_error": r.energy_error}))
"""


def clean_env():
    env = {k: v for k, v in os.environ.items()
           if not k.startswith("BALLFILM_") and k != "PYTHONPATH"}
    env["PIP_NO_CACHE_DIR"] = "1"
    return env


def venv(path):
    r = run([sys.executable, "-m", "venv", "--system-site-packages", path])
    return check(r.returncode == 0, "python3 -m venv --system-site-packages",
                 r.stderr)


def pip_install(py, *args):
    cmd = [py, "-m", "pip", "install", "--no-build-isolation", "--no-index",
           "--disable-pip-version-check", *args]
    r = subprocess.run(cmd, cwd=ROOT, capture_output=True, text=True,
                       env=clean_env())
    check(r.returncode == 0, "pip install " + " ".join(args),
          r.stdout[-3000:] + r.stderr[-3000:])
    return r.returncode == 0


def probe(py, where):
    r = subprocess.run([py, "-c", PROBE], cwd=where, capture_output=True,
                       text=True, env=clean_env())
    if not check(r.returncode == 0, "import ballfilm and run a shipped scene "
                 "from outside the repository", r.stdout + r.stderr):
        return None
    return json.loads(r.stdout.strip().splitlines()[-1])


def bf_version():
    with open(os.path.join(ROOT, "include", "ballfilm", "version.h")) as f:
        return re.search(r'^#define BF_VERSION "([^"]+)"', f.read(),
                         re.M).group(1)


def shipped_scenes():
    return sorted(f[:-4] for f in os.listdir(os.path.join(ROOT, "runs"))
                  if f.endswith(".ini"))


def under(path, d):
    return os.path.realpath(path).startswith(os.path.realpath(d) + os.sep)


def main():
    work = tempfile.mkdtemp(prefix="ballfilm-pip-")
    where = os.path.join(work, "elsewhere")
    os.mkdir(where)
    want = bf_version()
    try:
        v = os.path.join(work, "venv")
        if venv(v) and pip_install(os.path.join(v, "bin", "python"), "."):
            py = os.path.join(v, "bin", "python")
            site = subprocess.run([py, "-c", "import sysconfig; print("
                                   "sysconfig.get_paths()['platlib'])"],
                                  capture_output=True, text=True).stdout.strip()
            wheel = os.path.join(site, "ballfilm-%s.dist-info" % want, "WHEEL")
            text = open(wheel).read() if os.path.exists(wheel) else ""
            check("Root-Is-Purelib: false" in text and
                  "Tag: py3-none-linux_" in text,
                  "the wheel is tagged for the platform (it holds a library)",
                  text)
            p = probe(py, where)
            if p:
                pkg = os.path.join(site, "ballfilm")
                check(under(p["file"], pkg), "the installed package is "
                      "imported", p["file"])
                check(p["lib"] == os.path.join(pkg, "libballfilm.so." +
                                               ".".join(want.split(".")[:2])),
                      "the library inside the package is loaded", p["lib"])
                check(p["version"] == want, "__version__ is BF_VERSION " +
                      want, p["version"])
                check(under(p["scene"], pkg) and under(p["animate"], pkg),
                      "the scenes and plot scripts are the package's own",
                      p["scene"] + " " + p["animate"])
                check(p["scenes"] == shipped_scenes(),
                      f"every scene of runs/ ships ({len(p['scenes'])})",
                      str(p["scenes"]))
                check(abs(p["energy_error"] - 2.204034e-3) < 1e-8,
                      "bouncing_ball for 1 s: the energy error of `ballfilm "
                      "run` (2.204034e-03)", str(p["energy_error"]))
                check(os.path.exists(os.path.join(where, "b.h5")),
                      "the run wrote its file where it was asked to")
        e = os.path.join(work, "venv-e")
        if venv(e) and pip_install(os.path.join(e, "bin", "python"), "-e",
                                   "."):
            p = probe(os.path.join(e, "bin", "python"), where)
            if p:
                check(under(p["file"], os.path.join(ROOT, "python")),
                      "pip install -e: the repository's python/ballfilm is "
                      "imported", p["file"])
                check(p["lib"] == os.path.join(ROOT, "build",
                                               "libballfilm.so"),
                      "pip install -e: the repository's build/libballfilm.so "
                      "is loaded", p["lib"])
                check(p["scene"] == os.path.join(ROOT, "runs",
                                                 "bouncing_ball.ini") and
                      p["version"] == want,
                      "pip install -e: the repository's runs/ and version")
    finally:
        shutil.rmtree(work, ignore_errors=True)
    return CK.done()


if __name__ == "__main__":
    os.chdir(ROOT)
    sys.exit(main())
