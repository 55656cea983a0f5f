"""Observers written in Python, Ctrl-C, restart."""
import os
import signal
import threading
import time

import numpy as np
import pytest

import ballfilm


def scene(root):
    return os.path.join(root, "runs/two_balls_B.ini")


def test_an_observer_sees_the_output_rows(root):
    seen = []

    def watch(s):
        seen.append((s.step, s.t, s["balls/position"], s.energy_error))

    r = ballfilm.run(scene(root), t_end=1, observer=watch)
    steps = r["step"]
    assert [s[0] for s in seen] == list(steps)
    assert np.array_equal(np.array([s[2] for s in seen]), r["balls/position"])
    assert [s[1] for s in seen] == list(r.time)
    assert seen[-1][3] == r.energy_error


def test_an_observer_every_n_steps_changes_no_bit(root):
    calls = []
    plain = ballfilm.run(scene(root), t_end=1)
    r = ballfilm.run(scene(root), t_end=1, every=37,
                     observer=lambda s: calls.append(s.step))
    assert calls == list(range(0, 10001, 37))
    assert np.array_equal(plain["balls/position"], r["balls/position"])


def test_an_observer_stops_a_run_or_fails_it(root, tmp_path):
    r = ballfilm.run(scene(root), t_end=1, every=100,
                     output=tmp_path / "stop.h5",
                     observer=lambda s: s.step < 3000)
    assert r.status == "interrupted" and r.steps == 3000
    assert os.path.exists(tmp_path / "stop.h5.ckpt")

    def bad(s):
        if s.step == 500:
            raise ValueError("enough")

    with pytest.raises(ValueError, match="enough"):
        ballfilm.run(scene(root), t_end=1, every=100, observer=bad)


def test_ctrl_c_stops_with_a_checkpoint_and_restart_continues(root, tmp_path,
                                                             h5same,
                                                             sigint_raises):
    """SIGINT in the middle of a run (sent by an observer, from the run's
    own thread, as a terminal would): ballfilm.Interrupted with the
    checkpoint; restart gives the uninterrupted run's datasets."""
    full = ballfilm.run(scene(root), t_end=2, output=tmp_path / "full.h5")

    def ctrl_c(s):
        if s.step == 5000:
            os.kill(os.getpid(), signal.SIGINT)
            time.sleep(0.2)  # a run long enough to see it (these are fast)

    part = tmp_path / "part.h5"
    with pytest.raises(ballfilm.Interrupted) as e:
        ballfilm.run(scene(root), t_end=2, output=part, every=1000,
                     observer=ctrl_c)
    assert isinstance(e.value, KeyboardInterrupt)
    assert e.value.checkpoint == str(part) + ".ckpt"
    assert os.path.exists(e.value.checkpoint)
    assert 5000 <= e.value.result.steps < 20000
    assert e.value.result.status == "interrupted"
    done = ballfilm.restart(part)
    assert done.status == "ok" and done.steps == 20000
    h5same(full.path, str(part))
    assert threading.active_count() == 1  # the run's thread is gone
