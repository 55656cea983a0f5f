"""pychecks.py: the pass/fail bookkeeping of the Python tests
(test_movies.py, test_xdmf.py): one line per check, a closing
'NAME: N passed, N failed' line, and helpers to run the program."""
import subprocess


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
