"""Helpers shared by the CLI of every model family: quantity options, ranges, output."""

from __future__ import annotations

import argparse
import contextlib
import json
import math
import re
import sys
from pathlib import Path

import numpy as np

from springdyn.core.errors import InputError
from springdyn.core.io import to_jsonable
from springdyn.core.results import notes_lines, text_table
from springdyn.core.units import to_si

__all__ = [
    "quantity",
    "parse_range",
    "print_json",
    "emit",
    "print_table",
    "add_output_options",
    "existing_file",
    "whole_number",
    "as_options",
    "close_figure",
]


def quantity(text, unit: str, option: str, *, bare_unit: str | None = None) -> float:
    """Parse a CLI option value with units into SI (``"22mm"`` -> 0.022)."""
    return to_si(text, unit, option, bare_unit=bare_unit)


#: Most values one range or list option may give.
MAX_RANGE_POINTS = 100_000


def parse_range(
    text: str, unit: str, option: str, *, bare_unit: str | None = None, max_points: int = MAX_RANGE_POINTS
) -> np.ndarray:
    """Parse a range or a list option into an SI array: the one syntax of every CLI option.

    - ``START:STOP:STEP``: START < STOP, STEP > 0; STOP is included when it falls on the
      grid; it must give at least two values and at most ``max_points``;
    - ``a,b,c``: a list (one value alone is a list of one).

    Each value may carry units (``36mm:40mm:0.5mm``, ``1000,2000 rpm`` is not a list
    with units: write ``1000rpm,2000rpm``).

    Examples
    --------
    >>> parse_range("300:400:50", "m", "--x").tolist()
    [300.0, 350.0, 400.0]
    >>> parse_range("1,2.5", "m", "--x").tolist()
    [1.0, 2.5]
    """
    text = str(text).strip()
    example = "START:STOP:STEP (e.g. 300:4000:25) or a list a,b,c"
    if not text:
        raise InputError(f"{option} is empty: give {example}")
    if ":" in text:
        parts = text.split(":")
        if len(parts) != 3 or not all(p.strip() for p in parts):
            raise InputError(f"{option} = {text!r} must be {example}")
        if any("," in p for p in parts):
            raise InputError(f"{option} = {text!r}: a range START:STOP:STEP and a list a,b,c cannot be mixed")
        start, stop, step = (to_si(p, unit, option, bare_unit=bare_unit) for p in parts)
        if not step > 0:
            raise InputError(f"{option} = {text!r}: the STEP must be positive")
        if not stop > start:
            raise InputError(
                f"{option} = {text!r} is empty: STOP is below START (a range counts upwards, "
                "START:STOP:STEP with START < STOP)"
            )
        count = (stop - start) / step
        if not np.isfinite(count) or count + 1 > max_points:
            raise InputError(f"{option} = {text!r} gives more than {max_points} values: use a larger STEP")
        n = int(np.floor(count + 1e-9)) + 1
        if n < 2:
            raise InputError(
                f"{option} = {text!r} gives only one value (STEP is larger than STOP - START): "
                "use a smaller STEP, or give the one value alone"
            )
        values = start + step * np.arange(n)
        if not np.all(np.isfinite(values)):
            raise InputError(f"{option} = {text!r} gives values that are not finite numbers")
        return values
    items = text.split(",")
    if any(not item.strip() for item in items):
        raise InputError(f"{option} = {text!r}: a list a,b,c has an empty item")
    if len(items) > max_points:
        raise InputError(f"{option} = {text!r} gives more than {max_points} values")
    return np.asarray([to_si(item, unit, option, bare_unit=bare_unit) for item in items], dtype=float)


