"""tables.py: the convergence study and parameter sweeps of the library
(converge.h, sweep.h) from Python, their results as tables: numpy
structured arrays with one row per run or case (Table: an ndarray that
also carries each column's unit in .units).
"""
import ctypes
import os

import numpy as np

from . import _lib
from .errors import Interrupted, from_err
from .runner import _in_thread, _scene_file, _set_words, _sets, _StopOnSigint


class Table(np.ndarray):
    """A structured array (one row per run or case) whose .units maps
    every column to its unit (UDUNITS-2: "cm", "s", "1" for a number
    without one, "" for text).  Indexing, slicing and masks work as on
    any structured array and keep .units (a column, t["err_x"], is a
    plain ndarray); np.asarray(table) is the plain array."""

    def __new__(cls, rows, dtype, units):
        t = np.array(rows, dtype=dtype).view(cls)
        t.units = dict(units)
        return t

    def __array_finalize__(self, obj):
        self.units = dict(getattr(obj, "units", {}) or {})

    def __getitem__(self, index):
        """Rows (a mask, a slice) stay a Table; a column or a field of
        one row is a plain array or scalar, as numpy would give."""
        v = super().__getitem__(index)
        if isinstance(v, Table) and v.dtype.names is None:
            return v.view(np.ndarray)
        return v


def _python_words(e, what, value):
    """A BallfilmError whose message names the command line's option
    (--set, --methods, --vary) reworded for the Python argument."""
    msg = e.message
    for opt in ("--methods: error: ", "--set: error: ", "--vary "):
        if opt in msg:
            m = msg
            if opt == "--vary ":
                m = msg.split(": ", 1)[1] if ": " in msg else msg
            elif msg.startswith("method "):
                m = msg.split(opt, 1)[1]
            else:
                m = msg.replace(opt, "", 1)
            e.args = (f"{what}={value!r}: {m}",)
            e.message = e.args[0]
            break
    return e


def _doubles(values):
    if values is None:
        return None, 0, None
    a = np.ascontiguousarray([float(v) for v in values], dtype=np.float64)
    return a.ctypes.data_as(ctypes.POINTER(ctypes.c_double)), a.size, a


def converge(scene, methods, dts=None, tols=None, t_end=None, set=None,
             repeats=1, ref_rtol=0.0, max_step=0.0, rows=0):
    """`ballfilm converge` on a scene file of any model: every method (a
    name or "name:key=value", e.g. "arkode:table=ARKODE_CASH_KARP_6_4_5")
    at the steps `dts` (fixed-step methods) and tolerances `tols`
    (adaptive ones) against an ARKODE reference (converge.h; mac: the
    same method at a small dt, a self-convergence study, rtol NaN), the state
    compared at `rows` output rows (0: 10).  Returns (table, reference):
    table a structured array with columns method, label, adaptive, order,
    dt, tol, and for every state group G of the model (balls: x, v; the
    film: psi, h, ...) err_G (at T), err_max_G and err_rms_G (over the
    rows), order_G (observed, NaN for a method's first run), then
    invariant_err (the relative change of the energy or of the conserved
    totals), steps, evals, rejected, iterations, wall, status, message;
    reference a dict of the reference run's label, rtol, model, groups
    [(name, unit)], estimated errors err_G and err_max_G, invariant_err,
    max_step, t_end, notes, and its final state, group by group, as G_ref
    (balls: x_ref, v_ref).  Ctrl-C stops the study within a second and
    raises ballfilm.Interrupted; no table is returned."""
    lib = _lib.lib()
    if isinstance(methods, str):
        methods = [methods]
    if not methods:
        raise ValueError("converge needs at least one method")
    marr, nm, mkeep = _lib.cstrings(list(methods), "a method")
    sarr, ns, skeep = _lib.cstrings(_sets(set, None))
    dp, nd, dkeep = _doubles(dts)
    tp, nt, tkeep = _doubles(tols)
    o = _lib.ConvergeOpts(methods=marr, nmethods=nm, dts=dp, ndts=nd,
                          tols=tp, ntols=nt,
                          t_end=float(t_end) if t_end is not None else 0.0,
                          repeats=_lib.cinteger(repeats, "repeats", 1,
                                                _lib.C_INT_MAX),
                          rows=_lib.cinteger(rows, "rows", 0, _lib.C_LONG_MAX),
                          ref_rtol=float(ref_rtol), max_step=float(max_step))
    out = ctypes.POINTER(_lib.ConvergeResult)()
    err = _lib.Err()
    flag = ctypes.c_int(0)  # set by Ctrl-C (_in_thread): the study stops
    o.stop_flag = ctypes.cast(ctypes.pointer(flag), ctypes.c_void_p)
    scene_c = _scene_file(scene)
    st, ctrl_c = _in_thread(lambda: lib.bf_converge_file(
        scene_c, sarr, ns, ctypes.byref(o),
        ctypes.byref(out), ctypes.byref(err)), flag)
    del mkeep, skeep, dkeep, tkeep
    if ctrl_c and not st:  # Ctrl-C after the study's last check
        lib.bf_converge_free(out)
        st = 6
        err.msg = b"ballfilm.converge: interrupted (Ctrl-C)"
    if st == 6:
        raise Interrupted(err.msg.decode(errors="replace"))
    if st:
        e = from_err(err)
        if e.message.startswith("--set"):
            raise _set_words(e, set)
        bad = [m for m in methods if f"method '{m}':" in e.message]
        raise _python_words(e, "methods", bad or list(methods))
    try:
        return _converge_table(lib, out.contents)
    finally:
        lib.bf_converge_free(out)


