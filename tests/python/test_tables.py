"""converge() and sweep() return tables; against the program's own."""
import os
import signal
import subprocess
import threading

import numpy as np
import pytest

import ballfilm


def test_converge_finds_the_orders(root):
    t, ref = ballfilm.converge(os.path.join(root, "runs/harmonic.ini"),
                               ["verlet", "rk4"], dts=[0.02, 0.01, 0.005],
                               t_end=2)
    assert list(t["method"]) == ["verlet"] * 3 + ["rk4"] * 3
    assert set(t["status"]) == {"ok"}
    v, r = t[t["method"] == "verlet"], t[t["method"] == "rk4"]
    assert v["order_x"][1:] == pytest.approx([2, 2], abs=0.1)
    assert r["order_x"][1:] == pytest.approx([4, 4], abs=0.2)
    assert np.isnan(v["order_x"][0])
    # the reference is the oscillator's cos t at T = 2 (rtol 1e-12)
    assert ref["x_ref"][0] == pytest.approx(np.cos(2.0), abs=1e-9)


def test_sweep_is_the_program_s_sweep(program, root, tmp_path):
    scene = os.path.join(root, "runs/two_balls_A.ini")
    vary = {"ball.1.mass": "0.8:1.2:3"}
    sets = {"scene.t_end": 5.0, "lyapunov.enabled": True}
    t = ballfilm.sweep(scene, vary, tmp_path / "py", set=sets)
    assert list(t["ball.1.mass"]) == [0.8, 1.0, 1.2]
    assert set(t["status"]) == {"ok"} and list(t["index"]) == [0, 1, 2]
    p = subprocess.run([program, "sweep", scene, "--vary",
                        "ball.1.mass=0.8:1.2:3", "--set", "scene.t_end=5",
                        "--set", "lyapunov.enabled=yes", "-q", "-o",
                        str(tmp_path / "cli")], capture_output=True, text=True)
    assert p.returncode == 0, p.stderr
    s = ballfilm.load(tmp_path / "cli" / "summary.h5")
    assert np.array_equal(s["lyapunov"], t["lyapunov"])
    assert np.array_equal(s["energy_error"], t["energy_error"])
    # the finished cases are not run again: their files stay as they were
    case = tmp_path / "py" / "case_00001.h5"
    before = os.stat(case).st_mtime_ns
    again = ballfilm.sweep(scene, vary, tmp_path / "py", set=sets)
    assert os.stat(case).st_mtime_ns == before
    assert np.array_equal(again["lyapunov"], t["lyapunov"])


def test_ctrl_c_stops_a_sweep_and_a_rerun_completes_it(root, tmp_path,
                                                     sigint_raises):
    """SIGINT (from a timer, as a terminal would send it) during a sweep:
    ballfilm.Interrupted, the running case leaves no .done row; the rerun
    runs what is missing and gives the table of an uninterrupted sweep."""
    scene = os.path.join(root, "runs/two_balls_A.ini")
    vary = {"ball.1.mass": [0.8, 0.9, 1.0, 1.1, 1.2, 1.3]}
    sets = {"scene.t_end": 100.0, "lyapunov.enabled": True}
    whole = ballfilm.sweep(scene, vary, tmp_path / "whole", set=sets)
    timer = threading.Timer(0.5 * np.sum(whole["wall"]),
                            os.kill, (os.getpid(), signal.SIGINT))
    timer.start()
    with pytest.raises(ballfilm.Interrupted):
        ballfilm.sweep(scene, vary, tmp_path / "cut", set=sets)
    timer.join()
    done = sorted(p.name for p in (tmp_path / "cut").glob("case_*.done"))
    assert 0 < len(done) < 6, done
    again = ballfilm.sweep(scene, vary, tmp_path / "cut", set=sets)
    assert np.array_equal(again["lyapunov"], whole["lyapunov"])
    assert set(again["status"]) == {"ok"}
