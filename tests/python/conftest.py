"""conftest.py: what the Python tests share.  They import the package of
the repository (python/ballfilm, with the library of build/ unless
$BALLFILM_LIB names another) and run the program $BALLFILM_BIN (default
bin/ballfilm) for the comparisons with the command line.  Run them with
`make test-python` (after `make`), or
`/usr/bin/python3 -m pytest tests/python` from the repository's root."""
import os
import signal
import subprocess
import sys

import pytest

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
sys.path.insert(0, os.path.join(ROOT, "python"))


@pytest.fixture
def root():
    return ROOT


@pytest.fixture
def program():
    return os.environ.get("BALLFILM_BIN", os.path.join(ROOT, "bin", "ballfilm"))


@pytest.fixture
def killwrite():
    """The library that kills the program at a chosen write of HDF5
    (tests/killwrite.c; $BALLFILM_KILLWRITE, made by make build-tests)."""
    shim = os.environ.get("BALLFILM_KILLWRITE",
                          os.path.join(ROOT, "build", "tests", "killwrite.so"))
    assert os.path.exists(shim), f"{shim}: made by make build-tests"
    return shim


@pytest.fixture
def h5same():
    """h5same(a, b): assert that two files hold the same datasets, bit for
    bit (tests/compare/h5same.py)."""
    def same(a, b):
        p = subprocess.run([sys.executable,
                            os.path.join(ROOT, "tests", "compare", "h5same.py"),
                            a, b], capture_output=True, text=True)
        assert p.returncode == 0, p.stdout + p.stderr
    return same


@pytest.fixture(scope="session")
def plugin(tmp_path_factory):
    """tests/python/plugin.c compiled into a shared object that links the
    library under test."""
    import ballfilm
    lib = ballfilm.library_path()
    out = tmp_path_factory.mktemp("plugin") / "libplugin.so"
    cmd = ["gcc", "-std=c11", "-O2", "-Wall", "-Wextra", "-Werror", "-shared",
           "-fPIC", "-I", os.path.join(ROOT, "include"),
           os.path.join(ROOT, "tests", "python", "plugin.c"), "-o", str(out),
           lib, "-lm"]
    p = subprocess.run(cmd, capture_output=True, text=True)
    assert p.returncode == 0, p.stderr
    return str(out)


@pytest.fixture
def sigint_raises():
    """SIGINT raises KeyboardInterrupt in this process during the test,
    as in an interactive Python, also when the tests were started with
    SIGINT ignored (under nohup, or as a script's background job), which
    Python keeps; the disposition before is put back afterwards."""
    before = signal.signal(signal.SIGINT, signal.default_int_handler)
    yield
    signal.signal(signal.SIGINT, before)
