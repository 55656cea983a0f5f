"""ballfilm.load and ballfilm.run against the program: the same datasets,
bit for bit; overrides, scene text and dicts, initial arrays."""
import ctypes
import math
import os
import subprocess

import h5py
import numpy as np
import pytest

import ballfilm

SHORT = {"scene.t_end": 2.0}


def cli(program, root, scene, out, *sets):
    args = [program, "run", os.path.join(root, scene), "-q", "-o", str(out)]
    for s in sets:
        args += ["--set", s]
    p = subprocess.run(args, capture_output=True, text=True, cwd=root)
    assert p.returncode == 0, p.stderr
    return out


def test_load_reads_what_the_file_holds(program, root, tmp_path):
    out = cli(program, root, "runs/two_balls_B.ini", tmp_path / "b.h5",
              "scene.t_end=2", "lyapunov.enabled=yes")
    r = ballfilm.load(out)
    with h5py.File(out, "r") as f:
        names = []
        f.visititems(lambda n, o: names.append(n)
                     if isinstance(o, h5py.Dataset) else None)
        assert sorted(names) == r.keys()
        for n in names:
            assert np.array_equal(r[n], f[n][()])
            assert r["/" + n] is r[n]  # read once
            assert r.units[n] == f[n].attrs["unit"]
        assert r.energy_error == f.attrs["max_relative_energy_error"]
        assert r.counters["force_evaluations"] == f.attrs["force_evaluations"]
    with open(os.path.join(root, "runs/two_balls_B.ini")) as f:
        assert r.scene_text == f.read()
    assert r.status == "ok" and r.params["scene.model"] == "balls"
    assert r.params["ball.1.mass"] == 0.8 and r.param_units["ball.1.mass"] == "g"
    assert r.params["scene.t_end"] == 2 and "scene.t_end" not in r.defaults
    assert r.time[-1] == pytest.approx(2.0) and r.steps == 20000
    with pytest.raises(KeyError, match="no dataset /balls/nope"):
        r["balls/nope"]


def test_run_is_the_program_s_run(program, root, tmp_path, h5same):
    """The same scene and overrides in this process and through the
    program: every dataset and attribute the same (h5same.py)."""
    a = cli(program, root, "runs/two_balls_B.ini", tmp_path / "cli.h5",
            "scene.t_end=2", "ball.1.mass=0.9", "lyapunov.enabled=yes")
    r = ballfilm.run(os.path.join(root, "runs/two_balls_B.ini"),
                     set={"ball.1.mass": 0.9, "lyapunov.enabled": True},
                     t_end=2, output=tmp_path / "py.h5")
    h5same(str(a), str(tmp_path / "py.h5"))
    assert r.path == str(tmp_path / "py.h5")
    assert r["balls/mass"][0] == 0.9 and r.params["ball.1.mass"] == 0.9


def test_the_film_and_a_particle_model_too(program, root, tmp_path, h5same):
    for scene, sets in (("runs/kink_steady.ini", {"scene.t_end": 1.0}),
                        ("runs/greenspan73_hex_v50.ini",
                         {"scene.t_end": 0.05})):
        a = cli(program, root, scene, tmp_path / "cli.h5",
                *[f"{k}={v!r}" for k, v in sets.items()])
        ballfilm.run(os.path.join(root, scene), set=sets,
                     output=tmp_path / "py.h5")
        h5same(str(a), str(tmp_path / "py.h5"))


def test_scene_text_and_dicts_are_the_file(root, tmp_path):
    path = os.path.join(root, "runs/bouncing_ball.ini")
    with open(path) as f:
        text = f.read()
    sections = {"scene": {"model": "balls", "integrator": "mv2m",
                          "effects": ["gravity", "floor"], "dt": 3e-4,
                          "t_end": 2.0, "output_every": 1, "energy_every": 1},
                "ball.1": {"position": 0.2, "mass": 1.0, "radius": 0.1}}
    a = ballfilm.run(path, t_end=2)
    b = ballfilm.run(text, t_end=2)
    c = ballfilm.run(sections)
    for r in (b, c):
        assert np.array_equal(a["balls/position"], r["balls/position"])
        assert np.array_equal(a["energy/total"], r["energy/total"])
    assert b.scene_text == text and c.scene_text == ballfilm.scene_text(sections)


