"""What a notebook user meets: progress, summaries and reprs of results,
animate(), units on the study tables, messages worded for Python."""
import os

import numpy as np
import pytest

import ballfilm

BALL = {"scene.t_end": 0.3}


def ball(root):
    return os.path.join(root, "runs", "bouncing_ball.ini")


def test_progress_bar_on_stderr(root, capfd):
    ballfilm.run(ball(root), set=BALL)
    assert capfd.readouterr().err == ""          # off by default
    r = ballfilm.run(ball(root), set=BALL, progress=True)
    err = capfd.readouterr().err
    last = err.rstrip("\n").split("\r")[-1]
    assert "100%" in last and "0.3 s" in last and "steps/s" in last
    assert "ETA" in err and err.endswith("\n")
    assert r.status == "ok"


def test_progress_in_a_notebook(root, monkeypatch, capfd):
    shown = []

    class Handle:
        def update(self, obj):
            shown.append(obj)

    def display(obj, display_id=False):
        shown.append(obj)
        return Handle()

    from ballfilm import _progress
    monkeypatch.setattr(_progress, "_notebook_display", lambda: display)
    ballfilm.run(ball(root), set=BALL, progress=True)
    assert capfd.readouterr().err == ""
    assert len(shown) >= 2 and "100%" in str(shown[-1])
    assert "steps/s" in str(shown[-1])


def test_repr_summary_and_html(root, tmp_path):
    out = tmp_path / "b.h5"
    r = ballfilm.run(ball(root), set=BALL, output=out)
    line = repr(r)
    assert "\n" not in line
    for s in ("balls", "status ok", f"{r.steps} steps", "t=0.3",
              "energy error"):
        assert s in line, line
    text = r.summary()
    assert "bouncing ball" in text and "mv2m" in text and "status" in text
    for name in r.keys():
        assert "/" + name in text
        assert " x ".join(str(n) for n in r.shapes[name]) in text or \
            not r.shapes[name]
    assert "[1]" in text and "cm" in text
    html = r._repr_html_()
    assert "<table" in html and "/balls/position" in html and "cm" in html
    assert "&lt;" not in r.summary()
    # a result in memory says so
    m = ballfilm.run(ball(root), set=BALL)
    assert "in memory" in repr(m) and "\n" not in repr(m)
    assert "/balls/position" in m.summary()


def test_animate_returns_the_movie(root, tmp_path):
    out = tmp_path / "b.h5"
    r = ballfilm.run(ball(root), set={"scene.t_end": 0.05,
                                      "scene.output_every": 20}, output=out)
    movie = ballfilm.animate(r, output=tmp_path / "m.mp4", frames=4, fps=4)
    assert os.path.exists(movie) and os.path.getsize(movie) > 0
    assert os.path.dirname(movie) == str(tmp_path)
    with pytest.raises(ballfilm.BallfilmError, match="output="):
        ballfilm.animate(ballfilm.run(ball(root), set=BALL))
    with pytest.raises(ballfilm.BallfilmError, match="no such file"):
        ballfilm.animate(tmp_path / "missing.h5")
    with pytest.raises(ballfilm.BallfilmError, match="frames"):
        ballfilm.animate(out, frames="x")


def test_units_on_converge_and_sweep(root, tmp_path):
    t, ref = ballfilm.converge(os.path.join(root, "runs/harmonic.ini"),
                               ["verlet"], dts=[0.02, 0.01], t_end=1)
    assert t.units["err_x"] == "cm" and t.units["wall"] == "s"
    assert t.units["dt"] == "s"
    v = t[t["method"] == "verlet"]               # today's indexing
    assert len(v) == 2 and v.units["err_x"] == "cm"
    assert isinstance(t["err_x"][0], float)
    assert type(t["wall"]) is np.ndarray         # a column: plain numpy
    assert isinstance(np.sum(t["wall"]), float)
    assert np.array(t).dtype == t.dtype
    s = ballfilm.sweep(os.path.join(root, "runs/two_balls_A.ini"),
                       {"ball.1.mass": [0.8, 1.0]}, tmp_path / "sw",
                       set={"scene.t_end": 0.2})
    assert s.units["ball.1.mass"] == "g" and s.units["wall"] == "s"
    assert list(s["ball.1.mass"]) == [0.8, 1.0]


@pytest.mark.parametrize("call, wanted, unwanted", [
    (lambda s: ballfilm.run(s, set={"ball.1.mass": -1}),
     "set={'ball.1.mass': -1}: ", "--set"),
    (lambda s: ballfilm.run(s, set={"ball.1.masss": 1}),
     "set={'ball.1.masss': 1}: ", "--set"),
    (lambda s: ballfilm.run(s, set={"ball.1.mass": "heavy"}),
     "set={'ball.1.mass': 'heavy'}: ", "--set"),
    (lambda s: ballfilm.run(s + ".missing"), "no such file", "cannot open"),
    (lambda s: ballfilm.converge(s, ["nosuch"], dts=[0.1]),
     "methods=['nosuch']", "--methods"),
    (lambda s: ballfilm.sweep(s, {"ball.1.mass": "1:2"}, "/nonexistent/x"),
     "vary={'ball.1.mass': '1:2'}", "--vary"),
    (lambda s: ballfilm.sweep(s, {"ball.9.mass": [1, 2]}, "/nonexistent/x"),
     "vary={'ball.9.mass': ", "--vary"),
    (lambda s: ballfilm.sweep(s, ["ball.1.mass=x,y"], "/nonexistent/x"),
     "'x' is not a number", "--vary"),
    (lambda s: ballfilm.converge(s, ["verlet"], dts=[0.1],
                                 set={"ball.1.mass": 0}),
     "set={'ball.1.mass': 0}: [ball.1] mass", "--set"),
    (lambda s: ballfilm.run(s, t_end=-1), "t_end=-1: [scene] t_end", "--set"),
])
def test_messages_for_python(root, call, wanted, unwanted):
    with pytest.raises(ballfilm.BallfilmError) as e:
        call(ball(root))
    assert wanted in str(e.value) and unwanted not in str(e.value)
