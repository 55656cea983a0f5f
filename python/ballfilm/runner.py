"""runner.py: runs in this process through the C library (ballfilm.run,
ballfilm.restart), catalogs with effects and integrators of one's own
(ballfilm.Catalog), observers written in Python, and Ctrl-C.

How a run goes: the scene (a file, INI text, or a dict of sections) and
the overrides are handed to bf_run_load / bf_run_from_text, which validate
and build it (errors become BallfilmError with the library's message);
initial arrays are set (bf_sim_set); the output file is opened; then
bf_sim_run runs in a worker thread while this thread waits, so that
Ctrl-C (SIGINT, delivered to the main thread) can set the run's stop
flag: the loop stops after its current step, writes its checkpoint and
closes the file, and ballfilm.Interrupted is raised.  While the run and
its closing last, Python's SIGINT handler is replaced by one that only
sets the flag (_StopOnSigint), so that a second Ctrl-C, or one during
the closing, cannot end the call with a bare KeyboardInterrupt.
Observers are heartbeats (sim.h): a Python callable called in the worker
thread with a State, every `every` steps or (every = 0) at output rows.
"""
import ctypes
import os
import shutil
import signal
import tempfile
import threading

import numpy as np

from . import _lib, _progress
from .errors import BallfilmError, Interrupted, from_err
from .result import Result


class Catalog:
    """The built-in models, integrators and effects plus a program's own,
    written in C and compiled into a shared object that links
    libballfilm:

        cat = ballfilm.Catalog()
        cat.add_effect("./libmine.so", "my_effect")   # a bf_effect_type
        ballfilm.run(scene, catalog=cat)

    The symbol names a `const bf_effect_type` (bf_integrator_type,
    bf_model_type) that the object defines; it is used by reference, so
    the object stays loaded as long as the catalog lives."""

    def __init__(self):
        lib = _lib.lib()
        self._ptr = lib.bf_catalog_new(lib.bf_catalog_builtin())
        if not self._ptr:
            raise MemoryError("bf_catalog_new")
        self._objects = []

    def _add(self, kind, library, symbol):
        if not isinstance(symbol, str) or not symbol:
            raise TypeError("symbol must be the name of a descriptor")
        obj = ctypes.CDLL(os.fspath(library))
        try:
            addr = ctypes.addressof(ctypes.c_char.in_dll(obj, symbol))
        except ValueError:
            raise BallfilmError(f"{library}: no symbol '{symbol}'") from None
        self._objects.append(obj)
        err = _lib.Err()
        if getattr(_lib.lib(), "bf_catalog_add_" + kind)(self._ptr, addr,
                                                        ctypes.byref(err)):
            raise from_err(err)

    def add_effect(self, library, symbol):
        self._add("effect", library, symbol)

    def add_integrator(self, library, symbol):
        self._add("integrator", library, symbol)

    def add_model(self, library, symbol):
        self._add("model", library, symbol)

    def __del__(self):
        if getattr(self, "_ptr", None):
            _lib.lib().bf_catalog_free(self._ptr)
            self._ptr = None


class State:
    """What an observer sees of a running sim: .t (s), .step, .dt (s),
    .energy_error (relative, the largest so far), .energy (kinetic,
    potential in erg), and the model's state arrays by name, as copies:
    state["balls/position"]; state.names lists them."""

    def __init__(self, sim):
        lib = _lib.lib()
        self.t = lib.bf_sim_time(sim)
        self.step = lib.bf_sim_steps_done(sim)
        self.dt = lib.bf_sim_dt(sim)
        self.energy_error = lib.bf_sim_max_energy_error(sim)
        kin, pot = ctypes.c_double(), ctypes.c_double()
        lib.bf_sim_energy(sim, ctypes.byref(kin), ctypes.byref(pot))
        self.energy = (kin.value, pot.value)
        self.arrays = state_arrays(sim)
        self.names = list(self.arrays)

    def __getitem__(self, name):
        return self.arrays[name]