def whole_number(text, option: str, low: int, high: int | None, allowed: str) -> int:
    """A whole-number option (``--samples``, ``--seed``, ``--workers``): ``1e6`` and ``64`` are
    read, anything else is refused naming the option, the value and ``allowed`` (e.g. "from 1
    to 10000000"), not with a unit parser's words.

    Parameters
    ----------
    text : str
        The value as given [-].
    option : str
        The option, for messages [-].
    low, high : int
        The range (``high`` None: no upper end) [-].
    allowed : str
        The range in words [-].
    """
    message = f"{option} = {str(text)!r} must be a whole number {allowed}"
    t = str(text).strip()
    try:
        value = int(t)  # exactly, however large
    except ValueError:
        try:
            number = float(t)  # 1e6
        except ValueError:
            raise InputError(message) from None
        if not math.isfinite(number) or number != int(number):
            raise InputError(message) from None
        value = int(number)
    if value < low or (high is not None and value > high):
        raise InputError(message)
    return value


def existing_file(path: str, option: str) -> Path:
    p = Path(path)
    if p.is_dir():
        raise InputError(f"{option}: {path}: is a folder, not a file")
    if not p.is_file():
        raise InputError(f"{option}: {path}: no such file")
    return p


def print_json(data) -> None:
    json.dump(to_jsonable(data), sys.stdout, indent=2)
    sys.stdout.write("\n")


def print_table(rows, headers=("quantity", "value", "unit")) -> None:
    """Print rows of strings as an aligned plain-text table (:func:`springdyn.core.results.text_table`)."""
    print(text_table(rows, headers))


def print_notes(summary, skip=()) -> None:
    """Every caveat of a result's summary (its ``notes``) in words, one ``note:`` line each
    (:func:`springdyn.core.results.notes_lines`).

    Parameters
    ----------
    summary : Mapping
        The result's summary (its ``notes`` list, if any, is printed).
    skip : tuple of str
        Notes already printed in another form (by their first words).
    """
    for line in notes_lines(summary, skip):
        print(line)


def add_output_options(p: argparse.ArgumentParser, *, csv=True, plot=True, json=True) -> None:
    if csv:
        p.add_argument("--csv", metavar="OUT.csv", help="write the table as CSV (SI, unit in column names)")
    if plot:
        p.add_argument("--plot", metavar="OUT.png", help="write the plot as PNG")
    if json:
        p.add_argument("--json", action="store_true", help="print machine-readable JSON (SI) instead of a table")


@contextlib.contextmanager
def as_options(**names):
    """Name CLI options in the library's errors: ``as_options(stop="--to")`` turns an
    :class:`InputError` starting ``stop = 5 mm ...`` into ``--to = 5 mm ...``.  A callable in
    place of the option rewrites such a message itself (it gets the message, returns the new
    one or ``None``): an engine speed names the ``--engine-rpm`` the user gave."""
    try:
        yield
    except InputError as exc:
        text = str(exc)
        for arg, option in names.items():
            if callable(option):
                new = option(text) if re.match(rf"^{re.escape(arg)}(\[\d+\])?( = |: )", text) else None
                new = text if new is None else new
            else:
                new = re.sub(rf"^{re.escape(arg)}(\[\d+\])?( = |: )", rf"{option}\1\2", text)
            if new != text:
                raise InputError(new) from None
        raise


def announce_written(paths, args) -> None:
    """Name every written file: on stdout, or on stderr when stdout carries JSON."""
    for path in paths:
        if path:
            print(f"wrote {path}", file=sys.stderr if getattr(args, "json", False) else sys.stdout)


def emit(result, args, json_data=None) -> bool:
    """The outputs every command offers for a result: ``--csv`` (:meth:`to_csv`), ``--plot``
    (:meth:`plot`) and ``--json`` (``json_data``, else the result's ``to_dict()`` or summary).

    Options a command does not have count as not given.  Returns True when JSON was printed
    (the command then prints nothing else).
    """
    written = []
    if getattr(args, "csv", None):
        written.append(result.to_csv(args.csv))
    if getattr(args, "plot", None):
        close_figure(result.plot(args.plot))
        written.append(args.plot)
    announce_written(written, args)
    if getattr(args, "json", False):
        if json_data is None:
            json_data = result.to_dict() if hasattr(result, "to_dict") else dict(result.summary)
        print_json(json_data)
        return True
    return False


def close_figure(fig) -> None:
    """Close a matplotlib figure (matplotlib is imported only when a command plots)."""
    from springdyn.core.plotting import plt

    plt.close(fig)
