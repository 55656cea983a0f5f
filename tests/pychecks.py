"""pychecks.py: the pass/fail bookkeeping of the Python tests
(test_movies.py, test_xdmf.py, test_export.py): one line per check, a
closing 'NAME: N passed, N failed' line, helpers to run the program, and
one short run of each model for the tests that read every model's
output."""
import subprocess

# A short run of each model: a scene of runs/ and its --set overrides
# (a few output rows, the film's profiles included, seconds in all).
MODEL_RUNS = {
    "film": ("runs/kink_steady.ini", ["scene.t_end=1",
                                      "scene.output_every=0.1 s",
                                      "film.profile_every=0.1 s"]),
    "balls": ("runs/two_balls_B.ini", ["scene.t_end=0.5",
                                       "scene.output_every=200"]),
    "coupled": ("runs/coupled_fig8.ini", ["scene.t_end=0.03",
                                          "scene.output_every=100",
                                          "film.profile_every=0.004 s"]),
    "greenspan72": ("runs/greenspan72_ex2.ini", ["scene.t_end=1",
                                                 "scene.output_every=5"]),
    "greenspan73": ("runs/greenspan73_wall_friction.ini",
                    ["scene.output_every=10"]),
    "mac": ("runs/stratres.ini", ["scene.t_end=1", "scene.output_every=2"]),
}


class Checks:
    def __init__(self, name):
        self.name, self.passed, self.failed = name, 0, 0

    def check(self, ok, what, detail=""):
        if ok:
            self.passed += 1
            print("ok    %s" % what)
        else:
            self.failed += 1
            print("FAIL  %s%s" % (what, (": " + detail) if detail else ""))
        return ok

    def done(self):
        """Print the closing line; the exit status (1 on a failure)."""
        print("%s: %d passed, %d failed" % (self.name, self.passed,
                                            self.failed))
        return 1 if self.failed else 0


def run(cmd, env=None):
    return subprocess.run(cmd, capture_output=True, text=True, env=env)


def run_scene(prog, scene, h5, sets):
    """`ballfilm run SCENE -q -o H5 --set ...`"""
    cmd = [prog, "run", scene, "-q", "-o", h5]
    for s in sets:
        cmd += ["--set", s]
    return run(cmd)