def state_arrays(sim):
    """{name: copy of the array} of a sim's state."""
    lib = _lib.lib()
    vars_ = (_lib.StateVar * 64)()
    n = lib.bf_sim_state(sim, vars_, 64)
    out = {}
    for v in vars_[:min(n, 64)]:
        out[v.name.decode()] = np.ctypeslib.as_array(v.data, (v.n,)).copy() \
            if v.n else np.zeros(0)
    return out


def _value(v):
    """A Python value as scene text (floats at full precision)."""
    if isinstance(v, bool):
        return "yes" if v else "no"
    if isinstance(v, float):
        return repr(v)
    if isinstance(v, (list, tuple, np.ndarray)):
        return " ".join(_value(x) for x in
                        (v.tolist() if isinstance(v, np.ndarray) else v))
    if isinstance(v, (int, str, np.integer, np.floating)):
        return str(v) if not isinstance(v, np.floating) else repr(float(v))
    raise TypeError(f"a scene value must be a number, a string, a bool or "
                    f"a list of them, not {type(v).__name__}")


def _refuse_in_text(where, section, key, text, bad):
    """BallfilmError (input) if `text` holds one of the characters `bad`:
    a NUL byte would cut the text where C reads it, a line break would
    start a new line of the scene."""
    for c in bad:
        if c in text:
            what = "a NUL byte" if c == "\0" else "a line break"
            shown = repr(text) if len(text) <= 60 else \
                f"(at character {text.index(c)})"
            raise BallfilmError(f"{where} {shown} holds {what}", 2,
                                section, key)


def _sets(set_, t_end):
    if set_ is None:
        set_ = {}
    if not hasattr(set_, "items"):
        raise TypeError("set must be a dict {'section.key': value}")
    out = []
    for k, v in set_.items():
        if not isinstance(k, str):
            raise TypeError(f"a key of set must be 'section.key', not {k!r}")
        text = _value(v)
        sec, _, key = k.rpartition(".")
        _refuse_in_text(f"set[{k!r}]: the key", sec, key, k, "\0")
        _refuse_in_text(f"set[{k!r}]: the value", sec, key, text, "\0")
        out.append(f"{k}={text}")
    if t_end is not None:
        out.append(f"scene.t_end={_value(float(t_end))}")
    return out


def _set_words(e, set_, t_end=None):
    """A BallfilmError about an override, worded for Python: the library
    says "--set: error: [ball.1] mass: ..." (the command line's option);
    this says "set={'ball.1.mass': -1}: [ball.1] mass: ..."."""
    msg = e.message
    for opt in ("--set (stored): error: ", "--set: error: "):
        if msg.startswith(opt):
            items = dict(set_ or {})
            named = f"{e.section}.{e.key}"
            shown = {named: items[named]} if named in items else items
            arg = f"set={shown!r}"
            if named == "scene.t_end" and named not in items and \
                    t_end is not None:
                arg = f"t_end={t_end!r}"
            e.message = f"{arg}: {msg[len(opt):]}"
            e.args = (e.message,)
            break
    return e


def _scene_file(scene, what="scene"):
    """The path of a scene file as C bytes; BallfilmError (input) when
    there is no such file, naming the shipped scene of that name if
    there is one."""
    b = _lib.cpath(scene, what)
    if not os.path.exists(b):
        p = os.fspath(scene)
        hint = ""
        name = os.path.splitext(os.path.basename(p))[0]
        try:
            from ._share import scenes
            if name in scenes():
                hint = f" (a shipped scene: ballfilm.scene({name!r}))"
        except (OSError, FileNotFoundError):
            pass
        e = BallfilmError(f"{what} {p!r}: no such file{hint}", 2)
        e.file = p
        raise e
    return b


