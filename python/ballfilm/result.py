"""result.py: a ballfilm HDF5 file as a Python object (ballfilm.load).

Reads with h5py; needs nothing of the C library, so it works on files
from any machine.  Datasets are read when first asked for (a large run
is not loaded whole) unless the file is temporary (ballfilm.run without
an output path), then everything, attributes too, is read at once and
the Result no longer names the file, which is removed (.path is None).

The file of a run still written, or killed (OUT.h5.part), is read as the
program reads it (docs/output.md, "A killed run's file"): opened as an
HDF5 SWMR reader when its writer was in that mode, and every series cut
to the rows of the last complete flush, which the writer records in the
log dataset /flushed_rows (not listed among the datasets).
"""
import os

import h5py

FLUSH_LOG = "flushed_rows"


def _text(v):
    return v.decode() if isinstance(v, bytes) else str(v)


def _marked_for_writing(path):
    """Whether HDF5's superblock (version 2 or 3, at the start) marks the
    file as open for writing: byte 11, the file consistency flags."""
    try:
        with open(path, "rb") as f:
            sb = f.read(12)
    except OSError:
        return False
    return (len(sb) == 12 and sb[:8] == b"\x89HDF\r\n\x1a\n" and sb[8] >= 2
            and sb[11] & 0x05 != 0)


def _open(path):
    """The file read-only: plainly, or as a SWMR reader when a writer in
    HDF5's SWMR mode (running, or killed) holds it."""
    try:
        return h5py.File(path, "r")
    except FileNotFoundError:
        raise
    except OSError as plain:
        try:
            return h5py.File(path, "r", libver="latest", swmr=True)
        except OSError:
            if not _marked_for_writing(path):
                raise plain from None
            raise OSError(
                f"{path}: HDF5 marks it as open for writing ({plain}); if "
                f"the run writing it was killed, `h5clear -s {path}` clears "
                f"the mark") from None


def _flushed_rows(f):
    """{series path without "/": rows} of the last complete flush, from
    the log of a run's .part (its row g starts with g, counted from 1; a
    row whose length reached the disk before its values reads 0 there),
    or {} when the file has none."""
    if FLUSH_LOG not in f:
        return {}
    log = f[FLUSH_LOG][()]
    names = _text(f[FLUSH_LOG].attrs.get("series", "")).split("\n")
    r = len(log)
    while r > 0 and log[r - 1, 0] != r:
        r -= 1
    if not r:
        return {}
    return {n.lstrip("/"): int(v) for n, v in zip(names, log[r - 1, 1:]) if n}


