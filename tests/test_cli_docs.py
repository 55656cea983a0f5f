#!/usr/bin/python3
"""test_cli_docs.py: the man page and the bash completion of the program.

  /usr/bin/python3 tests/test_cli_docs.py PROGRAM MANPAGE COMPLETION

(make test-cli-docs).  The man page as man-db shows it
(`MANWIDTH=80 man -l MANPAGE | col -b`) must hold every section heading,
every option that `PROGRAM CMD --help` lists for every command (and the
program's own -h/-V), and every scene key of the program's table.  The
completion, sourced into bash, must complete a command, an option of a
command, the sections after --set and the keys of a section (--set
scene.<TAB>, --set=ball.2.<TAB>).  Exit status 1 with a line per problem.
"""
import os
import re
import subprocess
import sys

COMMANDS = ["run", "sweep", "converge", "xdmf", "animate", "info", "export"]
SECTIONS = ["NAME", "SYNOPSIS", "DESCRIPTION", "OPTIONS", "SCENE KEYS",
            "EXIT STATUS", "ENVIRONMENT", "FILES", "EXAMPLES"]
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


def man_text(page):
    env = dict(os.environ, MANWIDTH="80", LC_ALL="C.UTF-8")
    shown = run(["man", "-l", page], env=env)
    check(shown.returncode == 0, "man -l %s: status %d: %s"
          % (page, shown.returncode, shown.stderr[-500:]))
    plain = run(["col", "-b"], input=shown.stdout).stdout
    # groff's hyphen and minus, as the terminal shows them
    return plain.replace("\u2010", "-").replace("\u2212", "-")


def check_man(prog, page):
    text = man_text(page)
    heads = set(re.findall(r"^([A-Z][A-Z ]+)$", text, re.M))
    for s in SECTIONS:
        check(s in heads, "man page: no section %s" % s)
    words = set(re.findall(r"(?<![\w-])(--?[A-Za-z][\w-]*)", text))
    for c in COMMANDS:
        check(("   " + c) in text, "man page: no OPTIONS of %s" % c)
        for opt in sorted(help_options(prog, c)):
            check(opt in words, "man page: %s %s (in its --help) is missing"
                  % (c, opt))
    for opt in ["-h", "--help", "-V", "--version", "--restart",
                "--stop-after", "--keep-checkpoint"]:
        check(opt in words, "man page: %s is missing" % opt)
    keys = run([prog, "--complete-keys"]).stdout.split()
    check(len(keys) > 100, "--complete-keys: %d keys" % len(keys))
    sections = {k.rsplit(".", 1)[0] for k in keys}
    for s in sections:
        check("[%s]" % s in text, "man page: no scene section [%s]" % s)
    for k in keys:
        key = k.rsplit(".", 1)[1]
        check(re.search(r"^\s+%s\b" % re.escape(key), text, re.M),
              "man page: no scene key %s" % k)


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
    if len(sys.argv) != 4:
        sys.exit(__doc__)
    prog, page, script = (os.path.abspath(a) for a in sys.argv[1:])
    check_man(prog, page)
    check_completion(prog, script)
    for p in problems:
        print("test_cli_docs: " + p)
    if problems:
        sys.exit(1)
    print("test_cli_docs: man page and completion ok")


if __name__ == "__main__":
    main()
