"""Atomic writers for the tables springdyn produces (CSV, JSON).

Nothing is ever left half-written: each writer writes a temporary file in the target
folder and renames it over the target (``os.replace`` is atomic on POSIX and Windows).
CSV and JSON are SI, with the unit in the column name (``force_N``).
"""

from __future__ import annotations

import contextlib
import csv
import json
import math
import os
import re
import tempfile
from collections.abc import Iterator, Mapping
from pathlib import Path

import numpy as np

__all__ = [
    "dumps_toml",
    "atomic_path",
    "atomic_open",
    "output_set",
    "direct_outputs",
    "check_output_file",
    "check_output_folder",
    "write_csv",
    "write_json",
    "read_csv_columns",
    "to_jsonable",
    "NonFiniteOutputError",
]

#: Longest file name (one path component) most file systems take [bytes].
MAX_NAME_BYTES = 255


class NonFiniteOutputError(ValueError):
    """A NaN or inf reached an output writer (names where): a bug or an unhandled case."""


class _OutputSet:
    """Files written inside :func:`output_set`: temporaries renamed together at the end."""

    def __init__(self):
        self.pending: dict[Path, Path] = {}  # final path -> temporary

    def add(self, tmp: Path, path: Path) -> None:
        old = self.pending.pop(path.resolve(), None)
        if old is not None:
            with contextlib.suppress(FileNotFoundError):
                old.unlink()
        self.pending[path.resolve()] = tmp

    def commit(self) -> None:
        for path, tmp in list(self.pending.items()):
            try:
                os.replace(tmp, path)
            except OSError as exc:  # named by the file it was to become, not the temporary
                raise _naming_output(exc, tmp, path) from exc
            del self.pending[path]

    def discard(self) -> None:
        for tmp in self.pending.values():
            with contextlib.suppress(FileNotFoundError):
                tmp.unlink()
        self.pending.clear()


_SETS: list[_OutputSet] = []


@contextlib.contextmanager
def output_set():
    """Group the files written inside into one output set.

    Every :func:`atomic_path` inside writes its temporary file as usual but renames it
    onto its final name only when the block ends without an error, all files one after
    the other; on an error, ``KeyboardInterrupt`` or ``SystemExit`` every temporary is
    removed and no final file is touched.  Sets nest: an inner set hands its files to the
    outer one.
    """
    current = _OutputSet()
    _SETS.append(current)
    try:
        yield current
    except BaseException:
        _SETS.remove(current)
        current.discard()
        raise
    _SETS.remove(current)
    if _SETS and _SETS[-1] is not None:
        for path, tmp in current.pending.items():
            _SETS[-1].add(tmp, path)
    else:
        try:
            current.commit()
        except BaseException:
            current.discard()
            raise


@contextlib.contextmanager
def direct_outputs():
    """Inside an :func:`output_set`, write files onto their final names at once (for a job
    that reads back what it wrote, such as the report, which builds in a temporary folder
    of its own and renames that folder at the end)."""
    _SETS.append(None)
    try:
        yield
    finally:
        _SETS.pop()


#: A temporary of :func:`atomic_path` older than this [s] whose process number is alive (it
#: may be another process's, the number reused: a container's processes get the same low
#: numbers run after run) was left by a killed run: the next write in its folder removes it.
STALE_TEMPORARY_SECONDS = 86400.0
#: A temporary of earlier versions (``.<name>.XXXXXXXX<suffix>``, no process number) older than
#: this [s]: the next write of the same file removes it.
LEGACY_TEMPORARY_SECONDS = 3600.0
#: The temporaries of :func:`atomic_path`: ``.<name>.<pid>-<8 characters>.tmp<suffix>`` (the
#: final name, the writing process's number, :func:`tempfile.mkstemp`'s random part, the
#: final name's suffix kept for writers that read it, NetCDF and PNG).
TEMPORARY_NAME = re.compile(r"^\.(?P<name>.+)\.(?P<pid>\d+)-[a-z0-9_]{8}\.tmp(?P<suffix>\.[^.]*)?$")
#: When this process started [s since the epoch] (a temporary with this process's number that
#: is older was left by an earlier process of the same number).
_STARTED = __import__("time").time()
#: Folders swept of stale temporaries by this process (once a folder: a study's chunk folder
#: takes 400,000 writes).
_SWEPT: set = set()