def scene_text(sections):
    """INI text of a dict {section: {key: value}}."""
    lines = []
    for sec, keys in sections.items():
        if not hasattr(keys, "items"):
            raise TypeError(f"section [{sec}] must be a dict of keys")
        _refuse_in_text("a section's name", str(sec), "", str(sec), "\0\n\r")
        lines.append(f"[{sec}]")
        for k, v in keys.items():
            text = _value(v)
            _refuse_in_text(f"[{sec}] the key", str(sec), str(k), str(k),
                            "\0\n\r")
            _refuse_in_text(f"[{sec}] {k}", str(sec), str(k), text, "\0\n\r")
            lines.append(f"{k} = {text}")
    return "\n".join(lines) + "\n"


def _is_text(scene):
    return isinstance(scene, str) and ("\n" in scene or scene.lstrip()
                                       .startswith("["))


class _Observer:
    """A Python callable as a heartbeat; its exception is kept and raised
    again after the run (the run stops with it)."""

    def __init__(self, fn):
        self.fn = fn
        self.error = None
        self.stopped = False
        self.c = _lib.HEARTBEAT(self._call)

    def _call(self, ctx, sim, err):
        try:
            if self.fn(State(sim)) is False:
                self.stopped = True
                return 6  # BF_INTERRUPTED: stop as Ctrl-C does
            return 0
        except BaseException as e:  # noqa: B902 (raised again after the run)
            self.error = e
            msg = f"observer raised {type(e).__name__}: {e}".encode()[:1000]
            err.contents.msg = msg
            err.contents.status = 1
            return 1


class _StopOnSigint:
    """While a call runs and closes: SIGINT sets the run's stop flag and
    is remembered (.seen), instead of raising KeyboardInterrupt wherever
    the main thread happens to be; the handler before is put back at the
    end.  Only when Python's own handler is installed, in the main thread:
    a handler of the program's own is left alone, and an ignored SIGINT
    (a background job of a script) stays ignored."""

    def __init__(self, flag):
        self.flag = flag
        self.seen = False
        self._before = None

    def _on_sigint(self, signum, frame):
        self.seen = True
        self.flag.value = 1

    def __enter__(self):
        if (threading.current_thread() is threading.main_thread() and
                signal.getsignal(signal.SIGINT) is signal.default_int_handler):
            self._before = signal.signal(signal.SIGINT, self._on_sigint)
        return self

    def __exit__(self, *exc):
        if self._before is not None:
            signal.signal(signal.SIGINT, self._before)
            self._before = None
        return False


def _in_thread(fn, flag, tick=None):
    """fn() in a worker thread; Ctrl-C here sets flag (the run's stop
    flag) and waits for the run to stop; tick(), if given, is called
    between the waits (the progress line).  Returns (fn's value, whether
    Ctrl-C came).  The wait is on an Event of our own: a Thread.join that
    KeyboardInterrupt interrupts can leave the thread marked as stopped
    while it still runs (CPython before 3.13)."""
    box, ctrl_c, done = {}, False, threading.Event()

    def work():
        # SIGINT goes to the waiting (main) thread, whose wait it ends at
        # once, never to this one
        signal.pthread_sigmask(signal.SIG_BLOCK, [signal.SIGINT])
        try:
            box["v"] = fn()
        finally:
            done.set()

    t = threading.Thread(target=work, name="ballfilm-run", daemon=True)
    started = False
    while not done.is_set():
        try:
            if not started:
                started = True
                t.start()
            done.wait(0.05)
            if tick is not None:
                tick()
        except KeyboardInterrupt:
            ctrl_c = True
            flag.value = 1
    return box.get("v"), ctrl_c


