"""_lib.py: finding and loading libballfilm.so, and the ctypes mirrors of
the public C structs and functions the package calls.

Where the library comes from, first found wins:
  1. $BALLFILM_LIB, the path of a libballfilm.so;
  2. the library inside the package, libballfilm.so.0.2 beside this file
     (pip install puts it there);
  3. the repository's build/libballfilm.so, when this package is the
     repository's python/ballfilm (run `make` first; pip install -e .);
  4. the library `make install` installed next to this package
     (_install.py, written by make install);
  5. the system's loader (libballfilm.so.0.2 on its search path).
Every mirror is checked against the library's own sizes (bf_sizeof) when
the library is loaded, so a package and a library that do not match fail
with a message instead of corrupting memory.
"""
import ctypes
import os

ABI = "0.2"  # the soname's version: libballfilm.so.0.2

c_int, c_long, c_size_t, c_double = (ctypes.c_int, ctypes.c_long,
                                     ctypes.c_size_t, ctypes.c_double)
c_char_p, c_void_p, POINTER = ctypes.c_char_p, ctypes.c_void_p, ctypes.POINTER
c_ull = ctypes.c_ulonglong

BF_ERR_MSG = 1024
BF_SWEEP_MAX_VARY = 8


class Err(ctypes.Structure):
    _fields_ = [("status", c_int), ("msg", ctypes.c_char * BF_ERR_MSG),
                ("section", ctypes.c_char * 64), ("key", ctypes.c_char * 64)]


class SimOpts(ctypes.Structure):
    _fields_ = [("progress", c_int), ("stop_flag", POINTER(c_int)),
                ("stop_after", c_long), ("keep_checkpoint", c_int),
                ("step_by_step", c_int), ("keep_map_points", c_int),
                ("rank", c_int), ("nranks", c_int)]


class StateVar(ctypes.Structure):
    _fields_ = [("name", c_char_p), ("unit", c_char_p), ("n", c_size_t),
                ("data", POINTER(c_double)), ("settable", c_int)]


class Counters(ctypes.Structure):
    _fields_ = [("steps", c_ull), ("evals", c_ull), ("rejected", c_ull),
                ("iterations", c_ull)]


class Results(ctypes.Structure):
    _fields_ = [("has_lyapunov", c_int), ("lyapunov_exponent", c_double),
                ("lyapunov_time", c_double), ("has_return_map", c_int),
                ("map_points", c_size_t), ("map_multi_minima", c_size_t),
                ("map_z", POINTER(c_double)), ("map_v", POINTER(c_double))]


class SweepAxis(ctypes.Structure):
    _fields_ = [("key", ctypes.c_char * 256), ("n", c_size_t),
                ("values", POINTER(c_double))]


class Sweep(ctypes.Structure):
    _fields_ = [("scene_path", ctypes.c_char * 1024),
                ("dir", ctypes.c_char * 1024), ("base", c_void_p),
                ("axis", SweepAxis * BF_SWEEP_MAX_VARY), ("naxis", c_size_t),
                ("ncases", c_size_t), ("stop_flag", POINTER(c_int))]


class SweepRow(ctypes.Structure):
    _fields_ = [("index", c_long), ("values", c_double * BF_SWEEP_MAX_VARY),
                ("status", c_int), ("wall", c_double), ("lyapunov", c_double),
                ("map_points", c_double), ("map_fill", c_double),
                ("energy_error", c_double), ("steps", c_long),
                ("message", ctypes.c_char * 512)]


BF_CONVERGE_MAX_GROUPS = 6


class ConvergeOpts(ctypes.Structure):
    _fields_ = [("methods", POINTER(c_char_p)), ("nmethods", c_size_t),
                ("dts", POINTER(c_double)), ("ndts", c_size_t),
                ("tols", POINTER(c_double)), ("ntols", c_size_t),
                ("t_end", c_double), ("repeats", c_int), ("rows", ctypes.c_long),
                ("ref_rtol", c_double), ("ref_table", c_char_p),
                ("max_step", c_double), ("ref_may_be_compared", c_int),
                ("skip_checks", c_int), ("progress", c_void_p),
                ("stop_flag", c_void_p)]


class ConvergeGroup(ctypes.Structure):
    _fields_ = [("name", ctypes.c_char * 32), ("unit", ctypes.c_char * 16),
                ("n", c_size_t)]


_PER_GROUP = c_double * BF_CONVERGE_MAX_GROUPS


class ConvergeRow(ctypes.Structure):
    _fields_ = [("method", c_int), ("label", ctypes.c_char * 160),
                ("adaptive", c_int), ("order", c_int), ("dt", c_double),
                ("tol", c_double), ("err", _PER_GROUP),
                ("err_max", _PER_GROUP), ("err_rms", _PER_GROUP),
                ("order_obs", _PER_GROUP), ("invariant_err", c_double),
                ("count", Counters), ("wall", c_double),
                ("status", c_int), ("msg", ctypes.c_char * BF_ERR_MSG)]