def temporary_name(path: Path) -> str:
    """The prefix :func:`atomic_path` gives its temporary of ``path`` (``.<name>.<pid>-``)."""
    return f".{path.name[:100]}.{os.getpid()}-"


def _alive(pid: int) -> bool:
    """Whether a process of number ``pid`` runs (on this machine)."""
    if pid <= 0:
        return False
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except (PermissionError, OSError):
        return True  # another user's process, or a number we may not ask about: keep
    return True


def sweep_temporaries(folder: Path) -> list[Path]:
    """Remove the temporaries killed runs left in ``folder`` (:data:`TEMPORARY_NAME`): one whose
    process is gone, one of this process's number older than this process, one older than
    :data:`STALE_TEMPORARY_SECONDS`.  A live process's temporary is kept.  Returns those removed.

    Parameters
    ----------
    folder : Path
        The folder [-].
    """
    import time

    removed = []
    now = time.time()
    try:
        entries = list(os.scandir(folder))
    except OSError:
        return removed
    for entry in entries:
        found = TEMPORARY_NAME.match(entry.name)
        if not found:
            continue
        with contextlib.suppress(OSError):
            if not entry.is_file(follow_symlinks=False):
                continue
            pid, age = int(found["pid"]), now - entry.stat(follow_symlinks=False).st_mtime
            if pid == os.getpid():
                stale = now - age < _STARTED - 1.0  # written before this process started
            else:
                stale = not _alive(pid) or age > STALE_TEMPORARY_SECONDS
            if stale:
                os.unlink(entry.path)
                removed.append(Path(entry.path))
    return removed


def _remove_stale_temporaries(path: Path, suffix: str) -> None:
    """Remove the temporaries killed runs left in ``path``'s folder: this version's
    (:func:`sweep_temporaries`, once a folder and process) and an earlier version's of the same
    file (``.<name>.XXXXXXXX<suffix>``, older than :data:`LEGACY_TEMPORARY_SECONDS`)."""
    import time

    folder = path.parent if str(path.parent) else Path(".")
    where = os.path.abspath(folder)
    if where not in _SWEPT:
        _SWEPT.add(where)
        sweep_temporaries(folder)
    now = time.time()
    try:
        candidates = list(folder.glob(f".{glob_escape(path.name[:100])}.????????{glob_escape(suffix)}"))
    except OSError:
        return
    for old in candidates:
        with contextlib.suppress(OSError):
            if old.is_file() and now - old.stat().st_mtime > LEGACY_TEMPORARY_SECONDS:
                old.unlink()


def glob_escape(text: str) -> str:
    """``text`` with the glob characters escaped."""
    import glob

    return glob.escape(text)


def _naming_output(exc: OSError, tmp, path: Path) -> OSError:
    """``exc`` (raised while writing ``tmp``, the temporary of ``path``) naming ``path``: a
    message names the file the user asked for, not the hidden temporary (issue 40).  Errors of
    springdyn's own kinds (standard output's) and errors about other files are returned as
    they are."""
    if type(exc).__module__ != "builtins":
        return exc
    named = None if exc.filename is None else str(exc.filename)
    if named is not None and named != str(tmp) and not Path(named).name.startswith(temporary_name(path)):
        return exc  # about another file (a folder that cannot be made): named already
    text = exc.strerror or str(exc)
    for name in {str(tmp), named} - {None, "None"}:
        text = text.replace(name, str(path))
    if exc.errno is None:
        new = OSError(text)
        new.filename = str(path)
        return new
    return OSError(exc.errno, text, str(path))