def _converge_table(lib, r):
    groups = [(r.groups[g].name.decode(), r.groups[g].unit.decode())
              for g in range(r.ngroups)]
    names = [g for g, _ in groups]
    dtype = [("method", "U64"), ("label", "U160"), ("adaptive", bool),
             ("order", int), ("dt", float), ("tol", float)]
    for g in names:
        dtype += [(f"err_{g}", float), (f"err_max_{g}", float),
                  (f"err_rms_{g}", float), (f"order_{g}", float)]
    units = {"method": "", "label": "", "adaptive": "", "order": "1",
             "dt": "s", "tol": "1"}
    for g, u in groups:
        units.update({f"err_{g}": u, f"err_max_{g}": u, f"err_rms_{g}": u,
                      f"order_{g}": "1"})
    units.update({"invariant_err": "1", "steps": "1", "evals": "1",
                  "rejected": "1", "iterations": "1", "wall": "s",
                  "status": "", "message": ""})
    dtype += [("invariant_err", float), ("steps", np.int64),
              ("evals", np.int64), ("rejected", np.int64),
              ("iterations", np.int64), ("wall", float), ("status", "U16"),
              ("message", "U1024")]
    rows = []
    for k in range(r.nrows):
        w = r.rows[k]
        per = []
        for g in range(r.ngroups):
            per += [w.err[g], w.err_max[g], w.err_rms[g], w.order_obs[g]]
        rows.append((r.methods[w.method].decode(), w.label.decode(),
                     bool(w.adaptive), w.order, w.dt, w.tol, *per,
                     w.invariant_err, w.count.steps, w.count.evals,
                     w.count.rejected, w.count.iterations, w.wall,
                     lib.bf_status_name(w.status).decode(),
                     w.msg.decode(errors="replace")))
    ref = {"label": r.ref_label.decode(), "rtol": r.ref_rtol,
           "model": r.model.decode(), "groups": groups,
           "invariant": r.invariant.decode(),
           "invariant_err": r.ref_invariant_err, "max_step": r.max_step,
           "t_end": r.t_end, "notes": r.notes.decode(errors="replace")}
    off = 0
    for g, name in enumerate(names):
        ref[f"err_{name}"] = r.ref_err[g]
        ref[f"err_max_{name}"] = r.ref_err_max[g]
        n = r.groups[g].n
        ref[f"{name}_ref"] = np.array(r.ref_state[off:off + n])
        off += n
    return Table(rows, dtype, units), ref


def _vary_specs(vary):
    """["key=a:b:n" or "key=v1,v2"] from a dict {key: values} or a list."""
    if isinstance(vary, str):
        return [vary]
    if hasattr(vary, "items"):
        specs = []
        for k, v in vary.items():
            if isinstance(v, str):
                specs.append(f"{k}={v}")
            else:
                specs.append(f"{k}=" + ",".join(repr(float(x)) for x in v))
        return specs
    return list(vary)