class ConvergeResult(ctypes.Structure):
    _fields_ = [("scene", ctypes.c_char * 512), ("model", ctypes.c_char * 32),
                ("t_end", c_double), ("out_rows", ctypes.c_long),
                ("nmethods", c_size_t), ("methods", POINTER(c_char_p)),
                ("rows", POINTER(ConvergeRow)), ("nrows", c_size_t),
                ("ngroups", c_size_t),
                ("groups", ConvergeGroup * BF_CONVERGE_MAX_GROUPS),
                ("invariant", ctypes.c_char * 48),
                ("ref_label", ctypes.c_char * 160), ("ref_rtol", c_double),
                ("ref_err", _PER_GROUP), ("ref_err_max", _PER_GROUP),
                ("ref_invariant_err", c_double), ("max_step", c_double),
                ("ref_count", Counters), ("ref_wall", c_double),
                ("nstate", c_size_t), ("ref_state", POINTER(c_double)),
                ("notes", ctypes.c_char * 2048), ("priv", c_void_p)]


MIRRORS = {"bf_err": Err, "bf_sim_opts": SimOpts, "bf_state_var": StateVar,
           "bf_counters": Counters, "bf_results": Results, "bf_sweep": Sweep,
           "bf_sweep_axis": SweepAxis, "bf_sweep_row": SweepRow,
           "bf_converge_opts": ConvergeOpts, "bf_converge_row": ConvergeRow,
           "bf_converge_group": ConvergeGroup,
           "bf_converge_result": ConvergeResult}

# bf_status (*)(void *ctx, bf_sim *sim, bf_err *err)
HEARTBEAT = ctypes.CFUNCTYPE(c_int, c_void_p, c_void_p, POINTER(Err))

# name: (result type, argument types)
FUNCTIONS = {
    "bf_version_string": (c_char_p, []),
    "bf_sizeof": (c_size_t, [c_char_p]),
    "bf_status_name": (c_char_p, [c_int]),
    "bf_catalog_builtin": (c_void_p, []),
    "bf_catalog_new": (c_void_p, [c_void_p]),
    "bf_catalog_free": (None, [c_void_p]),
    "bf_catalog_add_effect": (c_int, [c_void_p, c_void_p, POINTER(Err)]),
    "bf_catalog_add_integrator": (c_int, [c_void_p, c_void_p, POINTER(Err)]),
    "bf_catalog_add_model": (c_int, [c_void_p, c_void_p, POINTER(Err)]),
    "bf_run_load": (c_int, [POINTER(c_void_p), c_void_p, c_char_p,
                            POINTER(c_char_p), c_size_t, POINTER(SimOpts),
                            POINTER(Err)]),
    "bf_run_from_text": (c_int, [POINTER(c_void_p), c_void_p, c_char_p,
                                 c_char_p, POINTER(c_char_p), c_size_t,
                                 POINTER(SimOpts), POINTER(Err)]),
    "bf_run_restart": (c_int, [POINTER(c_void_p), c_void_p, c_char_p,
                               POINTER(c_char_p), c_size_t, POINTER(SimOpts),
                               POINTER(Err)]),
    "bf_run_sim": (c_void_p, [c_void_p]),
    "bf_run_open_output": (c_int, [c_void_p, c_char_p, POINTER(Err)]),
    "bf_run_free": (None, [c_void_p]),
    "bf_sim_run": (c_int, [c_void_p, POINTER(Err)]),
    "bf_sim_close_output": (c_int, [c_void_p, c_int, POINTER(Err),
                                    POINTER(Err)]),
    "bf_sim_heartbeat": (c_int, [c_void_p, c_long, HEARTBEAT, c_void_p,
                                 POINTER(Err)]),
    "bf_sim_state": (c_size_t, [c_void_p, POINTER(StateVar), c_size_t]),
    "bf_sim_set": (c_int, [c_void_p, c_char_p, POINTER(c_double), c_size_t,
                           POINTER(Err)]),
    "bf_sim_steps_done": (c_long, [c_void_p]),
    "bf_sim_steps_total": (c_long, [c_void_p]),
    "bf_sim_time": (c_double, [c_void_p]),
    "bf_sim_dt": (c_double, [c_void_p]),
    "bf_sim_max_energy_error": (c_double, [c_void_p]),
    "bf_sim_energy": (None, [c_void_p, POINTER(c_double), POINTER(c_double)]),
    "bf_sim_counters": (None, [c_void_p, POINTER(Counters)]),
    "bf_sim_results": (None, [c_void_p, POINTER(Results)]),
    "bf_sweep_init": (c_int, [POINTER(Sweep), c_char_p, POINTER(c_char_p),
                              c_size_t, POINTER(c_char_p), c_size_t, c_char_p,
                              POINTER(Err)]),
    "bf_sweep_free": (None, [POINTER(Sweep)]),
    "bf_sweep_case_done": (c_int, [POINTER(Sweep), c_long,
                                   POINTER(SweepRow)]),
    "bf_sweep_case_pending": (c_int, [POINTER(Sweep), c_long, c_int,
                                      POINTER(SweepRow)]),
    "bf_sweep_run_case": (c_int, [POINTER(Sweep), c_long, POINTER(SweepRow),
                                  POINTER(Err)]),
    "bf_sweep_write_summary": (c_int, [POINTER(Sweep), POINTER(SweepRow),
                                       POINTER(Err)]),
    "bf_converge_file": (c_int, [c_char_p, POINTER(c_char_p), c_size_t,
                                 POINTER(ConvergeOpts),
                                 POINTER(POINTER(ConvergeResult)),
                                 POINTER(Err)]),
    "bf_converge_free": (None, [POINTER(ConvergeResult)]),
}


