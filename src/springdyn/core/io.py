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
import tempfile
from pathlib import Path
from typing import Iterator, Mapping

import numpy as np

__all__ = ["atomic_path", "atomic_open", "write_csv", "write_json", "read_csv_columns", "to_jsonable"]


@contextlib.contextmanager
def atomic_path(path: str | os.PathLike, suffix: str | None = None) -> Iterator[Path]:
    """Yield a temporary path beside ``path``; rename it onto ``path`` on success.

    On an exception the temporary file is removed and ``path`` is left untouched.
    """
    path = Path(path)
    if path.parent and not path.parent.exists():
        path.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(prefix=f".{path.name}.", suffix=suffix or path.suffix, dir=path.parent or ".")
    os.close(fd)
    tmp = Path(tmp)
    try:
        yield tmp
        umask = os.umask(0)
        os.umask(umask)
        os.chmod(tmp, 0o666 & ~umask)  # mkstemp makes 0600 files; give the usual permissions
        os.replace(tmp, path)
    except BaseException:
        with contextlib.suppress(FileNotFoundError):
            tmp.unlink()
        raise


@contextlib.contextmanager
def atomic_open(path: str | os.PathLike, mode: str = "w", **kwargs):
    """Open a temporary file for writing; it replaces ``path`` when closed without error."""
    with atomic_path(path) as tmp:
        with open(tmp, mode, **kwargs) as fh:
            yield fh


def to_jsonable(obj):
    """Convert numpy scalars/arrays (and nested containers) to JSON-ready Python objects.

    Non-finite floats become ``None`` (JSON has no NaN).
    """
    if isinstance(obj, Mapping):
        return {str(k): to_jsonable(v) for k, v in obj.items()}
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
        return f if math.isfinite(f) else None
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
            w.writerow([_cell(a[i]) for a in arrays])
    return Path(path)


def _cell(v):
    if isinstance(v, (float, np.floating)):
        return repr(float(v))
    if isinstance(v, (np.bool_, bool)):
        return int(bool(v))
    return v


def read_csv_columns(path: str | os.PathLike) -> dict[str, np.ndarray]:
    """Read a numeric CSV with a header row into a dict of float arrays.

    Raises
    ------
    springdyn.errors.InputError
        Missing file, empty file, or a cell that is not a number (file, row and column named).
    """
    from .errors import InputError

    path = Path(path)
    if not path.is_file():
        raise InputError(f"{path}: no such file")
    with open(path, newline="", encoding="utf-8-sig") as fh:
        rows = [r for r in csv.reader(fh) if r and any(c.strip() for c in r)]
    if not rows:
        raise InputError(f"{path}: the file is empty")
    header = [h.strip() for h in rows[0]]
    data = {h: [] for h in header}
    for lineno, row in enumerate(rows[1:], start=2):
        if len(row) != len(header):
            raise InputError(f"{path}: row {lineno} has {len(row)} cells, the header has {len(header)}")
        for h, cell in zip(header, row):
            try:
                data[h].append(float(cell))
            except ValueError:
                raise InputError(f"{path}: row {lineno}, column {h!r}: {cell!r} is not a number") from None
    return {h: np.asarray(v, dtype=float) for h, v in data.items()}
