"""springdyn's compiled kernels: one decorator, a disk cache that is right, a word while compiling.

Every numba kernel of springdyn is made by :func:`kernel` (the pattern of ``fluids.numba``:
small named kernels, each cached, with the exceptions listed).  Three things differ from a
plain ``numba.njit(cache=True)``:

1. **The cache key covers every file a kernel is compiled from.**  numba keys a cached
   function on the content of its *own* file, so an edit to a function it calls in another
   file leaves a stale machine code in place.  Here the stamp is a hash of the kernel's
   *source group*: every ``.py`` file in the kernel's own package folder and in
   ``springdyn/numerics`` (:func:`source_group`).  A kernel may call compiled code from
   nowhere else; ``tests/numerics/test_jit.py`` walks every kernel's globals and checks it.
2. **A cache that cannot be used never stops a run.**  With no writable cache folder the
   kernels compile in memory for the process; an unreadable (corrupt, truncated, foreign)
   cache file is dropped and its kernel compiles again.  One line on stderr says so, once
   (:func:`notices`).
3. **The user hears about a compilation before waiting for it.**  :func:`compiling` wraps
   the call of an engine: when numba starts to compile (a cache miss), one line on stderr
   says what compiles, about how long it takes and that it happens once per machine and
   version.  Silent when everything loads from the cache, and after ``notices(False)``
   (the CLI's ``--quiet``).

Where the cache lives: numba's own rules (``NUMBA_CACHE_DIR`` if set, else the package's
``__pycache__`` folders if writable, else the user's cache folder).

Not cached: kernels with ``inline="always"`` compile into their callers (whose cache holds
them); nothing else is exempt.
"""

from __future__ import annotations

import contextlib
import hashlib
import os
import sys
import threading
import types
from functools import cache
from pathlib import Path

import numba
from numba.core import caching as _nc
from numba.core import event as _ev

__all__ = ["kernel", "twins", "rebind", "call", "source_group", "group_stamp", "compiling", "notices"]

#: springdyn's package folder; kernels live below it.
PACKAGE_DIR = Path(__file__).resolve().parents[1]
#: Folders whose files every kernel's cache stamp includes (the shared numerical pieces).
SHARED_DIRS = (PACKAGE_DIR / "numerics",)

#: Every kernel made by :func:`kernel` (the tests check their sources and caches).
KERNELS: list = []

_state = {"notices": True, "warned": set()}
_lock = threading.Lock()


def notices(on: bool | None = None) -> bool:
    """Switch the one-line compile and cache notices on stderr on or off.

    Parameters
    ----------
    on : bool, optional
        New setting; omitted: only report it.

    Returns
    -------
    bool
        The setting before the call.
    """
    old = _state["notices"]
    if on is not None:
        _state["notices"] = bool(on)
    return old


def _say_once(key: str, text: str) -> None:
    with _lock:
        if key in _state["warned"]:
            return
        _state["warned"].add(key)
    if _state["notices"]:
        print(f"springdyn: {text}", file=sys.stderr, flush=True)


def source_group(py_file) -> tuple:
    """The source files whose content keys the cache of a kernel defined in ``py_file``.

    Parameters
    ----------
    py_file : str or Path
        The kernel's module file.

    Returns
    -------
    tuple of Path
        Sorted ``.py`` files of the module's own folder and of :data:`SHARED_DIRS`.
    """
    folders = {Path(py_file).resolve().parent, *SHARED_DIRS}
    return tuple(sorted(p for d in folders for p in d.glob("*.py")))


@cache
def _stamp_of(files: tuple, stats: tuple) -> str:
    h = hashlib.sha256()
    for f in files:
        h.update(str(f.relative_to(PACKAGE_DIR)).encode())
        h.update(f.read_bytes())
    return h.hexdigest()


def group_stamp(py_file) -> str:
    """Content hash [-] of :func:`source_group` of ``py_file`` (the kernels' cache stamp).

    Parameters
    ----------
    py_file : str or Path
        The kernel's module file.
    """
    files = source_group(py_file)
    stats = tuple((os.stat(f).st_mtime_ns, os.stat(f).st_size) for f in files)
    return _stamp_of(files, stats)


class _GroupStamp:
    """Locator mixin: the source stamp is the hash of the whole source group."""

    def get_source_stamp(self):
        return group_stamp(self._py_file)


class _UserProvided(_GroupStamp, _nc.UserProvidedCacheLocator):
    pass


class _InTree(_GroupStamp, _nc.InTreeCacheLocator):
    pass


class _UserWide(_GroupStamp, _nc.UserWideCacheLocator):
    pass


class _Impl(_nc.CompileResultCacheImpl):
    _locator_classes = [_UserProvided, _InTree, _UserWide]


class _Cache(_nc.FunctionCache):
    """numba's function cache with the group stamp, and never fatal: a file that cannot be
    read or written makes this kernel compile in memory (said once)."""

    _impl_class = _Impl

    def load_overload(self, sig, target_context):
        try:
            return super().load_overload(sig, target_context)
        except Exception as exc:  # a corrupt, truncated or foreign cache file: drop its entries
            try:
                self.flush()
                what = "its entries were dropped and the kernels compile again"
            except Exception:
                self.disable()
                what = "the kernels compile in memory for this run"
            _say_once(
                "cache-read", f"the compile cache in {self.cache_path} could not be read ({type(exc).__name__}): {what}"
            )
            return None

    def save_overload(self, sig, data):
        try:
            super().save_overload(sig, data)
        except Exception as exc:  # the folder became unwritable, the disk is full, ...
            self.disable()
            _say_once(
                "cache-write",
                f"the compile cache in {self.cache_path} could not be written "
                f"({type(exc).__name__}); the engines compile in memory for this run",
            )