def _drive(run, lib, flag, output, temp, observers, initial, opened=False,
           progress=False):
    """Set up, run and close one bf_run (its output opened here unless
    `opened`: a restart), with a progress line when `progress`; returns
    the Result (or raises)."""
    sim = lib.bf_run_sim(run)
    err = _lib.Err()
    for name, values in (initial or {}).items():
        a = np.ascontiguousarray(values, dtype=np.float64).ravel()
        if lib.bf_sim_set(sim, _lib.cbytes(name, "initial: the array"),
                          a.ctypes.data_as(ctypes.POINTER(ctypes.c_double)),
                          a.size, ctypes.byref(err)):
            raise from_err(err)
    keep = []
    for fn, every in observers:
        ob = _Observer(fn)
        keep.append(ob)
        if lib.bf_sim_heartbeat(sim, int(every), ob.c, None,
                                ctypes.byref(err)):
            raise from_err(err)
    bar = None
    if progress:
        bar = _progress.Progress()
        if bar.attach(lib, sim, err):
            raise from_err(err)
    if output is not None and not opened and lib.bf_run_open_output(
            run, _lib.cpath(output, "output"), ctypes.byref(err)):
        raise from_err(err)
    with _StopOnSigint(flag) as stop:
        return _run_and_close(lib, sim, flag, stop, output, temp, keep, bar)


def _run_and_close(lib, sim, flag, stop, output, temp, keep, bar=None):
    """Run the sim to its end or stop, close its output and return its
    Result, or raise what ended it (Ctrl-C: ballfilm.Interrupted)."""
    err = _lib.Err()
    status, ctrl_c = _in_thread(lambda: lib.bf_sim_run(sim, ctypes.byref(err)),
                                flag, bar.tick if bar is not None else None)
    if bar is not None:
        bar.finish(lib, sim)
    ctrl_c = ctrl_c or stop.seen
    cerr = _lib.Err()
    cstatus = lib.bf_sim_close_output(sim, status, ctypes.byref(err),
                                      ctypes.byref(cerr))
    result = None
    if output is not None and not cstatus:
        path = os.fspath(output)
        if not os.path.exists(path):
            path += ".part"
        result = Result(path, eager=temp)
    for ob in keep:
        if ob.error is not None:
            raise ob.error
    if cstatus:
        raise from_err(cerr, result)
    if status == 6 and (ctrl_c or not any(o.stopped for o in keep)):
        ck = os.fspath(output) + ".ckpt" if output is not None else None
        raise Interrupted(err.msg.decode(errors="replace"), output,
                          ck if ck and os.path.exists(ck) else None, result)
    if status and status != 6:
        raise from_err(err, result)
    if result is None:
        result = _summary(sim, status)
    return result


def _summary(sim, status):
    """A run without an output file: what the sim itself knows."""
    lib = _lib.lib()
    c = _lib.Counters()
    lib.bf_sim_counters(sim, ctypes.byref(c))
    r = Result.__new__(Result)
    r.path, r._cache, r.attrs = None, {}, {}
    r.units, r.descriptions, r.shapes = {}, {}, {}
    r.scene_text = r.scene_file = r.version = r.message = ""
    r.params, r.param_units, r.defaults = {}, {}, set()
    r.status = _lib.lib().bf_status_name(status).decode()
    r.counters = {"steps_done": lib.bf_sim_steps_done(sim),
                  "t_final": lib.bf_sim_time(sim),
                  "force_evaluations": c.evals, "rejected_steps": c.rejected,
                  "iterations": c.iterations}
    e = lib.bf_sim_max_energy_error(sim)
    r.energy_error = None if e != e else e
    r.state = state_arrays(sim)
    return r


def _opts(flag):
    o = _lib.SimOpts()
    o.stop_flag = ctypes.pointer(flag)
    return o


def _observers(observer, every):
    if observer is None:
        return []
    obs = observer if isinstance(observer, (list, tuple)) else [observer]
    for ob in obs:
        if not callable(ob):
            raise TypeError("observer must be callable (or a list of them)")
    every = _lib.cinteger(every, "every", 0,
                          _lib.C_LONG_MAX)
    return [(ob, every) for ob in obs]


