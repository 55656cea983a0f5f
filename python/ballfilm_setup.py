"""ballfilm_setup.py: the build steps that pyproject.toml names for pip
(setuptools), kept beside the package and not installed with it.

  - VERSION: BF_VERSION of include/ballfilm/version.h, the one place the
    version is written;
  - build_py: runs `make shared` in the repository (libballfilm.so), then
    puts into the package what it needs away from the repository: the
    library under its soname (ballfilm/libballfilm.so.0.2), the scenes and
    plot scripts (ballfilm/share/runs, ballfilm/share/plots) and
    _version.py.  For `pip install -e .` it only runs make: the package is
    then python/ballfilm itself, which finds build/, runs/ and plots/ in
    the repository;
  - bdist_wheel: the wheel holds a compiled library, so it is tagged for
    this platform (py3-none-linux_x86_64), not as pure Python.

Offline, with Debian's setuptools and wheel:
    /usr/bin/python3 -m pip install --no-build-isolation --no-index .
"""
import glob
import os
import re
import shutil
import subprocess

from setuptools.command.build_py import build_py as _build_py

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def _version():
    with open(os.path.join(ROOT, "include", "ballfilm", "version.h")) as f:
        m = re.search(r'^#define BF_VERSION "([^"]+)"', f.read(), re.M)
    if not m:
        raise RuntimeError("include/ballfilm/version.h: no BF_VERSION")
    return m.group(1)


VERSION = _version()

# pyproject.toml sends setuptools' work files (egg-info, build/lib) to
# build/setuptools; egg_info refuses a folder that does not exist, and it
# runs before build_py's make, so a fresh clone needs it made here (this
# module is read with the configuration, before any command runs).
os.makedirs(os.path.join(ROOT, "build", "setuptools"), exist_ok=True)


def _abi(version):
    """The soname's version: major, and minor too while major is 0."""
    major, minor = version.split(".")[:2]
    return major + "." + minor if major == "0" else major


class build_py(_build_py):
    def run(self):
        jobs = os.environ.get("BALLFILM_MAKE_JOBS", str(os.cpu_count() or 1))
        cmd = ["make", "--no-print-directory", "-C", ROOT, "-j" + jobs,
               "shared"]
        print(" ".join(cmd))
        if subprocess.call(cmd) != 0:
            raise SystemExit("ballfilm: `make shared` failed: libballfilm "
                             "needs gcc, make and Debian's libhdf5-dev, "
                             "libsundials-dev, libgsl-dev, libinih-dev "
                             "(`make deps` as root installs them)")
        super().run()
        if not getattr(self, "editable_mode", False):
            self._bundle(os.path.join(self.build_lib, "ballfilm"))

    def _bundle(self, pkg):
        for old in glob.glob(os.path.join(pkg, "libballfilm.so*")):
            os.remove(old)  # build_lib outlives a build: no stale library
        so = os.path.join(ROOT, "build", "libballfilm.so." + VERSION)
        self.copy_file(so, os.path.join(pkg, "libballfilm.so." +
                                        _abi(VERSION)))
        for sub, pattern in (("runs", "*.ini"), ("plots", "*.py")):
            dest = os.path.join(pkg, "share", sub)
            if os.path.isdir(dest):
                shutil.rmtree(dest)  # nothing left from an older build
            self.mkpath(dest)
            for f in sorted(glob.glob(os.path.join(ROOT, sub, pattern))):
                self.copy_file(f, os.path.join(dest, os.path.basename(f)))
        with open(os.path.join(pkg, "_version.py"), "w") as f:
            f.write('version = "%s"\n' % VERSION)


from wheel.bdist_wheel import bdist_wheel as _bdist_wheel  # noqa: E402


class bdist_wheel(_bdist_wheel):
    def finalize_options(self):
        super().finalize_options()
        self.root_is_pure = False

    def get_tag(self):
        return ("py3", "none", super().get_tag()[2])