#: numba options of every kernel unless a kernel says otherwise: NumPy's error model (a
#: division by zero gives inf/NaN, which the engines check, instead of an exception).
DEFAULTS = dict(error_model="numpy")


def kernel(function=None, **options):
    """Compile ``function`` with numba as a springdyn kernel (decorator).

    Parameters
    ----------
    function : callable, optional
        The plain-Python kernel; omitted, a decorator taking it is returned.
    **options
        Options of :func:`numba.njit` (``fastmath``, ``nogil``, ``inline``, ...) on top of
        :data:`DEFAULTS`.  ``cache`` is not an option: every kernel is cached as the module
        docstring says.

    Returns
    -------
    numba dispatcher
        The kernel; its plain-Python original is ``.py_func``.
    """
    if function is None:
        return lambda f: kernel(f, **options)
    opts = {**DEFAULTS, **options}
    opts.pop("cache", None)
    dispatcher = numba.njit(**opts)(function)
    if opts.get("inline", "never") == "never":
        try:
            dispatcher._cache = _Cache(dispatcher.py_func)
        except Exception as exc:  # no writable cache folder anywhere
            _say_once(
                "cache-none", f"no writable compile cache folder ({exc}); the engines compile in memory for this run"
            )
    KERNELS.append(dispatcher)
    return dispatcher


def twins(namespace: dict, names, **options) -> dict:
    """Compiled twins of plain-Python functions that call each other, each inlined where it is called.

    The functions stay plain Python (the NumPy / SciPy references run them as they are);
    their twins are the same code with globals in which every named function is replaced
    by its twin, compiled with ``inline="always"``: numba inlines them before typing, which
    types far less than inlining registered overloads (``register_jitable``) after it.

    Parameters
    ----------
    namespace : dict
        The module's globals (``globals()``).
    names : iterable of str
        The functions to twin, callees first (a function the module imported from another
        module also sees the names only that module defines, e.g. its constants).
    **options
        Options of :func:`kernel` for every twin.

    Returns
    -------
    dict
        Name -> twin; ``"__globals__"``: the twins' shared globals, for further kernels
        (:func:`kernel` with ``namespace=``).
    """
    g = dict(namespace)
    out = {"__globals__": g}
    for name in names:
        fn = namespace[name]
        if fn.__globals__ is not namespace:  # imported: the names only its module defines (constants)
            for key, value in fn.__globals__.items():
                g.setdefault(key, value)
        copy = types.FunctionType(fn.__code__, g, fn.__name__, fn.__defaults__, fn.__closure__)
        copy.__qualname__ = fn.__qualname__
        copy.__module__ = fn.__module__
        copy.__doc__ = fn.__doc__
        twin = kernel(copy, inline="always", **options)
        g[name] = twin
        out[name] = twin
    return out


def rebind(fn, namespace: dict):
    """``fn`` with the globals ``namespace`` (the shared globals of :func:`twins`), so that a
    kernel made from it calls the twins.

    Parameters
    ----------
    fn : callable
        A plain-Python function.
    namespace : dict
        Globals to use.
    """
    copy = types.FunctionType(fn.__code__, namespace, fn.__name__, fn.__defaults__, fn.__closure__)
    copy.__qualname__ = fn.__qualname__
    copy.__module__ = fn.__module__
    copy.__doc__ = fn.__doc__
    return copy


class _NoticeListener(_ev.Listener):
    def __init__(self, text):
        self.text = text
        self.fired = False

    def on_start(self, event):
        # listeners are process-wide: threads that start the same engine together hear each
        # other's compilation, and the line is said once
        if not self.fired:
            self.fired = True
            _say_once("compiling: " + self.text, self.text)

    def on_end(self, event):
        pass


def _call(fn, args):
    return fn(*args)


#: :func:`_call` with a frame of ~5 MB of value stack (code object's ``co_stacksize``).  On
#: CPython 3.11+ the frames of every call live in chunks of a per-thread stack; a chunk is
#: mapped on demand and unmapped when the call that opened it returns.  numba's compiler
#: recurses deeply and crosses a chunk boundary back and forth some hundred thousand times
#: per engine: each crossing maps and unmaps a chunk (measured: a million page faults, 6 s of
#: system time in a 20 s compilation).  Called through this frame, the compilation runs in
#: the big chunk this frame opens, and crosses no boundary.
_call_deep = types.FunctionType(
    _call.__code__.replace(co_stacksize=_call.__code__.co_stacksize + 640_000), _call.__globals__, "_call_deep"
)


def call(fn, *args, compile_likely: bool = True):
    """Call ``fn(*args)``; when a compilation is likely, on a deep frame (see :data:`_call_deep`).

    Parameters
    ----------
    fn : callable
        A kernel (or any callable).
    *args
        Its arguments.
    compile_likely : bool
        False once this call's variant has run in the process (then a plain call).
    """
    if compile_likely:
        return _call_deep(fn, args)
    return fn(*args)


@contextlib.contextmanager
def compiling(what: str, seconds: float):
    """Announce a compilation that starts inside the block, once, on stderr.

    Parameters
    ----------
    what : str
        What compiles, e.g. ``"the valve engine (spring alone, Dormand-Prince 5(4))"``.
    seconds : float
        About how long it takes on a 2-core machine [s] (measured, docs/performance.md).
    """
    text = (
        f"compiling {what} for this machine: about {seconds:.0f} s, once per machine and springdyn version "
        "(later runs load it from the cache)"
    )
    listener = _NoticeListener(text)
    with _ev.install_listener("numba:compile", listener):
        yield listener
