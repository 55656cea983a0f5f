#!/usr/bin/python3
"""mkman.py: the man page ballfilm(1) from its hand-written roff
(src/cli/ballfilm.1.in) and the program's own key table.

  /usr/bin/python3 src/cli/mkman.py PROGRAM TEMPLATE VERSION > ballfilm.1

@VERSION@ in the template becomes VERSION, and the line @KEYS@ becomes the
SCENE KEYS section: the part of `PROGRAM run --help` from "Scene files are
INI files" on, in roff.  That text is laid out as
  [section]  doc                 a section (the line before it may be
                                 "-- used by MODELS --")
    key      doc                 a key (two spaces in), or a model,
                                 integrator or effect under a heading
                       [...]     the key's type, unit and default
  Heading (...):                 the lists of models, integrators, effects
Only the Python standard library is used.
"""
import subprocess
import sys


def roff_text(s):
    """Plain text for roff: backslashes escaped, no control line, and a
    place to break a line after each | of a long list of choices."""
    s = s.replace("\\", "\\e").replace("-", "\\-").replace("|", "|\\:")
    return "\\&" + s if s[:1] in (".", "'") else s


def keys_roff(help_text):
    start = help_text.find("Scene files are INI files")
    if start < 0:
        sys.exit("mkman: no key table in `run --help`")
    out, used_by = [], None
    for line in help_text[start:].splitlines():
        if not line.strip():
            continue
        body = line.strip()
        indent = len(line) - len(line.lstrip(" "))
        if body.startswith("Scene files are INI files"):
            out.append(roff_text(body))
        elif indent == 0 and body.startswith("-- used by") and body.endswith("--"):
            used_by = body.strip("- ").strip()
        elif indent == 0 and body.startswith("["):
            name, _, doc = body.partition("]")
            out.append(".SS %s]" % roff_text(name))
            out.append(roff_text(doc.strip()) +
                       (" (%s.)" % roff_text(used_by.capitalize())
                        if used_by else ""))
            used_by = None
        elif indent == 0:
            out.append(".SS %s" % roff_text(body.rstrip(":")))
        elif indent <= 4:
            key, _, doc = body.partition(" ")
            out.append(".TP")
            out.append(".B %s" % roff_text(key))
            out.append(roff_text(doc.strip()))
        else:  # the key's [type; unit; default] line
            out.append(".br")
            out.append(roff_text(body))
    return "\n".join(out)


def main():
    if len(sys.argv) != 4:
        sys.exit(__doc__)
    prog, template, version = sys.argv[1:]
    text = subprocess.run([prog, "run", "--help"], check=True,
                          capture_output=True, text=True).stdout
    with open(template) as f:
        page = f.read()
    if "\n@KEYS@\n" not in page:
        sys.exit("mkman: %s has no @KEYS@ line" % template)
    page = page.replace("@VERSION@", version)
    page = page.replace("\n@KEYS@\n", "\n" + keys_roff(text) + "\n")
    sys.stdout.write(page)


if __name__ == "__main__":
    main()