@contextlib.contextmanager
def atomic_path(path: str | os.PathLike, suffix: str | None = None) -> Iterator[Path]:
    """Yield a temporary path beside ``path``; rename it onto ``path`` on success.

    On an exception the temporary file is removed and ``path`` is left untouched.  Inside
    :func:`output_set` the rename waits for the end of the set.  The temporary is
    ``.<name>.<pid>-XXXXXXXX.tmp<suffix>`` (:data:`TEMPORARY_NAME`); the first write of a
    process in a folder removes the temporaries killed runs left there
    (:func:`sweep_temporaries`).  An :class:`OSError` names ``path``, not the temporary.
    """
    path = Path(path)
    tmp = None
    try:
        if path.parent and not path.parent.exists():
            path.parent.mkdir(parents=True, exist_ok=True)
        _remove_stale_temporaries(path, suffix or path.suffix)
        fd, tmp = tempfile.mkstemp(
            prefix=temporary_name(path), suffix=f".tmp{suffix or path.suffix}", dir=path.parent or "."
        )
        os.close(fd)
    except OSError as exc:
        raise _naming_output(exc, tmp, path) from exc
    tmp = Path(tmp)
    try:
        yield tmp
        umask = os.umask(0)
        os.umask(umask)
        os.chmod(tmp, 0o666 & ~umask)  # mkstemp makes 0600 files; give the usual permissions
        if _SETS and _SETS[-1] is not None:
            _SETS[-1].add(tmp, path)
        else:
            os.replace(tmp, path)
    except BaseException as exc:
        with contextlib.suppress(FileNotFoundError):
            tmp.unlink()
        if isinstance(exc, OSError):
            new = _naming_output(exc, tmp, path)
            if new is not exc:
                raise new from exc
        raise


def _output_name(path, name: str, what: str) -> Path:
    """``path`` as a :class:`Path`, checked as every output name is: given (not empty), and no
    part of it longer than :data:`MAX_NAME_BYTES` (``what``: "file" or "folder", for messages)."""
    from .errors import InputError

    if path is None or str(path).strip() == "":
        raise InputError(f"{name}: an empty {what} name was given")
    path = Path(path)
    for part in path.parts:
        if len(part.encode("utf-8", "surrogateescape")) > MAX_NAME_BYTES:
            raise InputError(f"{name}: the file name is longer than {MAX_NAME_BYTES} bytes")
    return path


def _check_parent(path: Path, name: str) -> None:
    from .errors import InputError

    parent = path.parent if str(path.parent) else Path(".")
    if not parent.exists():
        raise InputError(f"{name} = {str(path)!r}: the folder {str(parent)!r} does not exist")
    if not parent.is_dir():
        raise InputError(f"{name} = {str(path)!r}: {str(parent)!r} is a file, not a folder")
    if not os.access(parent, os.W_OK | os.X_OK):
        raise InputError(f"{name} = {str(path)!r}: cannot write into the folder {str(parent)!r} (no permission)")


def check_output_file(path, name: str) -> Path:
    """Check before any work that a file can be written at ``path`` (``name``: the option or argument).

    Parameters
    ----------
    path : str or path-like
        The output file.
    name : str
        Its option or argument name, for messages.
    """
    from .errors import InputError

    path = _output_name(path, name, "file")
    if path.is_dir():
        raise InputError(f"{name} = {str(path)!r} is a folder: give a file name such as {str(path / 'out')!r}")
    _check_parent(path, name)
    return path


def check_output_folder(path, name: str) -> Path:
    """Check before any work that ``path`` is a folder, or can be made one.

    Parameters
    ----------
    path : str or path-like
        The output folder.
    name : str
        Its option or argument name, for messages.
    """
    from .errors import InputError

    path = _output_name(path, name, "folder")
    if path.exists() and not path.is_dir():
        raise InputError(f"{name} = {str(path)!r} is an existing file: give a folder (new or existing)")
    if path.is_dir():
        if not os.access(path, os.W_OK | os.X_OK):
            raise InputError(f"{name} = {str(path)!r}: cannot write into this folder (no permission)")
        return path
    _check_parent(path, name)
    return path


