#!/usr/bin/python3
"""Check that the documentation stands on its own.

  /usr/bin/python3 tests/check_docs.py        (from anywhere inside the repository)

1. Every relative Markdown link and image in README.md and docs/**/*.md,
   [text](target) and ![alt](target) and reference definitions
   "[label]: target", must name a file or folder of the repository: it must
   exist, lie inside the repository and not be ignored by git (out/, build/,
   bin/ are not in a clone).  #anchors are stripped; http(s):, mailto: and
   pure #anchor links are not checked.  Links inside fenced code blocks and
   `code spans` are not links and are skipped.
2. No file tracked by git may point outside the repository: no relative
   path into the shared folder beside it, no absolute path of a particular
   machine (home, root, work and temporary folders; a mktemp template ending
   in XXXXXX is a pattern, not a path, and is allowed), and no reference to
   the project's external notes by name (the "spec" documents, which a clone
   does not contain).  The exact patterns are the list OUTSIDE below.
3. README.md and docs/ carry no dated remarks (no YYYY-MM-DD dates).

Prints one line per problem (FILE:LINE: what) and, when there is none,
"check_docs: N links, M files: ok".  Exit status 0 if ok, 1 otherwise.
Only the Python standard library and git are used.
"""
import os
import re
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))


def git(*args, cwd):
    return subprocess.run(["git", *args], cwd=cwd, check=True,
                          stdout=subprocess.PIPE).stdout.decode()


ROOT = git("rev-parse", "--show-toplevel", cwd=HERE).strip()
SELF = os.path.relpath(os.path.abspath(__file__), ROOT)

# ---------------------------------------------------------------- patterns
# Kept in one place; this file is exempt from check 2 for these lines only
# (lines that contain a PATTERN-LIST marker).
OUTSIDE = [  # PATTERN-LIST
    (re.compile(r"\.\./shared"), "points outside the repository (../shared)"),  # PATTERN-LIST
    (re.compile(r"(?<![\w.~-])/(work|home|root|tmp)/"),  # PATTERN-LIST
     "absolute path of a machine"),  # PATTERN-LIST
    (re.compile(r"\bspec\s+(sec\.|section\b|§)|\bspec\s+[\w-]+\.md\b"  # PATTERN-LIST
                r"|\b(greenspan|mac-thesis|film-scheme|yasuda-balls)\.md\b"  # PATTERN-LIST
                r"|\(spec,\s+uncertain\b|\bseeds?[ /]0\d\d\b"),  # PATTERN-LIST
     "refers to notes outside the repository (the 'spec' or a 'seed')"),  # PATTERN-LIST
]  # PATTERN-LIST
MKTEMP = re.compile(r"/tmp/[\w.-]*XXXXXX")   # a template, not a path  PATTERN-LIST
DATE = re.compile(r"\b(19|20)\d\d-[01]\d-[0-3]\d\b")

LINK = re.compile(r"!?\[(?:[^\[\]]|\[[^\[\]]*\])*\]\(\s*<?([^()\s<>]*(?:\([^()\s]*\)[^()\s<>]*)*)>?"
                  r"(?:\s+(?:\"[^\"]*\"|'[^']*'|\([^)]*\)))?\s*\)")
REFDEF = re.compile(r"^\s{0,3}\[[^\]]+\]:\s*<?(\S+?)>?(?:\s+.*)?$")
CODESPAN = re.compile(r"(`+)(?:(?!\1).)+?\1")
FENCE = re.compile(r"^\s{0,3}(```|~~~)")


def doc_files():
    out = []
    if os.path.isfile(os.path.join(ROOT, "README.md")):
        out.append("README.md")
    for d, _, files in os.walk(os.path.join(ROOT, "docs")):
        for f in sorted(files):
            if f.endswith(".md"):
                out.append(os.path.relpath(os.path.join(d, f), ROOT))
    return sorted(out)


