#!/usr/bin/python3
"""test_cli_docs.py: the bash completion of the program.

  /usr/bin/python3 tests/test_cli_docs.py PROGRAM COMPLETION

(make test-cli-docs).  The completion, sourced into bash, must complete a command, an option of a
command, the sections after --set and the keys of a section (--set
scene.<TAB>, --set=ball.2.<TAB>).  Exit status 1 with a line per problem.
"""
import os
import re
import subprocess
import sys

COMMANDS = ["run", "sweep", "converge", "xdmf", "animate", "info"]
problems = []


def check(ok, what):
    if not ok:
        problems.append(what)


def run(cmd, **kw):
    return subprocess.run(cmd, capture_output=True, text=True, **kw)


def help_options(prog, command):
    """The options a command's --help lists: every -x and --name of its
    usage lines and of its option lines (those that begin with '-'),
    before the scene keys."""
    text = run([prog, command, "--help"]).stdout
    text = text.split("Scene files are INI files")[0]
    found, usage = set(), False
    for line in text.splitlines():
        usage = line.startswith("usage:") or (usage and line[:1] == " ")
        if usage or line.lstrip().startswith("-"):
            found |= set(re.findall(r"(?<![\w-])(--?[A-Za-z][\w-]*)", line))
    return found


def complete(script, prog, words):
    """COMPREPLY of the completion for the words (the last is completed)."""
    code = ('source "$1"; shift; COMP_WORDS=("$@"); '
            'COMP_CWORD=$((${#COMP_WORDS[@]} - 1)); _ballfilm; '
            'printf "%s\\n" "${COMPREPLY[@]}"')
    r = run(["bash", "-c", code, "bash", script, prog] + words)
    check(r.returncode == 0, "completion %s: status %d: %s"
          % (words, r.returncode, r.stderr))
    return r.stdout.split()


def check_completion(prog, script):
    got = complete(script, prog, ["ru"])
    check(got == ["run"], "completion of 'ru': %s" % got)
    got = complete(script, prog, ["run", "x.ini", "--stop"])
    check(got == ["--stop-after"], "completion of 'run --stop': %s" % got)
    got = complete(script, prog, ["sweep", "x.ini", "--re"])
    check(got == ["--retry-failed"], "completion of 'sweep --re': %s" % got)
    for c in COMMANDS:
        got = set(complete(script, prog, [c, "-"]))
        missing = help_options(prog, c) - got
        check(not missing, "completion of '%s -': lacks %s"
              % (c, sorted(missing)))
    got = complete(script, prog, ["run", "x.ini", "--set", ""])
    check("scene." in got and "ball." in got and "film." in got,
          "completion of '--set ': %s" % got)
    got = complete(script, prog, ["run", "x.ini", "--set", "scene."])
    check("scene.dt=" in got and "scene.t_end=" in got
          and all(g.startswith("scene.") for g in got),
          "completion of '--set scene.': %s" % got)
    # --set=ball.2.m: bash splits the word at '='
    got = complete(script, prog, ["run", "x.ini", "--set", "=", "ball.2.m"])
    check(got == ["ball.2.mass="], "completion of '--set=ball.2.m': %s" % got)
    got = complete(script, prog, ["sweep", "x.ini", "--vary", "film.d"])
    check("film.dx=" in got, "completion of '--vary film.d': %s" % got)


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    prog, script = (os.path.abspath(a) for a in sys.argv[1:])
    check_completion(prog, script)
    for p in problems:
        print("test_cli_docs: " + p)
    if problems:
        sys.exit(1)
    print("test_cli_docs: completion ok")


if __name__ == "__main__":
    main()