def sweep(scene, vary, dir, set=None, retry_failed=False):
    """`ballfilm sweep` in this process, serially: one run of the scene
    file for every combination of the varied keys (vary: {"ball.1.mass":
    [0.8, 1.0, 1.2]} or {"ball.1.mass": "0.5:2:16"}), each in
    dir/case_NNNNN.h5, the summary in dir/summary.h5 and summary.csv.
    Cases finished by an earlier call are not run again, except those
    that failed to write (status "io": a full disk), which are; with
    retry_failed, every failed case is run again.  Returns a
    structured array, one row per case: index, one column per varied key,
    status, wall, lyapunov, map_points, map_fill, energy_error, steps,
    message.  Ctrl-C stops the running case (it is run again next time)
    and raises ballfilm.Interrupted."""
    lib = _lib.lib()
    specs = _vary_specs(vary)
    varr, nv, vkeep = _lib.cstrings(specs, "vary")
    sarr, ns, skeep = _lib.cstrings(_sets(set, None))
    sw = _lib.Sweep()
    err = _lib.Err()
    if lib.bf_sweep_init(ctypes.byref(sw), _scene_file(scene), sarr,
                         ns, varr, nv, _lib.cpath(dir, "dir"),
                         ctypes.byref(err)):
        e = from_err(err)
        if "--set: error: " in e.message:
            raise _set_words(e, set)
        raise _python_words(e, "vary", _vary_arg(vary, e.message))
    flag = ctypes.c_int(0)
    sw.stop_flag = ctypes.pointer(flag)
    rows = (_lib.SweepRow * max(sw.ncases, 1))()
    keys = [sw.axis[a].key.decode() for a in range(sw.naxis)]

    retry = 1 if retry_failed else 0  # bf_sweep_retry: failed, or I/O only

    def all_cases():
        for k in range(sw.ncases):
            if not lib.bf_sweep_case_pending(ctypes.byref(sw), k, retry,
                                             ctypes.byref(rows[k])):
                continue
            st = lib.bf_sweep_run_case(ctypes.byref(sw), k,
                                       ctypes.byref(rows[k]), ctypes.byref(err))
            if st:
                return st
        return lib.bf_sweep_write_summary(ctypes.byref(sw), rows,
                                          ctypes.byref(err))

    try:
        with _StopOnSigint(flag) as stop:
            st, ctrl_c = _in_thread(all_cases, flag)
            ctrl_c = ctrl_c or stop.seen
        if st == 6 or ctrl_c:
            raise Interrupted(err.msg.decode(errors="replace") or
                              "sweep interrupted", os.fspath(dir))
        if st:
            raise from_err(err)
        dtype = [("index", np.int64)] + [(k, float) for k in keys] + [
            ("status", "U16"), ("wall", float), ("lyapunov", float),
            ("map_points", float), ("map_fill", float),
            ("energy_error", float), ("steps", np.int64), ("message", "U512")]
        table = []
        for k in range(sw.ncases):
            w = rows[k]
            table.append((w.index, *[w.values[a] for a in range(sw.naxis)],
                          lib.bf_status_name(w.status).decode(), w.wall,
                          w.lyapunov, w.map_points, w.map_fill,
                          w.energy_error, w.steps,
                          w.message.decode(errors="replace")))
        return Table(table, dtype, _sweep_units(dir, keys))
    finally:
        lib.bf_sweep_free(ctypes.byref(sw))
        del vkeep, skeep




def _vary_arg(vary, message):
    """The part of `vary` a message of the library names (the whole of
    it when none)."""
    if hasattr(vary, "items"):
        for k, v in vary.items():
            if f"{k}=" in message or f"--vary {k}:" in message:
                return {k: v}
    return vary


def _sweep_units(dir, keys):
    """The sweep table's units: the varied keys' from summary.h5's
    /params (column_units), the others fixed."""
    units = {"index": "", "status": "", "wall": "s", "lyapunov": "s-1",
             "map_points": "1", "map_fill": "1", "energy_error": "1",
             "steps": "1", "message": ""}
    try:
        from .result import load
        cu = load(os.path.join(os.fspath(dir), "summary.h5")) \
            .column_units.get("params", [])
    except (OSError, KeyError):
        cu = []
    for i, k in enumerate(keys):
        units[k] = cu[i] if i < len(cu) else ""
    return units