@contextlib.contextmanager
def atomic_open(path: str | os.PathLike, mode: str = "w", **kwargs):
    """Open a temporary file for writing; it replaces ``path`` when closed without error."""
    with atomic_path(path) as tmp:
        with open(tmp, mode, **kwargs) as fh:
            yield fh


def to_jsonable(obj):
    """Convert numpy scalars/arrays (and nested containers) to JSON-ready Python objects.

    A NaN or inf raises :class:`NonFiniteOutputError` naming the key: springdyn never
    writes one (a figure that does not apply is ``None`` with a note saying why).
    """
    if isinstance(obj, Mapping):
        out = {}
        for k, v in obj.items():
            try:
                out[str(k)] = to_jsonable(v)
            except NonFiniteOutputError as exc:
                raise NonFiniteOutputError(f"{exc} at key {k!r}") from None
        return out
    if hasattr(obj, "to_dict") and callable(obj.to_dict):
        return to_jsonable(obj.to_dict())
    if isinstance(obj, (list, tuple)):
        return [to_jsonable(v) for v in obj]
    if isinstance(obj, np.ndarray):
        return to_jsonable(obj.tolist())
    if isinstance(obj, (np.bool_, bool)):
        return bool(obj)
    if isinstance(obj, (np.integer,)):
        return int(obj)
    if isinstance(obj, (np.floating, float)):
        f = float(obj)
        if not math.isfinite(f):
            raise NonFiniteOutputError(f"{f} in an output")
        return f
    if isinstance(obj, Path):
        return str(obj)
    return obj


def write_json(path: str | os.PathLike, data) -> Path:
    """Write ``data`` as indented JSON, atomically."""
    with atomic_open(path, "w", encoding="utf-8") as fh:
        json.dump(to_jsonable(data), fh, indent=2)
        fh.write("\n")
    return Path(path)


def write_csv(path: str | os.PathLike, columns: Mapping[str, object]) -> Path:
    """Write equal-length columns to CSV, atomically.

    Parameters
    ----------
    path : path-like
        Output file.
    columns : mapping of str to array-like
        Column name (with the SI unit in it, e.g. ``force_N``) to values.  Scalars are
        broadcast.
    """
    names = list(columns)
    arrays = [np.atleast_1d(np.asarray(columns[n])) for n in names]
    n = max((a.shape[0] for a in arrays), default=0)
    arrays = [np.broadcast_to(a, (n,)) if a.shape[0] == 1 else a for a in arrays]
    for name, a in zip(names, arrays):
        if a.shape[0] != n:
            raise ValueError(f"column {name} has {a.shape[0]} rows, expected {n}")
    with atomic_open(path, "w", newline="", encoding="utf-8") as fh:
        w = csv.writer(fh)
        w.writerow(names)
        for i in range(n):
            try:
                w.writerow([_cell(a[i]) for a in arrays])
            except NonFiniteOutputError as exc:
                bad = next(name for name, a in zip(names, arrays) if not _finite(a[i]))
                raise NonFiniteOutputError(f"{exc}: column {bad!r}, row {i + 1} of {path}") from None
    return Path(path)


def _finite(v) -> bool:
    return not isinstance(v, (float, np.floating)) or math.isfinite(v)


def _cell(v):
    if isinstance(v, (float, np.floating)):
        if not math.isfinite(v):
            raise NonFiniteOutputError(f"{v} in a CSV cell")
        return repr(float(v))
    if isinstance(v, (np.bool_, bool)):
        return int(bool(v))
    return v


#: Largest CSV file springdyn reads [bytes] (a long rig record is a few tens of MB).
MAX_CSV_BYTES = 500_000_000


