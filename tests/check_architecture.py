#!/usr/bin/python3
"""check_architecture.py: the layering rules of docs/architecture.md, checked
on the code as it is.

Reads the layer table of docs/architecture.md (rows "| N | layer | `src/x` |
`a.h` `b.h` |": a folder of the library, its layer number and the public
headers it implements), then every #include "..." line of src/**/*.{c,h}
and include/ballfilm/*.h, and fails (exit 1, one line per problem) when
  - a file includes a header of a higher layer (an arrow that runs up);
  - the folders include each other in a circle (also within one layer);
  - the files of one folder include each other in a circle (a file and
    its header of the same name are one unit);
  - include/ballfilm/ holds a header no row names, more than 20 headers,
    or an inline function with a loop (a numerical kernel: kernels are
    private, beside their code);
  - a source file of src/ has more than 900 lines;
  - a file outside src/io and src/compose calls the scene API (bf_scene_);
  - git tracks an entry at the top level other than TOP_LEVEL (the
    repository's fixed layout; README.md's "Where things are");
  - more than MAX_SHARED_PATHS dataset paths are written as string
    literals in two or more files of src/ (dataset_path_literals below
    states the rule; src/io/xdmf*.c is counted and reported apart);
  - the convergence driver (src/compose/converge*, study*) knows a model
    by more than its descriptor's study (study_driver_problems below).
Run from the repository root: /usr/bin/python3 tests/check_architecture.py
"""
import os
import re
import sys

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), ".."))
MAX_LINES = 900
MAX_PUBLIC = 20
SCENE_LAYERS = ("src/io", "src/compose")
TOP_LEVEL = {"Makefile", "README.md", "src", "include", "runs", "tests",
             "plots", "bench", "docs", "examples", "python", ".ci",
             ".gitignore",
             # packaging metadata for pip (the build steps are in python/)
             "pyproject.toml",
             # a link to python/ballfilm, so that /usr/bin/python3 run
             # from the root imports the package with no PYTHONPATH
             "ballfilm"}


MAX_SHARED_PATHS = 5
# The first components of file-system paths written in src/ ("/proc/...",
# "/usr/bin/python3"): such literals name no dataset.
FS_ROOTS = {"proc", "dev", "usr", "share", "plots", "etc", "tmp", "sys",
            "bin", "lib", "var", "home"}
PATH_LITERAL = re.compile(r'"(/[A-Za-z_][A-Za-z0-9_]*(?:/[A-Za-z0-9_]+)*)"')
COMMENT = re.compile(r"/\*.*?\*/|//[^\n]*", re.S)


def dataset_path_literals(exclude=()):
    """{path: set of files}: the dataset paths written as string literals
    in src/**/*.{c,h}.  The rule: a C string literal (outside comments)
    that is exactly "/" followed by one or more names of letters, digits
    and '_' separated by '/' ("/time", "/film/h", "/mac/particles/x"),
    whose first name is no FS_ROOTS entry.  A literal spliced from several
    ("/a" "/b") counts as its parts; a path built at run time, or taken
    from a table or a macro of one header, counts once, where its text
    is."""
    found = {}
    for dirpath, _, names in os.walk(os.path.join(ROOT, "src")):
        for n in names:
            if not n.endswith((".c", ".h")):
                continue
            rel = os.path.relpath(os.path.join(dirpath, n), ROOT)
            if any(rel.startswith(e) for e in exclude):
                continue
            with open(os.path.join(ROOT, rel), encoding="utf-8") as fh:
                text = COMMENT.sub(" ", fh.read())
            for m in PATH_LITERAL.finditer(text):
                path = m.group(1)
                if path.split("/")[1] in FS_ROOTS:
                    continue
                found.setdefault(path, set()).add(rel)
    return found


def shared_path_problems():
    """dataset paths written in two or more files (xdmf*.c counted; the
    count without it is printed too)"""
    every = dataset_path_literals()
    shared = sorted(p for p, fs in every.items() if len(fs) > 1)
    without = dataset_path_literals(exclude=("src/io/xdmf",))
    shared_wo = sorted(p for p, fs in without.items() if len(fs) > 1)
    print(f"check_architecture: dataset paths as literals: {len(every)}, "
          f"{len(shared)} in two or more files ({len(shared_wo)} without "
          "src/io/xdmf*.c)")
    if len(shared_wo) <= MAX_SHARED_PATHS:
        return []
    return [f"{p}: a dataset path written in {len(without[p])} files "
            f"({', '.join(sorted(without[p]))}); more than "
            f"{MAX_SHARED_PATHS} such paths: take it from its table or a "
            "header" for p in shared_wo]