class _Call:
    """What a call that builds a bf_run hands the library: the catalog,
    the overrides as char **, the options with the run's stop flag, an
    error to fill and the handle to receive (kept alive together)."""

    def __init__(self, set_, t_end, observer, every, catalog):
        self.lib = lib = _lib.lib()
        self.set_, self.t_end = set_, t_end
        self.obs = _observers(observer, every)
        self.cat = catalog._ptr if catalog is not None \
            else lib.bf_catalog_builtin()
        self.flag = ctypes.c_int(0)
        self.opts = _opts(self.flag)
        self.sets, self.nsets, self._keep = _lib.cstrings(_sets(set_, t_end))
        self.err = _lib.Err()
        self.handle = ctypes.c_void_p()

    def args(self):
        """handle, catalog ... sets, nsets, opts, err around the scene's."""
        return ((ctypes.byref(self.handle), self.cat),
                (self.sets, self.nsets, ctypes.byref(self.opts),
                 ctypes.byref(self.err)))

    def built(self, status):
        if status:
            raise _set_words(from_err(self.err), self.set_, self.t_end)


def run(scene, set=None, t_end=None, output=None, observer=None, every=0,
        initial=None, catalog=None, name="scene", progress=False):
    """Run a scene in this process and return its Result (ballfilm.load).

    scene     the path of a scene file, INI text, or a dict
              {section: {key: value}}
    set       overrides {"section.key": value} (like --set)
    t_end     shorthand for set={"scene.t_end": t_end}
    output    the HDF5 file to write; None: a temporary file, read into
              memory and removed
    observer  a callable (or a list) called with a ballfilm.State every
              `every` steps, or at every output row when every = 0; a
              return value of False stops the run (status "interrupted")
    initial   initial arrays {"film/h": array, "balls/position": array}
              set before the first step (bf_sim_set)
    catalog   a ballfilm.Catalog with effects or integrators of one's own
    name      the name of INI text or a dict in messages
    progress  True: a progress line (bar, simulated time of t_end,
              steps/s, time left) on stderr, or in a Jupyter notebook
              one line of output updated in place

    Bad scenes, keys and values raise BallfilmError with the library's
    message (FILE:LINE, section and key); a run that goes unstable raises
    it too, with .result holding the rows up to the last good step.
    Ctrl-C stops the run cleanly and raises ballfilm.Interrupted (its
    checkpoint written when there is an output file; ballfilm.restart
    continues it).
    """
    c = _Call(set, t_end, observer, every, catalog)
    pre, post = c.args()
    if isinstance(scene, dict):
        scene = scene_text(scene)
    if _is_text(scene):
        _refuse_in_text(f"the scene text {name!r}", "", "", scene, "\0")
        c.built(c.lib.bf_run_from_text(*pre, _lib.cbytes(name, "name"),
                                       scene.encode(), *post))
    elif isinstance(scene, (str, os.PathLike)):
        c.built(c.lib.bf_run_load(*pre, _scene_file(scene), *post))
    else:
        raise TypeError("scene must be a path, INI text or a dict of sections")
    tmpdir = None
    try:
        temp = output is None
        if temp:
            tmpdir = tempfile.mkdtemp(prefix="ballfilm-")
            output = os.path.join(tmpdir, "run.h5")
        result = _drive(c.handle, c.lib, c.flag, output, temp, c.obs, initial,
                        progress=progress)
        if temp and result.path is not None:
            result.forget_file()
        return result
    except Interrupted:
        tmpdir = None  # the checkpoint lives there: keep it
        raise
    except BallfilmError as e:
        if temp and e.result is not None and e.result.path is not None:
            e.result.forget_file()
        raise
    finally:
        c.lib.bf_run_free(c.handle)
        if tmpdir:
            shutil.rmtree(tmpdir, ignore_errors=True)


def restart(output, set=None, t_end=None, observer=None, every=0,
            catalog=None, progress=False):
    """Continue the run of `output` from its checkpoint (output.ckpt) and
    return its Result; only keys that change when and how often a run
    writes may be set (t_end, output_every, ...)."""
    c = _Call(set, t_end, observer, every, catalog)
    pre, post = c.args()
    c.built(c.lib.bf_run_restart(*pre, _lib.cpath(output, "output"), *post))
    try:
        return _drive(c.handle, c.lib, c.flag, output, False, c.obs, None,
                      opened=True, progress=progress)
    finally:
        c.lib.bf_run_free(c.handle)