#: A measured-data cell: a plain decimal number, optionally with an exponent (no digit
#: underscores, hexadecimal or words, which Python's float() would take).
PLAIN_NUMBER = re.compile(r"[+-]?(\d+\.?\d*|\.\d+)([eE][+-]?\d+)?")


def read_csv_columns(path: str | os.PathLike) -> dict[str, np.ndarray]:
    """Read a numeric CSV with a header row into a dict of float arrays.

    Parameters
    ----------
    path : str or path-like
        The CSV file (UTF-8, a header row, then numbers).

    Raises
    ------
    springdyn.core.errors.InputError
        Missing file, a folder, an empty or binary or non-UTF-8 file, duplicate or empty
        column names, a row of the wrong length, or a cell that is not a finite number
        (file, row and column named).
    """
    from .errors import InputError
    from .params import decode_utf8, read_text_file

    path, data = read_text_file(path, "CSV", max_bytes=MAX_CSV_BYTES)
    text = decode_utf8(path, data, "CSV")
    try:
        rows = [(n, r) for n, r in enumerate(csv.reader(text.splitlines()), start=1) if r and any(c.strip() for c in r)]
    except csv.Error as exc:
        raise InputError(f"{path}: not a CSV file springdyn can read: {exc}") from None
    if not rows:
        raise InputError(f"{path}: the file is empty")
    header = [h.strip() for h in rows[0][1]]
    if any(not h for h in header):
        raise InputError(f"{path}: the header row has an empty column name (column {header.index('') + 1})")
    dup = [h for h in header if header.count(h) > 1]
    if dup:
        raise InputError(f"{path}: the header names column {dup[0]!r} twice")
    if len(rows) < 2:
        raise InputError(f"{path}: the file has a header but no data rows")
    data_cols: dict[str, list] = {h: [] for h in header}
    for lineno, row in rows[1:]:
        if len(row) != len(header):
            raise InputError(f"{path}: row {lineno} has {len(row)} cells, the header has {len(header)}")
        for h, cell in zip(header, row):
            try:
                value = float(cell)
            except ValueError:
                raise InputError(f"{path}: row {lineno}, column {h!r}: {cell.strip()!r} is not a number") from None
            if math.isfinite(value) and not PLAIN_NUMBER.fullmatch(cell.strip()):  # Python's "4_2e-5"
                raise InputError(
                    f"{path}: row {lineno}, column {h!r}: {cell.strip()!r} is not a plain number (like -4.2e-5; "
                    "no digit underscores)"
                )
            if not math.isfinite(value):
                raise InputError(f"{path}: row {lineno}, column {h!r}: {cell.strip()!r} is not a finite number")
            data_cols[h].append(value)
    return {h: np.asarray(v, dtype=float) for h, v in data_cols.items()}


def _toml_value(v) -> str:
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, (int, float)):
        if isinstance(v, float) and not math.isfinite(v):
            raise ValueError(f"{v!r} has no TOML form here")
        return repr(v)
    if isinstance(v, str):
        return json.dumps(v, ensure_ascii=False)  # a JSON string is a TOML basic string
    if isinstance(v, Mapping):
        return "{ " + ", ".join(f"{k} = {_toml_value(x)}" for k, x in v.items()) + " }"
    if isinstance(v, (list, tuple)):
        return "[" + ", ".join(_toml_value(x) for x in v) + "]"
    raise TypeError(f"{type(v).__name__} has no TOML form here")


def dumps_toml(doc: Mapping, header: str = "") -> str:
    """A TOML document of top-level tables of plain values (strings, numbers, booleans,
    arrays and inline tables), as springdyn's definitions are; ``header`` becomes comment lines.

    Parameters
    ----------
    doc : Mapping
        ``{table: {key: value}}``.
    header : str
        Text written as ``#`` comments first.
    """
    lines = [f"# {line}".rstrip() for line in header.splitlines()]
    for name, table in doc.items():
        lines += ["", f"[{name}]"] + [f"{k} = {_toml_value(v)}" for k, v in table.items()]
    return "\n".join(lines).lstrip("\n") + "\n"