class Result:
    """What a ballfilm output file holds.

    r["balls/position"]       a dataset as a numpy array (leading "/"
                              optional); r.keys() lists them all
    r.units[name], r.descriptions[name]
                              each dataset's unit (UDUNITS-2) and
                              description
    r.column_units[name]      a unit per column (a list): the dataset's
                              "column_units" where its columns differ, else
                              its unit for every fixed column ([] for a
                              column per item or none)
    r.columns[name]           the names of its fixed columns (a list)
    r.scaled_units[name]      the model's scaled unit ("L", "R W^2"; the
                              MAC model), or "" (a list per column where
                              they differ)
    r.roles[name], r.kinds[name]
                              what it is for ("time", "position_x",
                              "velocity_half_step", "field", ...) and how it
                              grows ("rows", "snapshot", "events",
                              "static"); "" in files of programs that did
                              not write them
    r.time                    /time (s), the output rows' times
    r.params                  every resolved scene key: {"ball.1.mass": 1.0}
    r.param_units             their units; r.defaults: the keys left at their
                              default
    r.scene_text, r.scene_file, r.version
    r.status, r.message       how the run ended ("ok", "interrupted", ...)
    r.counters                steps, t_final, force evaluations, rejected
                              steps, iterations
    r.energy_error            the largest relative energy error (None for a
                              model without an energy); with non-conservative
                              forces that of the balance E - E0 + W_dissipated
                              - W_injected (/energy/dissipated, /injected)
    r.energy_balance          True when energy_error is that of the balance
    r.attrs                   every root attribute as h5py reads it
    r.summary()               what `ballfilm info` prints (Jupyter shows
                              the same as HTML, _repr_html_); repr(r) is
                              one line: model, status, steps, t, energy
                              error
    """

    def __init__(self, path, eager=False):
        self.path = os.fspath(path)
        self._cache = {}
        self._obj_attrs = None  # {name: attributes} when read at once
        self.units, self.descriptions, self.shapes = {}, {}, {}
        self.column_units, self.columns, self.scaled_units = {}, {}, {}
        self.roles, self.kinds = {}, {}
        with _open(self.path) as f:
            self.attrs = {k: f.attrs[k] for k in f.attrs}
            self._rows = _flushed_rows(f)
            if eager:
                self._obj_attrs = {}

            def visit(name, obj):
                if eager and name != FLUSH_LOG:
                    self._obj_attrs[name] = {k: obj.attrs[k]
                                             for k in obj.attrs}
                if isinstance(obj, h5py.Dataset) and name != FLUSH_LOG:
                    self.units[name] = _text(obj.attrs.get("unit", ""))
                    self.descriptions[name] = _text(
                        obj.attrs.get("description", ""))
                    self._describe(name, obj)
                    shape = obj.shape
                    if name in self._rows and shape:
                        shape = (min(shape[0], self._rows[name]),) + shape[1:]
                    self.shapes[name] = shape
                    if eager:
                        self._cache[name] = self._read(obj, name)

            f.visititems(visit)
        a = self.attrs
        self.scene_text = _text(a.get("scene_text", ""))
        self.scene_file = _text(a.get("scene_file", ""))
        self.version = _text(a.get("version", ""))
        self.status = _text(a.get("status", ""))
        self.message = _text(a.get("message", ""))
        self.params, self.param_units, self.defaults = {}, {}, set()
        for k, v in a.items():
            if k.endswith(".unit"):
                self.param_units[k[:-5]] = _text(v)
            elif k.endswith(".default"):
                self.defaults.add(k[:-8])
            elif "." in k:
                self.params[k] = _text(v) if isinstance(v, (str, bytes)) else v
        self.counters = {}
        for key in ("steps_done", "t_final", "force_evaluations",
                    "rejected_steps", "iterations"):
            if key in a:
                self.counters[key] = a[key].item() if hasattr(a[key], "item") \
                    else a[key]
        e = a.get("max_relative_energy_error")
        self.energy_error = float(e) if e is not None else None
        # with non-conservative forces energy_error is that of the balance
        # E - E0 + W_dissipated - W_injected (/energy/dissipated, injected)
        self.energy_balance = "energy_balance" in a

    def _describe(self, name, obj):
        """the attributes of series.h: columns, their units, role, kind"""
        def listed(key, sep):
            t = _text(obj.attrs.get(key, ""))
            return [x.strip() for x in t.split(sep)] if t else []
        self.columns[name] = listed("columns", ",")
        cu = listed("column_units", ";")
        if not cu and self.columns[name]:
            cu = [self.units[name]] * len(self.columns[name])
        self.column_units[name] = cu
        su = listed("scaled_unit", ";")
        self.scaled_units[name] = (su[0] if len(su) == 1 else su) if su else ""
        self.roles[name] = _text(obj.attrs.get("role", ""))
        self.kinds[name] = _text(obj.attrs.get("kind", ""))

    def _read(self, obj, name):
        if name in self._rows and obj.shape:
            return obj[:self.shapes[name][0]]
        return obj[()]

    @staticmethod
    def _name(name):
        return name[1:] if name.startswith("/") else name

    def keys(self):
        return sorted(self.shapes)

    def __contains__(self, name):
        return self._name(name) in self.shapes

    def forget_file(self):
        """Detach a Result read at once from its file, which is about to
        be removed: nothing names it any more."""
        assert self._obj_attrs is not None, "only a Result read at once"
        self.path = None

    def _where(self):
        return self.path if self.path is not None else \
            "the run's result (read into memory; its temporary file is gone)"

    def __getitem__(self, name):
        n = self._name(name)
        if n not in self.shapes:
            raise KeyError(f"{self._where()} has no dataset /{n} (it has: "
                           f"{', '.join(self.keys())})")
        if n not in self._cache:
            with _open(self.path) as f:
                self._cache[n] = self._read(f[n], n)
        return self._cache[n]

    def group(self, name):
        """{dataset name below the group: array}, e.g. r.group("converge")."""
        g = self._name(name).rstrip("/") + "/"
        return {k[len(g):]: self[k] for k in self.keys() if k.startswith(g)}

    def attrs_of(self, name):
        """The attributes of a dataset or group, as h5py reads them."""
        if self._obj_attrs is not None:
            n = self._name(name)
            if n not in self._obj_attrs:
                raise KeyError(f"{self._where()} has no dataset or group /{n}")
            return dict(self._obj_attrs[n])
        with _open(self.path) as f:
            obj = f["/" + self._name(name)]
            return {k: obj.attrs[k] for k in obj.attrs}

    @property
    def time(self):
        return self["time"]

    @property
    def steps(self):
        return self.counters.get("steps_done")

    def _info(self):
        """[(label, value)] of the run, as `ballfilm info` prints them."""
        p, c = self.params, self.counters
        rows = [("file", self.path or "in memory (its temporary file is "
                 "gone)")]
        for label, key in (("title", "scene.title"), ("model", "scene.model"),
                           ("integrator", "scene.integrator"),
                           ("effects", "scene.effects")):
            if p.get(key, "") != "":
                rows.append((label, str(p[key])))
        if self.version:
            rows.append(("written by", self.version))
        if self.scene_file:
            rows.append(("scene file", self.scene_file))
        status = self.status or "?"
        if self.message and self.message != self.status:
            status += f" ({self.message})"
        rows.append(("status", status))
        if "steps_done" in c:
            t = f" (t = {c['t_final']:g} s)" if "t_final" in c else ""
            rows.append(("steps", f"{c['steps_done']}{t}"))
        for label, key in (("force evaluations", "force_evaluations"),
                           ("rejected steps", "rejected_steps"),
                           ("iterations", "iterations")):
            if key in c:
                rows.append((label, str(c[key])))
        rows.append(("max relative energy error",
                     "none (no energy)" if self.energy_error is None
                     else f"{self.energy_error:.6e}"))
        return rows

    def _datasets(self):
        """[(name, shape text, unit, description)] of every dataset."""
        return [("/" + n, "[" + " x ".join(str(d) for d in self.shapes[n])
                 + "]" if self.shapes[n] else "[]", self.units.get(n, ""),
                 self.descriptions.get(n, "")) for n in self.keys()]

    def summary(self):
        """What `ballfilm info` prints of the file: the scene (title,
        model, integrator, effects), the version that wrote it, the status
        and message, the steps and counters, the energy error, and every
        dataset with its shape, unit and description."""
        info = self._info()
        w = max(len(k) for k, _ in info) + 2
        lines = [f"{k + ':':<{w}}{v}" for k, v in info]
        ds = self._datasets()
        lines.append(f"datasets: {len(ds)}")
        if ds:
            wn = max(len(d[0]) for d in ds) + 2
            ws = max(len(d[1]) for d in ds) + 2
            wu = max(len(d[2]) for d in ds) + 2
            for name, shape, unit, desc in ds:
                lines.append(f"  {name:<{wn}}{shape:<{ws}}{unit:<{wu}}"
                             f"{desc}".rstrip())
        return "\n".join(lines)

    def _repr_html_(self):
        """summary() as HTML tables (Jupyter shows it for a Result)."""
        from html import escape
        head = "".join(f"<tr><th style='text-align:left'>{escape(k)}</th>"
                       f"<td style='text-align:left'>{escape(v)}</td></tr>"
                       for k, v in self._info())
        body = "".join("<tr>" + "".join(
            f"<td style='text-align:left'>{escape(x)}</td>" for x in d) +
            "</tr>" for d in self._datasets())
        return (f"<div><b>ballfilm.Result</b><table>{head}</table>"
                f"<table><tr><th>dataset</th><th>shape</th><th>unit</th>"
                f"<th>description</th></tr>{body}</table></div>")

    def __repr__(self):
        c = self.counters
        e = "n/a" if self.energy_error is None else f"{self.energy_error:.3g}"
        t = f"{c['t_final']:g}" if "t_final" in c else "?"
        return (f"<ballfilm.Result {self.path or 'in memory'}: "
                f"{self.params.get('scene.model', '?')}, "
                f"status {self.status or '?'}, {c.get('steps_done', '?')} "
                f"steps, t={t} s, energy error {e}, "
                f"{len(self.shapes)} datasets>")


def load(path):
    """The contents of a ballfilm output file (a run's OUT.h5, its
    OUT.h5.part while unfinished, a sweep's summary.h5, a converge
    table)."""
    path = os.fspath(path)
    if not os.path.exists(path) and os.path.exists(path + ".part"):
        path = path + ".part"
    return Result(path)
