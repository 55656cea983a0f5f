#!/usr/bin/python3
"""test_units.py: every dataset's unit parses with UDUNITS-2, and
docs/output.md documents every dataset.

A short run of each model (balls with the return map, the Lyapunov
exponent and the integrator comparison; the film with a kink; the
coupled model with symmetrize; Greenspan 1972 and 1973; MAC) and, for
every dataset of its file: its "unit" and each entry of "column_units"
(series.h) parse with `udunits2 -H UNIT -W ''` (Debian's udunits-bin);
the dataset has "kind" and "role"; its path appears in docs/output.md in
a table row that also names its unit (or, for a dataset in a model's
scaled units, its "scaled_unit").  Every dataset path docs/output.md
names in a table row is written by one of the runs.

usage: test_units.py BIN/ballfilm WORKDIR   (make test-units)
Ends with 'units: N passed, N failed'; exit 1 on a failure."""
import os
import re
import shutil
import subprocess
import sys

import h5py

from pychecks import Checks, run_scene

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
RUNS = {
    "balls": ("runs/two_balls_B.ini",
              ["scene.t_end=2", "lyapunov.enabled=yes", "compare.a=verlet"]),
    "balls_damped": ("runs/bouncing_ball.ini",
                     ["scene.t_end=1", "scene.integrator=rk4",
                      "floor.restitution=0.8", "floor.amplitude=0.01",
                      "floor.frequency=5"]),
    "film": ("runs/kink_steady.ini", ["scene.t_end=0.2"]),
    "coupled": ("runs/coupled_fig8_sym.ini", ["scene.t_end=0.05"]),
    "coupled_auto": ("runs/coupled_fig8.ini",
                     ["scene.t_end=0.05", "coupled.film_every=auto"]),
    "greenspan72": ("runs/greenspan72_ex2.ini", ["scene.t_end=0.2"]),
    "greenspan73": ("runs/greenspan73_hex_v50.ini", ["scene.t_end=0.1"]),
    "mac": ("runs/stratres.ini", ["scene.t_end=0.2"]),
}
# not datasets of a run's file: the flush log lives only while it runs
NOT_DOCUMENTED = {"flushed_rows"}

CK = Checks("units")
check = CK.check
_parsed = {}


def parses(unit):
    if unit not in _parsed:
        r = subprocess.run(["udunits2", "-H", unit, "-W", ""],
                           capture_output=True, text=True)
        _parsed[unit] = r.returncode == 0 and "Don't recognize" not in (
            r.stdout + r.stderr)
    return _parsed[unit]


def text(v):
    return v.decode() if isinstance(v, bytes) else str(v)


def doc_rows():
    """{path: row text} of every table row of docs/output.md naming a
    dataset path in backticks"""
    rows = {}
    section = ""
    with open(os.path.join(ROOT, "docs", "output.md"), encoding="utf-8") as f:
        for line in f:
            if line.startswith("## "):
                section = line
            # the exported files' layout is another file's, not a run's
            if "Export" in section or not line.startswith("| `/"):
                continue
            cells = line.split("|")
            for p in re.findall(r"`(/[A-Za-z0-9_/]+)`", cells[1]):
                rows[p] = line
    return rows


def main(prog, work):
    if not shutil.which("udunits2"):
        print("units: udunits2 is missing (make deps-units installs "
              "udunits-bin)")
        return 1
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    docs = doc_rows()
    written = set()
    for model, (scene, sets) in RUNS.items():
        h5 = os.path.join(work, model + ".h5")
        r = run_scene(prog, os.path.join(ROOT, scene), h5, sets)
        if not check(r.returncode == 0, f"{model}: the run", r.stderr[-400:]):
            continue
        with h5py.File(h5, "r") as f:
            names = []
            f.visititems(lambda n, o: names.append(n)
                         if isinstance(o, h5py.Dataset) else None)
            for n in names:
                if n in NOT_DOCUMENTED:
                    continue
                a = f[n].attrs
                path = "/" + n
                written.add(path)
                unit = text(a.get("unit", ""))
                check(parses(unit) and unit != "",
                      f"{model}: {path}: unit '{unit}' parses")
                cu = text(a.get("column_units", ""))
                for u in (x.strip() for x in cu.split(";") if cu):
                    check(parses(u), f"{model}: {path}: column unit '{u}'")
                check("kind" in a and "role" in a,
                      f"{model}: {path}: kind and role")
                row = docs.get(path)
                if check(row is not None, f"{model}: {path} documented"):
                    shown = text(a.get("scaled_unit", "")) or unit
                    shown = cu or shown
                    check(all(u.strip() in row for u in shown.split(";")),
                          f"{model}: {path}: docs/output.md gives its unit "
                          f"'{shown}'", row.strip())
    for p in sorted(set(docs) - written):
        check(False, f"docs/output.md: {p} is written by a run")
    check_sweep_summary(prog, work)
    return CK.done()


def check_sweep_summary(prog, work):
    """A sweep's summary.h5: every unit parses, and /params keeps the unit
    of each swept key (g for a mass, cm for a position) in column_units,
    with unit "1" since the two differ."""
    out = os.path.join(work, "sweep")
    r = subprocess.run([prog, "sweep", os.path.join(ROOT, "runs",
                                                    "two_balls_B.ini"),
                        "--vary", "ball.1.mass=0.8:1.2:2",
                        "--vary", "ball.2.position=0.6:0.7:2",
                        "--set", "scene.t_end=0.2", "-o", out],
                       capture_output=True, text=True)
    if not check(r.returncode == 0, "sweep: the run", r.stderr[-400:]):
        return
    with h5py.File(os.path.join(out, "summary.h5"), "r") as f:
        for n, d in f.items():
            if isinstance(d, h5py.Dataset):
                unit = text(d.attrs.get("unit", ""))
                check(parses(unit) and unit != "",
                      f"sweep summary: /{n}: unit '{unit}' parses")
        a = f["params"].attrs
        check(text(a.get("column_units", "")) == "g; cm" and
              text(a.get("unit", "")) == "1",
              "sweep summary: /params keeps the swept keys' units",
              f"unit {a.get('unit')!r}, column_units "
              f"{a.get('column_units')!r}")


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    sys.exit(main(sys.argv[1], sys.argv[2]))