def test_initial_arrays(root):
    """Initial fields from arrays: the film's own kink set as psi on a
    uniform film gives the kink run, bit for bit; positions set for balls
    are where the run starts."""
    film = {"scene": {"model": "film", "dt": 1e-3, "t_end": 0.1,
                      "output_every": 10},
            "film": {"length": 10, "dx": 0.1, "initial": "kink"}}
    kink = ballfilm.run(film)
    # eq. 3.17 with a = b = gamma = 1: psi = tanh(x / sqrt 2), with the C
    # library's tanh (the film's), so that the bits are the film's
    tanh = ctypes.CDLL("libm.so.6").tanh
    tanh.restype, tanh.argtypes = ctypes.c_double, [ctypes.c_double]
    psi = [tanh(x / math.sqrt(2.0)) for x in kink["film/x"]]
    film["film"]["initial"] = "uniform"
    mine = ballfilm.run(film, initial={"film/psi": psi})
    assert np.array_equal(kink["film/psi"], mine["film/psi"])
    assert np.array_equal(kink["film/u_d"], mine["film/u_d"])
    r = ballfilm.run(os.path.join(root, "runs/two_balls_B.ini"), t_end=0.01,
                     initial={"balls/position": [0.3, 0.7]})
    assert list(r["balls/position"][0]) == [0.3, 0.7]


def test_a_killed_run_reads_its_last_flush(program, root, tmp_path,
                                           killwrite):
    """A run killed at a write inside a flush (tests/killwrite.c, the K-th
    write after its file entered SWMR mode; a flush is 35-50 writes) is
    read as the program reads it: every series cut to the rows of the last
    complete flush (/flushed_rows), so /time, /step and /balls/position
    have one length and every row is a real one.  Plain h5py would see
    lengths of different flushes at some of these writes."""
    out = tmp_path / "k.h5"
    part = str(out) + ".part"
    for k in range(1, 48, 2):
        if os.path.exists(part):
            os.unlink(part)
        env = dict(os.environ, LD_PRELOAD=killwrite, BF_KILL_AT_WRITE=str(k))
        p = subprocess.run([program, "run",
                            os.path.join(root, "runs/two_balls_B.ini"), "-q",
                            "-o", str(out), "--set", "scene.t_end=1e5",
                            "--set", "scene.output_every=10", "--set",
                            "scene.flush_seconds=0.001"],
                           env=env, capture_output=True)
        assert p.returncode == -9, (k, p.returncode, p.stderr)
        r = ballfilm.load(part)
        assert "flushed_rows" not in r.keys()
        t, step, x = r["time"], r["step"], r["balls/position"]
        n = len(t)
        assert n > 0 and len(step) == n and x.shape == (n, 2), (k, n, len(step),
                                                                x.shape)
        assert r.shapes["balls/velocity"][0] == n
        assert np.array_equal(step, 10 * np.arange(n)), k
        assert np.array_equal(t, step * 1e-4), k
        assert np.all(x[:, 0] > 0) and np.all(x[:, 1] > x[:, 0]), k


def test_a_file_marked_open_for_writing_names_h5clear(program, root, tmp_path,
                                                      killwrite):
    """A run killed before its file entered SWMR mode (tests/killwrite.c
    counting from the first write: the 20th is inside set-up) leaves a file
    that HDF5 marks as open for writing; load says so and names the command
    that clears the mark."""
    out = tmp_path / "early.h5"
    env = dict(os.environ, LD_PRELOAD=killwrite, BF_KILL_AT_WRITE="20",
               BF_KILL_FROM_START="1")
    p = subprocess.run([program, "run",
                        os.path.join(root, "runs/two_balls_B.ini"), "-q",
                        "-o", str(out)], env=env, capture_output=True)
    assert p.returncode == -9, p.stderr
    with pytest.raises(OSError, match="h5clear -s"):
        ballfilm.load(str(out) + ".part")