STUDY_DRIVER = re.compile(r"src/compose/(converge|study)[^/]*\.[ch]$")
SCENE_SECTION = re.compile(r"\bbf_scene_\w+\s*\(\s*[^,()]+,\s*\"(\w+)\"")
STUDY_TABLE = re.compile(r"\bbf_study_type\s*\*\s*const\s+\w+\s*\[")
STRCMP = re.compile(r"\bstr(?:n|case)?cmp\s*\(")


def call_args(code, start):
    """The text of a call's arguments, from just after its "(" at start to
    the matching ")"."""
    depth, i = 1, start
    while i < len(code) and depth:
        depth += {"(": 1, ")": -1}.get(code[i], 0)
        i += 1
    return code[start:i - 1]


def name_registry(code):
    """Offsets of string comparisons whose arguments name a model (model,
    ->model, "scene", "model") and of tables of studies."""
    hits = [m.start() for m in STUDY_TABLE.finditer(code)]
    for m in STRCMP.finditer(code):
        if re.search(r"\bmodel\b", call_args(code, m.end())):
            hits.append(m.start())
    return hits


def study_driver_problems(files):
    """The driver of `ballfilm converge` asks a model's descriptor for its
    study (ballfilm/study.h, model.h's .study) and nothing else: in
    src/compose/converge*.[ch] and study*.[ch] (outside comments) it fails
    on a scene read of a section other than [scene] (a model's key read
    by string: bf_scene_str(sc, "film", "scheme")), on a comparison with a
    model's name (strcmp(..., model ...)) or a table of studies (a registry
    by name), and on an include of a model's private header (models/*.h,
    what a cast of the model's void * to its type needs)."""
    out = []
    for f in files:
        if not STUDY_DRIVER.match(f):
            continue
        with open(os.path.join(ROOT, f), errors="replace") as fh:
            # comments blanked, their line breaks kept (line numbers)
            code = COMMENT.sub(lambda c: " " + "\n" * c.group(0).count("\n"),
                               fh.read())
        for m in SCENE_SECTION.finditer(code):
            if m.group(1) != "scene":
                line = code.count("\n", 0, m.start()) + 1
                out.append(f"{f}:{line}: reads [{m.group(1)}] from the "
                           "scene: a model's keys reach its study as filled "
                           "structs (study.h)")
        for at in name_registry(code):
            line = code.count("\n", 0, at) + 1
            out.append(f"{f}:{line}: a study looked up by model name: the "
                       "model's descriptor points to its study (.study)")
        for m in INCLUDE.finditer(code):
            if m.group(1).startswith("models/"):
                line = code.count("\n", 0, m.start()) + 1
                out.append(f"{f}:{line}: includes {m.group(1)}: the driver "
                           "sees a model through its descriptor only")
    return out


def top_level_problems():
    """Tracked top-level entries outside TOP_LEVEL (none outside git)."""
    import subprocess
    try:
        out = subprocess.run(["git", "-C", ROOT, "ls-files"], check=True,
                             capture_output=True, text=True).stdout
    except (OSError, subprocess.CalledProcessError):
        return []
    tops = {line.split("/", 1)[0] for line in out.splitlines() if line}
    return [f"{t}: an entry at the top level outside the fixed layout "
            f"({', '.join(sorted(TOP_LEVEL))})" for t in sorted(tops - TOP_LEVEL)]


def rel(path):
    return os.path.relpath(path, ROOT)


def read_table():
    """folder -> layer, header -> folder, from docs/architecture.md"""
    folder_layer, header_folder = {}, {}
    with open(os.path.join(ROOT, "docs", "architecture.md")) as f:
        for line in f:
            cells = [c.strip() for c in line.strip().strip("|").split("|")]
            if len(cells) < 4 or not cells[0].isdigit():
                continue
            folders = re.findall(r"`(src/[a-z_]+)`", cells[2])
            for folder in folders:
                folder_layer[folder] = int(cells[0])
            for h in re.findall(r"`([a-z_0-9]+\.h)`", cells[3]):
                if len(folders) != 1:
                    sys.exit(f"architecture.md: the row of {h} must name one "
                             "folder")
                header_folder[f"include/ballfilm/{h}"] = folders[0]
    if not folder_layer:
        sys.exit("check_architecture: no layer table in docs/architecture.md")
    return folder_layer, header_folder


def sources():
    out = []
    for base in ("src", "include"):
        for d, _, files in os.walk(os.path.join(ROOT, base)):
            for name in files:
                if name.endswith((".c", ".h")):
                    out.append(rel(os.path.join(d, name)))
    return sorted(out)


INCLUDE = re.compile(r'^\s*#\s*include\s+"([^"]+)"', re.M)


def resolve(includer, name):
    """the repository file an #include "name" of includer means, or None"""
    for cand in (os.path.join(os.path.dirname(includer), name),
                 os.path.join("include", name), os.path.join("src", name)):
        cand = os.path.normpath(cand)
        if os.path.isfile(os.path.join(ROOT, cand)):
            return cand
    return None