def ignored(paths):
    """The subset of paths (relative to ROOT) that git ignores."""
    if not paths:
        return set()
    p = subprocess.run(["git", "check-ignore", "--no-index", "--stdin", "-z"],
                       cwd=ROOT, input="\0".join(paths).encode(),
                       stdout=subprocess.PIPE)
    return set(x for x in p.stdout.decode().split("\0") if x)


def links_of(path):
    """(line number, target) of every link in a Markdown file."""
    found = []
    fenced = None
    with open(os.path.join(ROOT, path), encoding="utf-8") as fh:
        for n, line in enumerate(fh, 1):
            m = FENCE.match(line)
            if m:
                if fenced is None:
                    fenced = m.group(1)
                elif m.group(1) == fenced:
                    fenced = None
                continue
            if fenced:
                continue
            text = CODESPAN.sub("", line)
            for m in LINK.finditer(text):
                found.append((n, m.group(1)))
            m = REFDEF.match(text)
            if m:
                found.append((n, m.group(1)))
    return found


def check_links(problems):
    checked = []
    for doc in doc_files():
        base = os.path.dirname(doc)
        for n, target in links_of(doc):
            if not target or target.startswith("#"):
                continue
            if re.match(r"^[a-zA-Z][a-zA-Z0-9+.-]*:", target):
                continue   # http:, https:, mailto:, ...
            rel = target.split("#", 1)[0].split("?", 1)[0]
            if rel.startswith("/"):
                problems.append("%s:%d: absolute link %s (use a relative one)"
                                % (doc, n, target))
                continue
            full = os.path.normpath(os.path.join(ROOT, base, rel))
            inrepo = os.path.relpath(full, ROOT)
            checked.append((doc, n, target, inrepo))
            if inrepo == ".." or inrepo.startswith(".." + os.sep):
                problems.append("%s:%d: link %s leaves the repository"
                                % (doc, n, target))
            elif not os.path.exists(full):
                problems.append("%s:%d: link %s: no such file %s"
                                % (doc, n, target, inrepo))
    bad = ignored([c[3] for c in checked
                   if os.path.exists(os.path.join(ROOT, c[3]))
                   and not c[3].startswith("..")])
    for doc, n, target, inrepo in checked:
        if inrepo in bad:
            problems.append("%s:%d: link %s: %s is ignored by git (a build "
                            "output, not in a clone)" % (doc, n, target, inrepo))
    return len(checked)


def check_tracked(problems):
    files = [f for f in git("ls-files", "-z", cwd=ROOT).split("\0") if f]
    n = 0
    for f in files:
        full = os.path.join(ROOT, f)
        if not os.path.isfile(full):
            continue
        with open(full, "rb") as fh:
            data = fh.read()
        if b"\0" in data:
            continue   # binary
        n += 1
        text = data.decode("utf-8", errors="replace")
        for k, line in enumerate(text.splitlines(), 1):
            if f == SELF and "PATTERN-LIST" in line:
                continue
            scrubbed = MKTEMP.sub("", line)
            for rx, what in OUTSIDE:
                m = rx.search(scrubbed)
                if m:
                    problems.append("%s:%d: %s: %s" % (f, k, what,
                                                       m.group(0).strip()))
    return n


def check_dates(problems):
    for doc in doc_files():
        with open(os.path.join(ROOT, doc), encoding="utf-8") as fh:
            for n, line in enumerate(fh, 1):
                m = DATE.search(line)
                if m:
                    problems.append("%s:%d: dated remark (%s): state what "
                                    "holds now" % (doc, n, m.group(0)))


def main():
    problems = []
    nlinks = check_links(problems)
    nfiles = check_tracked(problems)
    check_dates(problems)
    for p in problems:
        print(p)
    if problems:
        print("check_docs: %d problem(s) (%d links, %d files)"
              % (len(problems), nlinks, nfiles))
        return 1
    print("check_docs: %d links, %d files: ok" % (nlinks, nfiles))
    return 0


if __name__ == "__main__":
    sys.exit(main())
