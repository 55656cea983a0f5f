#!/usr/bin/python3
"""killpoints.py: what a SIGKILL at each write of a flush leaves behind.

    /usr/bin/python3 tests/killpoints.py [--from-start] [--h5clear] PROGRAM FIRST LAST

Runs runs/two_balls_B.ini (t_end 1e5 s, a row every 10 steps, a flush
every millisecond) with build/tests/killwrite.so preloaded, once for each
K in FIRST..LAST, killed before its K-th write to the file: counted from
the write that puts the file into HDF5's SWMR mode, or with --from-start
from the first write (for a program before SWMR mode, e.g. one built at
3053c40).  Reads each killed OUT.h5.part with ballfilm.load (python/) and
prints how many were whole (/time, /step and /balls/position of one
length, every row a real one), torn (lengths that differ, or rows of
zeros), or did not open, with the K of each that was not whole.  With
--h5clear, a file that does not open is given to `h5clear -s` (which
clears HDF5's open-for-writing mark, in place) and read again.  Needs
`make build-tests` (the preloaded library) and Debian's python3-h5py (and
hdf5-tools for --h5clear).
"""
import os
import subprocess
import sys
import tempfile

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), ".."))
sys.path.insert(0, os.path.join(ROOT, "python"))
import numpy as np  # noqa: E402

import ballfilm  # noqa: E402


def state(part):
    try:
        r = ballfilm.load(part)
        t, step, x = r["time"], r["step"], r["balls/position"]
    except Exception as e:  # a file that does not open, or a dataset
        return "does not open", str(e).split("\n")[0][:80]
    n = len(t)
    if len(step) != n or len(x) != n:
        return "torn", f"{n}, {len(step)} and {len(x)} rows"
    if not (np.array_equal(step, 10 * np.arange(n))
            and np.array_equal(t, step * 1e-4)):
        return "torn", "rows that are not real ones"
    return "whole", f"{n} rows"


def main():
    args = sys.argv[1:]
    from_start = "--from-start" in args
    clear = "--h5clear" in args
    args = [a for a in args if a not in ("--from-start", "--h5clear")]
    if len(args) != 3:
        sys.exit(__doc__)
    program, first, last = os.path.abspath(args[0]), int(args[1]), int(args[2])
    shim = os.path.join(ROOT, "build", "tests", "killwrite.so")
    if not os.path.exists(shim):
        sys.exit(f"{shim}: run make build-tests first")
    counts, bad = {}, []
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "k.h5")
        for k in range(first, last + 1):
            for f in (out, out + ".part"):
                if os.path.exists(f):
                    os.unlink(f)
            env = dict(os.environ, LD_PRELOAD=shim, BF_KILL_AT_WRITE=str(k))
            if from_start:
                env["BF_KILL_FROM_START"] = "1"
            p = subprocess.run(
                [program, "run", os.path.join(ROOT, "runs/two_balls_B.ini"),
                 "-q", "-o", out, "--set", "scene.t_end=1e5", "--set",
                 "scene.output_every=10", "--set", "scene.flush_seconds=0.001"],
                env=env, capture_output=True)
            if p.returncode != -9:
                sys.exit(f"write {k}: the run was not killed "
                         f"(status {p.returncode})")
            what, detail = state(out + ".part")
            if what == "does not open" and clear:
                subprocess.run(["h5clear", "-s", out + ".part"],
                               capture_output=True)
                what, detail = state(out + ".part")
                what = what if what != "whole" else "whole after h5clear"
            counts[what] = counts.get(what, 0) + 1
            if what not in ("whole", "whole after h5clear"):
                bad.append(f"  write {k}: {what}: {detail}")
    print(f"{program}, killed at writes {first}..{last} "
          f"({'from the first write' if from_start else 'after SWMR mode began'}):")
    for what in ("whole", "whole after h5clear", "torn", "does not open"):
        print(f"  {what:20s} {counts.get(what, 0)}")
    print("\n".join(bad))


if __name__ == "__main__":
    main()