def folder_of(path, header_folder):
    if path.startswith("include/"):
        return header_folder.get(path)
    parts = path.split("/")
    return "/".join(parts[:2]) if len(parts) > 2 else None


def find_cycle(graph):
    """a cycle of the directed graph {node: set(nodes)} as a list, or None"""
    state, stack = {}, []

    def visit(u):
        state[u] = 1
        stack.append(u)
        for v in sorted(graph.get(u, ())):
            if state.get(v) == 1:
                return stack[stack.index(v):] + [v]
            if not state.get(v):
                c = visit(v)
                if c:
                    return c
        stack.pop()
        state[u] = 2
        return None

    for u in sorted(graph):
        if not state.get(u):
            c = visit(u)
            if c:
                return c
    return None


def inline_kernels(path, text):
    """names of inline functions with a loop in a header"""
    out = []
    for m in re.finditer(r"static\s+inline[^;{]*?\b(\w+)\s*\([^;{]*\)\s*\{",
                         text):
        depth, i = 1, m.end()
        while depth and i < len(text):
            depth += {"{": 1, "}": -1}.get(text[i], 0)
            i += 1
        if re.search(r"\b(for|while)\s*\(", text[m.end():i]):
            out.append(m.group(1))
    return out


def main():
    folder_layer, header_folder = read_table()
    problems = top_level_problems() + shared_path_problems()
    files = sources()
    folder_graph, unit_graph = {}, {}
    nedges = 0
    problems += study_driver_problems(files)
    public = [f for f in files if f.startswith("include/ballfilm/")]
    for h in public:
        if h not in header_folder:
            problems.append(f"{h}: a public header that no row of "
                            "docs/architecture.md names")
    if len(public) > MAX_PUBLIC:
        problems.append(f"include/ballfilm/ holds {len(public)} headers "
                        f"(at most {MAX_PUBLIC})")
    for f in files:
        with open(os.path.join(ROOT, f), errors="replace") as fh:
            text = fh.read()
        src_folder = folder_of(f, header_folder)
        if src_folder is None:
            continue
        if src_folder not in folder_layer:
            problems.append(f"{f}: folder {src_folder} is in no layer of "
                            "docs/architecture.md")
            continue
        layer = folder_layer[src_folder]
        if f.startswith("src/") and f.endswith(".c"):
            n = text.count("\n")
            if n > MAX_LINES:
                problems.append(f"{f}: {n} lines (at most {MAX_LINES})")
        if f.startswith("include/"):
            for k in inline_kernels(f, text):
                problems.append(f"{f}: inline function {k} has a loop (a "
                                "kernel: make it private)")
        if not f.startswith(SCENE_LAYERS) and f != "include/ballfilm/scene.h":
            code = re.sub(r"/\*.*?\*/", "", text, flags=re.S)
            for m in re.finditer(r"\bbf_scene_\w+", code):
                line = code.count("\n", 0, m.start()) + 1
                problems.append(f"{f}:{line}: {m.group(0)}: only src/io and "
                                "src/compose read scenes")
                break
        for m in INCLUDE.finditer(text):
            target = resolve(f, m.group(1))
            if target is None:
                continue  # a system or generated header
            nedges += 1
            line = text.count("\n", 0, m.start()) + 1
            tfolder = folder_of(target, header_folder)
            if tfolder is None or tfolder not in folder_layer:
                problems.append(f"{f}:{line}: includes {target}, which is in "
                                "no layer")
                continue
            tlayer = folder_layer[tfolder]
            if tlayer > layer:
                problems.append(f"{f}:{line}: includes {target} (layer "
                                f"{tlayer}) from layer {layer}: an arrow "
                                "up")
            if tfolder != src_folder:
                folder_graph.setdefault(src_folder, set()).add(tfolder)
            elif f.startswith("src/") and target.startswith("src/"):
                u = os.path.splitext(f)[0]
                v = os.path.splitext(target)[0]
                if u != v:
                    unit_graph.setdefault(u, set()).add(v)
    cycle = find_cycle(folder_graph)
    if cycle:
        problems.append("folders include each other in a circle: " +
                        " -> ".join(cycle))
    cycle = find_cycle(unit_graph)
    if cycle:
        problems.append("files of one folder include each other in a "
                        "circle: " + " -> ".join(cycle))
    for p in problems:
        print(p)
    if problems:
        print(f"check_architecture: {len(problems)} problems")
        return 1
    print(f"check_architecture: {len(files)} files, {nedges} includes, "
          f"{len(folder_layer)} folders in "
          f"{len(set(folder_layer.values()))} layers, {len(public)} public "
          "headers: ok")
    return 0


if __name__ == "__main__":
    sys.exit(main())
