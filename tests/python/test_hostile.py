"""What the package hands to C is what the caller gave, or refused: no
string cut at a NUL byte, no integer wrapped; Ctrl-C during the closing
of a run ends in ballfilm.Interrupted; a temporary result names no file
that is gone; a sweep reruns the cases that failed to write."""
import os
import signal
import time

import pytest

import ballfilm
from ballfilm import runner

HARMONIC = "runs/harmonic.ini"


def scene(root, name=HARMONIC):
    return os.path.join(root, name)


def refused(fn, *words):
    """fn() raises BallfilmError with status "input" whose message holds
    every one of words; returns it."""
    with pytest.raises(ballfilm.BallfilmError) as e:
        fn()
    assert e.value.status == "input", e.value.message
    for w in words:
        assert w in e.value.message, e.value.message
    return e.value


def test_nul_bytes_refused_naming_what(root, tmp_path):
    """C reads a string up to its first NUL: '4\\0 junk' would run with
    stiffness 4.  Every string that crosses to C is checked."""
    e = refused(lambda: ballfilm.run(scene(root), t_end=0.01,
                                     set={"spring.stiffness": "4\0 junk"}),
                "spring.stiffness", "NUL")
    assert (e.section, e.key) == ("spring", "stiffness")
    refused(lambda: ballfilm.run(scene(root), t_end=0.01,
                                 set={"spring.stiff\0ness": 4.0}), "NUL")
    refused(lambda: ballfilm.run(scene(root) + "\0.txt", t_end=0.01),
            "scene", "NUL")
    refused(lambda: ballfilm.run(scene(root), t_end=0.01,
                                 output=str(tmp_path / "a.h5\0b")),
            "output", "NUL")
    with open(scene(root)) as f:
        text = f.read()
    refused(lambda: ballfilm.run(text + "\0", t_end=0.01), "NUL")
    # a dict's value may not start a new line of the scene either
    sections = {"scene": {"model": "balls", "integrator": "verlet",
                          "dt": 1e-3, "t_end": 0.01, "effects": "spring"},
                "ball.1": {"mass": "1\n[evil]", "position": 1.0}}
    refused(lambda: ballfilm.run(sections), "[ball.1] mass", "line break")
    refused(lambda: ballfilm.sweep(scene(root), {"spring.stiffness": [1, 2]},
                                   str(tmp_path / "sw\0x")), "dir", "NUL")
    refused(lambda: ballfilm.converge(scene(root), "rk4\0", dts=[1e-3],
                                      t_end=0.01), "method", "NUL")
    assert not os.listdir(tmp_path)


def test_out_of_range_integers_refused(root):
    """ctypes passes 2**70 as a C long of 0; -1 is no number of steps."""
    for every in (2 ** 70, -1, 2 ** 63):
        refused(lambda: ballfilm.run(scene(root), t_end=0.01, every=every,
                                     observer=lambda s: None), "every")
    for every in (1.5, "2", True):
        with pytest.raises(TypeError, match="every"):
            ballfilm.run(scene(root), t_end=0.01, every=every,
                         observer=lambda s: None)
    refused(lambda: ballfilm.converge(scene(root), "rk4", dts=[1e-3],
                                      t_end=0.01, repeats=2 ** 32 + 1),
            "repeats")
    refused(lambda: ballfilm.converge(scene(root), "rk4", dts=[1e-3],
                                      t_end=0.01, rows=-1), "rows")


def test_second_ctrl_c_while_closing_still_interrupted(root, tmp_path,
                                                       monkeypatch,
                                                       sigint_raises):
    """A Ctrl-C stops the run; a second one arrives while the stopped
    run's file is being read: the call still ends in ballfilm.Interrupted
    (a KeyboardInterrupt too), with the result, and Python's handler is
    back afterwards."""
    real = runner.Result

    def read_with_a_second_ctrl_c(*args, **kw):
        os.kill(os.getpid(), signal.SIGINT)
        return real(*args, **kw)

    monkeypatch.setattr(runner, "Result", read_with_a_second_ctrl_c)

    def ctrl_c(s):
        if s.step == 2000:
            os.kill(os.getpid(), signal.SIGINT)
            time.sleep(0.2)  # a run long enough to see it (it is fast)

    try:
        ballfilm.run(scene(root, "runs/two_balls_B.ini"), t_end=2,
                     output=tmp_path / "p.h5", every=1000, observer=ctrl_c)
        pytest.fail("the run was not interrupted")
    except ballfilm.Interrupted as e:
        got = e
    except KeyboardInterrupt:
        pytest.fail("a bare KeyboardInterrupt, not ballfilm.Interrupted")
    assert got.result is not None and got.result.status == "interrupted"
    assert signal.getsignal(signal.SIGINT) is signal.default_int_handler


def test_temporary_result_names_no_gone_file(root):
    r = ballfilm.run(scene(root), t_end=0.1)
    assert r.path is None
    assert r.attrs_of("time")["unit"] in ("s", b"s")
    with pytest.raises(KeyError) as e:
        r["nope"]
    assert "ballfilm-" not in str(e.value) and "read into memory" in str(e.value)
    assert "ballfilm-" not in repr(r)
    with pytest.raises(ballfilm.BallfilmError) as e:
        ballfilm.run(scene(root), set={"scene.dt": 5.0, "scene.t_end": 1000})
    assert e.value.status == "unstable"
    assert e.value.result.path is None
    assert e.value.result.attrs_of("time")


def test_sweep_reruns_cases_that_failed_to_write(root, tmp_path):
    """A case whose row says it failed to write (status 5, as on a full
    disk) is run again by the next call; one refused as bad input is not,
    unless retry_failed."""
    sc = scene(root)
    vary = {"spring.stiffness": [-1.0, 1.0, 2.0]}
    sets = {"scene.t_end": 0.1}
    first = ballfilm.sweep(sc, vary, tmp_path / "sw", set=sets)
    assert list(first["status"]) == ["bad input", "ok", "ok"]
    done = tmp_path / "sw" / "case_00001.done"
    fields = done.read_text().split(",")
    assert fields[2] == "0"
    fields[2] = "5"  # what a case that hit a full disk records
    done.write_text(",".join(fields))
    bad = tmp_path / "sw" / "case_00000.done"
    before = os.stat(bad).st_mtime_ns
    again = ballfilm.sweep(sc, vary, tmp_path / "sw", set=sets)
    assert list(again["status"]) == ["bad input", "ok", "ok"]
    assert os.stat(bad).st_mtime_ns == before
    assert again["steps"][1] == first["steps"][1]
    ballfilm.sweep(sc, vary, tmp_path / "sw", set=sets, retry_failed=True)
    assert os.stat(bad).st_mtime_ns != before


def test_ctrl_c_stops_converge(root, sigint_raises):
    """Ctrl-C during ballfilm.converge stops the study within a second and
    raises ballfilm.Interrupted (the study's stop flag), instead of
    running the whole study first."""
    import threading
    scene_path = os.path.join(root, "runs", "two_balls_B.ini")
    timer = threading.Timer(0.5, os.kill, (os.getpid(), signal.SIGINT))
    start = time.monotonic()
    timer.start()
    try:
        with pytest.raises(ballfilm.Interrupted):
            ballfilm.converge(scene_path, ["rk4", "verlet"],
                              dts=[1e-5, 5e-6, 2.5e-6], t_end=50)
    finally:
        timer.cancel()
    assert time.monotonic() - start < 2.5
