#!/usr/bin/python3
"""test_notebooks.py: every notebook of examples/notebooks/ executed as a
reader would run it, with Debian's python3-nbclient and python3-ipykernel
(kernel python3), the package being the repository's python/ballfilm with
its build/libballfilm.so.

A notebook passes when
  - it is committed without outputs: no code cell has outputs or an
    execution count (so git holds the code, not one run's results);
  - every cell runs without an error within the per-notebook timeout; each
    notebook ends with the numbers that say whether to trust it and asserts
    them, so a wrong number is an error here.
The notebooks must cover every model (balls, film, coupled, greenspan72,
greenspan73, mac), work-precision (ballfilm.converge) and a sweep
(ballfilm.sweep).  The executed copies are left in build/test-notebooks/.

usage: test_notebooks.py [NOTEBOOK.ipynb ...]   (make test-notebooks)
Ends with the line 'notebooks: N passed, N failed'; exit 1 on a failure."""
import glob
import os
import re
import subprocess
import sys
import time

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), ".."))
NB_DIR = os.path.join(ROOT, "examples", "notebooks")
OUT = os.path.join(ROOT, "build", "test-notebooks")
TIMEOUT = 120  # s, one notebook, kernel start included
JOBS = 2       # notebooks at once (each is one kernel, one core)
REQUIRED = {"balls": "balls", "film": "film", "coupled": "coupled",
            "greenspan72": "greenspan72", "greenspan73": "greenspan73",
            "mac": "mac", "work_precision": "ballfilm.converge",
            "sweep": "ballfilm.sweep"}


def stored_outputs(nb):
    """The code cells (numbered among all cells from 1) committed with outputs or counts."""
    return [k + 1 for k, c in enumerate(nb.cells)
            if c.cell_type == "code" and (c.get("outputs") or
                                          c.get("execution_count") is not None)]


def execute_one(path, out):
    """Child process: run one notebook, write the executed copy to out."""
    import nbformat
    from nbclient import NotebookClient
    from nbclient.exceptions import CellExecutionError
    nb = nbformat.read(path, as_version=4)
    work = os.path.splitext(out)[0] + ".run"
    os.makedirs(work, exist_ok=True)
    client = NotebookClient(nb, timeout=TIMEOUT, kernel_name="python3",
                            resources={"metadata": {"path": work}})
    try:
        client.execute()
    except CellExecutionError as e:
        nbformat.write(nb, out)
        print(str(e)[-2500:])
        return 1
    nbformat.write(nb, out)
    return 0


def run_one(path, env):
    """(name, ok, seconds, detail): one notebook in a child process."""
    name = os.path.basename(path)
    t0 = time.monotonic()
    try:
        r = subprocess.run([sys.executable, os.path.abspath(__file__),
                            "--one", path, os.path.join(OUT, name)],
                           env=env, capture_output=True, text=True,
                           timeout=TIMEOUT)
        ok, detail = r.returncode == 0, r.stdout[-3000:]
        if not ok and not detail.strip():
            detail = r.stderr[-3000:]
    except subprocess.TimeoutExpired:
        ok, detail = False, f"more than {TIMEOUT} s"
    return (name, ok, time.monotonic() - t0,
            re.sub(r"\x1b\[[0-9;]*m", "", detail))


def main(paths):
    import nbformat
    os.makedirs(OUT, exist_ok=True)
    env = dict(os.environ)
    env.pop("BALLFILM_LIB", None)
    env["PYDEVD_DISABLE_FILE_VALIDATION"] = "1"  # ipykernel's debugger note
    env["PYTHONPATH"] = os.path.join(ROOT, "python") + (
        os.pathsep + env["PYTHONPATH"] if env.get("PYTHONPATH") else "")
    passed = failed = 0
    if not paths:
        paths = sorted(glob.glob(os.path.join(NB_DIR, "*.ipynb")))
        names = {os.path.splitext(os.path.basename(p))[0] for p in paths}
        missing = sorted(set(REQUIRED) - names)
        if missing:
            failed += 1
            print("FAIL  missing notebooks: " + ", ".join(
                f"{m}.ipynb ({REQUIRED[m]})" for m in missing))
    todo = []
    for path in paths:
        name = os.path.basename(path)
        dirty = stored_outputs(nbformat.read(path, as_version=4))
        if dirty:
            failed += 1
            print(f"FAIL  {name}: committed with outputs or execution counts "
                  f"in cells {dirty} (clear them before committing)")
        else:
            todo.append(path)
    from concurrent.futures import ThreadPoolExecutor
    with ThreadPoolExecutor(JOBS) as pool:
        for name, ok, dt, detail in pool.map(lambda p: run_one(p, env), todo):
            if ok:
                passed += 1
                print(f"ok    {name} ({dt:.1f} s)")
            else:
                failed += 1
                print(f"FAIL  {name} ({dt:.1f} s): {detail}")
    print(f"notebooks: {passed} passed, {failed} failed")
    return 1 if failed else 0


if __name__ == "__main__":
    if len(sys.argv) == 4 and sys.argv[1] == "--one":
        sys.exit(execute_one(sys.argv[2], sys.argv[3]))
    sys.exit(main(sys.argv[1:]))
