"""A user-defined effect from C; bad arguments raise exceptions with the
library's message, never crash."""
import math
import os

import pytest

import ballfilm

WELL = """[scene]
integrator = rk4
effects = quartic
dt = 0.01
t_end = 1
output_every = 10
[ball.1]
position = 1.5
mass = 2
[quartic]
strength = 8
centre = 0.5
"""


def test_a_user_defined_effect_from_c(plugin):
    """RK4 to the analytic quarter period of the quartic well finds the
    ball at the centre at full speed (see plugin.c): position error below
    1e-6 and falling by 2^4 when dt halves; the energy diagnostic, which
    sums the plugin's potential, at truncation level."""
    cat = ballfilm.Catalog()
    cat.add_effect(plugin, "quartic_well")
    m, q, A = 2.0, 8.0, 1.0
    T = 4 * math.sqrt(2 * m / q) / A * 1.3110287771460599
    errs = []
    for steps in (100, 200):
        r = ballfilm.run(WELL, catalog=cat,
                         set={"scene.t_end": T / 4, "scene.dt": T / 4 / steps})
        x, v = r["balls/position"][-1, 0], r["balls/velocity"][-1, 0]
        errs.append(abs(x - 0.5))
        assert v == pytest.approx(-A * A * math.sqrt(q / (2 * m)), abs=1e-6)
        assert r.energy_error < 1e-6
    assert errs[1] < 1e-6
    assert math.log2(errs[0] / errs[1]) == pytest.approx(4, abs=0.3)
    with pytest.raises(ballfilm.BallfilmError, match="quartic"):
        ballfilm.run(WELL)  # the built-in catalog does not know it
    with pytest.raises(ballfilm.BallfilmError, match="already"):
        cat.add_effect(plugin, "quartic_well")
    with pytest.raises(ballfilm.BallfilmError, match="no symbol 'nope'"):
        cat.add_effect(plugin, "nope")


BAD_SCENE = "[scene]\ndt = 1e-3\nt_end = 1\n[ball.1]\nposition = 1\nmass = -2\n"


@pytest.mark.parametrize("kwargs, message, where", [
    (dict(scene="runs/nope.ini"), "no such file", ("runs/nope.ini",
                                                            None)),
    (dict(scene=BAD_SCENE, name="bad.ini"), "must be > 0", ("bad.ini", 6)),
    (dict(scene="runs/bouncing_ball.ini", set={"ball.1.mas": 1}),
     "unknown key", ("--set", None)),
    (dict(scene="runs/bouncing_ball.ini", set={"scene.dt": "fast"}),
     "not a finite real number", ("--set", None)),
    (dict(scene="runs/bouncing_ball.ini", set={"scene.integrator": "euler"}),
     "unknown integrator 'euler'", ("--set", None)),
    (dict(scene="runs/bouncing_ball.ini", every=-1, observer=print),
     "every = -1", (None, None)),
    (dict(scene="runs/bouncing_ball.ini", initial={"balls/position": [1, 2]}),
     "balls/position has 1 values; 2 given", (None, None)),
    (dict(scene="runs/bouncing_ball.ini", initial={"balls/position": [0.05]}),
     "penetrates the floor", (None, None)),
    (dict(scene="runs/bouncing_ball.ini", initial={"film/h": [1.0]}),
     "no settable array 'film/h'", (None, None)),
    (dict(scene="runs/bouncing_ball.ini", set={"scene.dt": 1.0}),
     "unstable", (None, None)),
])
def test_bad_arguments_raise_the_library_s_message(root, kwargs, message,
                                                   where):
    os.chdir(root)
    with pytest.raises(ballfilm.BallfilmError) as e:
        ballfilm.run(**kwargs)
    text = f"{e.value.status}: {e.value}"
    assert message in text
    if where[0]:
        assert e.value.file == where[0], text
    if where[1]:
        assert e.value.line == where[1], text


def test_bad_python_arguments_raise_type_errors(root):
    path = os.path.join(root, "runs/bouncing_ball.ini")
    with pytest.raises(TypeError):
        ballfilm.run(path, set=["scene.dt=1"])
    with pytest.raises(TypeError):
        ballfilm.run(path, set={"scene.dt": object()})
    with pytest.raises(TypeError):
        ballfilm.run(path, observer=42)
    with pytest.raises(TypeError):
        ballfilm.run(12)


def test_where_the_library_comes_from():
    """$BALLFILM_LIB when set (make test-python sets it), else the
    repository's build/libballfilm.so."""
    path = ballfilm.library_path()
    want = os.environ.get("BALLFILM_LIB")
    assert path == want if want else path.endswith("build/libballfilm.so")
    assert os.path.basename(path).startswith("libballfilm.so")
    assert ballfilm.version().startswith("ballfilm 0.")