class LibraryError(ImportError):
    """libballfilm.so was not found, or does not match this package."""


def _candidates():
    env = os.environ.get("BALLFILM_LIB")
    if env:
        yield env, "$BALLFILM_LIB"
        return
    here = os.path.dirname(os.path.realpath(__file__))
    inside = os.path.join(here, "libballfilm.so." + ABI)
    if os.path.exists(inside):
        yield inside, "the package's own library (pip install)"
    repo = os.path.normpath(os.path.join(here, "..", "..", "build",
                                         "libballfilm.so"))
    if os.path.exists(repo):
        yield repo, "the repository's build/"
    try:
        from . import _install
        yield _install.LIBRARY, "the installed library (make install)"
    except ImportError:
        pass
    yield "libballfilm.so." + ABI, "the system's library path"


def _load():
    tried = []
    for path, where in _candidates():
        try:
            lib = ctypes.CDLL(path)
        except OSError as e:
            tried.append(f"{where}: {e}")
            continue
        for name, (res, args) in FUNCTIONS.items():
            f = getattr(lib, name)
            f.restype, f.argtypes = res, args
        for cname, mirror in MIRRORS.items():
            size = lib.bf_sizeof(cname.encode())
            if size != ctypes.sizeof(mirror):
                raise LibraryError(
                    f"{path}: struct {cname} has {size} bytes, the package's "
                    f"mirror {ctypes.sizeof(mirror)}: the package and the "
                    "library are of different versions")
        return lib, path
    raise LibraryError("cannot load libballfilm: " + "; ".join(tried) +
                       " (pip install the package, build it with make, or set BALLFILM_LIB to the "
                       "path of libballfilm.so)")


_lib = None
_path = None


def lib():
    """The loaded library (loaded on first use)."""
    global _lib, _path
    if _lib is None:
        _lib, _path = _load()
    return _lib


def path():
    """The file the library was loaded from."""
    lib()
    return _path


C_LONG_MAX = 2 ** (8 * ctypes.sizeof(c_long) - 1) - 1
C_INT_MAX = 2 ** (8 * ctypes.sizeof(c_int) - 1) - 1


def _input_error(message, key=""):
    from .errors import BallfilmError
    return BallfilmError(message, 2, key=key)


def cbytes(value, what, key=""):
    """A str (UTF-8) or a path (the file system's encoding) as the bytes
    of a C string.  C reads up to the first NUL byte, so a value holding
    one would be cut silently: it is refused, naming `what`."""
    b = os.fsencode(value) if isinstance(value, os.PathLike) \
        else value.encode()
    if b"\0" in b:
        raise _input_error(f"{what} {value!r}: holds a NUL byte, where C "
                           f"would cut it", key)
    return b


def cpath(value, what):
    """A file or directory path (str, bytes or os.PathLike) as C bytes."""
    b = os.fsencode(value)
    if b"\0" in b:
        raise _input_error(f"{what} {value!r}: holds a NUL byte, where C "
                           f"would cut it")
    return b


def cinteger(value, what, low, high):
    """A whole number in [low, high] for a C integer argument: ctypes
    would wrap a larger one silently (2**70 steps as 0)."""
    if isinstance(value, bool) or not hasattr(value, "__index__"):
        raise TypeError(f"{what} must be a whole number, not "
                        f"{type(value).__name__}")
    v = value.__index__()
    if not low <= v <= high:
        raise _input_error(f"{what} = {v}: must be between {low} and {high}")
    return v


def cstrings(items, what="a string"):
    """A (char **, n) pair for a list of str, and the keep-alive list."""
    enc = [cbytes(s, what) for s in items]
    arr = (c_char_p * max(len(enc), 1))(*enc)
    return arr, len(enc), enc
