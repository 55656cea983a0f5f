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
4. No page of README.md and docs/**/*.md narrates the history of the work:
   no issue number ("issue 21", "issue #21", "#21" in prose, "item 5"), no
   round of measurement ("the eighth round"), no run of a series ("the
   ninth run", "the sixth `make bench`", "Nine whole make bench runs"), no
   session ("a session later"), no commit as a point in time ("since
   9e36768") and no month of work ("December 2026").  A page says what
   holds now and the command that shows it; the history is in git.  Not
   flagged: round-off, rounding, a round trip, N rounds of a benchmark,
   runs of steps, a Python session, an upstream project's issue
   ("SUNDIALS issue 311"), and "Report #153" or a month in a section that
   cites the papers.  Fenced code blocks and link targets are skipped.
   The patterns are HISTORY below; self_test() checks them on examples
   (good and bad) at every run.
5. docs/performance.md has at most 250 lines (MAX_LINES): a reference,
   not a log.

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

# ---------------------------------------------------------------- history
_ORD = (r"(?:first|second|third|fourth|fifth|sixth|seventh|eighth|ninth|"
        r"tenth|eleventh|twelfth|\d+(?:st|nd|rd|th))")
_NUMS = r"two|three|four|five|six|seven|eight|nine|ten|eleven|twelve|\d+"
_NUM = r"(?:" + _NUMS + r")"
_MONTH = (r"(?:January|February|March|April|May|June|July|August|September|"
          r"October|November|December)")
# (pattern, what it is); matched case-insensitively on a line's prose.
HISTORY = [
    (r"\bissues?\s*#?\d+", "an issue number"),
    (r"\bitems?\s+\d+\b", "an issue's item"),
    (r"(?<![\w&#/])#\d+\b", "an issue number (#N)"),
    (r"\b(?:" + _ORD + r"|this|that|previous|next|earlier|later|latest|last)"
     r"(?:\s+(?:and|to|or)\s+" + _ORD + r")?\s+rounds?\b",
     "a round of measurement"),
    (r"\brounds?\s+(?:of\s+(?:measurement|work|profiling|optimi[sz]ation)"
     r"|\d+\b)", "a round of measurement"),
    # not "a second run on the same path" (another run), nor runs of steps
    (r"(?<!\ba )(?<!\ban )\b" + _ORD + r"\s+(?:whole\s+)?"
     r"(?:make\s+bench\b|runs?\b(?!\s+of\s+steps))", "a run of a series"),
    (r"\b" + _NUM + r"\s+(?:whole\s+)?(?:make\s+bench|bench)\s+runs\b",
     "a series of runs"),
    (r"\b(?:a|an|one|" + _NUMS + r"|this|that|same|previous|next|"
     r"earlier|later|last|another)\s+sessions?\b", "a session"),
    (r"\bsessions?\s+(?:later|earlier|before|ago)\b", "a session"),
    (r"\b(?:since|until|before|after|as\s+of|at)\s+(?:commit\s+)?"
     r"(?=[0-9a-f]*[a-f])(?=[0-9a-f]*\d)[0-9a-f]{7,40}\b",
     "a commit as a point in time"),
    (r"(?<!\d\s)\b" + _MONTH + r"\s+(?:19|20)\d\d\b", "a month of work"),
]
HISTORY = [(re.compile(p, re.IGNORECASE), w) for p, w in HISTORY]
# an issue number after an upstream project's name is that project's tracker
UPSTREAM = {"sundials", "arkode", "hdf5", "h5py", "numpy", "gcc", "glibc",
            "python", "cpython", "gsl", "inih", "openmpi", "mpi", "ffmpeg",
            "matplotlib", "debian", "linux"}
CITE_SECTION = re.compile(r"^#+\s.*\b(cit|referenc|bibliograph)", re.IGNORECASE)
CITE_OK = {"an issue number (#N)", "a month of work"}
MAX_LINES = {"docs/performance.md": 250}

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


def prose(line):
    """A Markdown line without its link targets, twice: with its code spans
    unquoted, and without them."""
    line = re.sub(r"\]\([^)]*\)", "]()", line)
    m = REFDEF.match(line)
    if m:
        line = line[:m.start(1)]
    return (CODESPAN.sub(lambda m: m.group(0).strip("`"), line),
            CODESPAN.sub(" ", line))


def history_in(lines):
    """(line number, what, text) of every remark in lines (a Markdown page)
    that narrates the history of the work."""
    found = []
    fenced = None
    citing = False
    for n, line in enumerate(lines, 1):
        m = FENCE.match(line)
        if m:
            if fenced is None:
                fenced = m.group(1)
            elif m.group(1) == fenced:
                fenced = None
            continue
        if fenced:
            continue
        if line.startswith("#"):
            citing = bool(CITE_SECTION.match(line))
        unquoted, bare = prose(line)
        for rx, what in HISTORY:
            # "#N" in prose only: `#include` and the like are code
            text = bare if what == "an issue number (#N)" else unquoted
            for m in rx.finditer(text):
                if citing and what in CITE_OK:
                    continue
                before = text[:m.start()].split()
                word = before[-1].strip("(,;:*_") if before else ""
                if what == "an issue number" and word.lower() in UPSTREAM:
                    continue
                if what == "an issue number (#N)" and word in ("Report", "No."):
                    continue
                found.append((n, what, m.group(0)))
    return found


def check_history(problems):
    for doc in doc_files():
        with open(os.path.join(ROOT, doc), encoding="utf-8") as fh:
            lines = fh.read().splitlines()
        for n, what, text in history_in(lines):
            problems.append("%s:%d: narrates the history of the work (%s: "
                            "\"%s\"): state what holds now and the command "
                            "that shows it; the history is in git"
                            % (doc, n, what, text))
        limit = MAX_LINES.get(doc)
        if limit is not None and len(lines) > limit:
            problems.append("%s:%d: %d lines, more than %d: a reference, "
                            "not a log" % (doc, len(lines), len(lines), limit))


def self_test():
    """The history patterns on examples: each bad line is flagged, no good
    line is.  Returns the examples that went wrong."""
    bad = ["What they printed for each point of issue 21:",
           "see issue #21 for the goal", "fixed in #21.",
           "Issue 19, items 3 and 4.", "(item 5 below)",
           "the eighth round of item 5", "#### Fifth round: branches",
           "the first rounds were measured elsewhere",
           "the third to eighth rounds are at the end",
           "Nine whole `make bench` runs on the AMD machine",
           "| ninth run (41d7be2) |", "the sixth `make bench` printed",
           "the ninth at 41d7be2, a session later",
           "in a later session, after the work", "two sessions later",
           "since 9e36768 the program asks", "measured at d680fe8, on",
           "December 2026, load average about 1",
           "its first runs found a NaN marker"]
    good = ["round-off breaks the symmetry", "rounding error of each update",
            "rounded to 0.01", "a round trip through the file",
            "the sixth stage is the next step's first (Runge-Kutta)",
            "20 rounds of 10⁵ steps each", "in five alternating rounds",
            "its ratio to the smallest N measured in the same round",
            "or a Python session, can use it", "- **SUNDIALS issue 311**",
            "Technical Report #153, Computer Sciences",
            "[Greenspan 1972](docs/models/greenspan72.md#200704-particles)",
            "a fourth-order Runge–Kutta, the first-return map",
            "the loop's first run of steps", "runs of steps",
            "a second run on the same path is refused",
            "`#include <ballfilm/run.h>`", "the first step, the second ball",
            "against a752c43, both built here", "16 September 2009",
            "a run issued by the sweep", "around 100 pairs"]
    wrong = []
    for line in bad:
        if not history_in([line]):
            wrong.append("not flagged: " + line)
    for line in good:
        if history_in([line]):
            wrong.append("flagged: %s (%s)" % (line, history_in([line])))
    cite = ["## How to cite the papers", "Report #171, Madison, March 1973."]
    if history_in(cite):
        wrong.append("flagged in a citation: " + cite[1])
    if not history_in(["## Timings", "Madison, March 1973."]):
        wrong.append("not flagged outside a citation: March 1973")
    return wrong


def main():
    problems = []
    wrong = self_test()
    if wrong:
        for w in wrong:
            print("check_docs: self-test of the history patterns: " + w)
        return 1
    nlinks = check_links(problems)
    nfiles = check_tracked(problems)
    check_dates(problems)
    check_history(problems)
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
